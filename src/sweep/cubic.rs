//! One cubic piece of an interpolating spline, stored by its end values and end second
//! derivatives ("M form"), the representation shared by the natural spline in t and the
//! periodic spline in θ (§3).
//!
//! On a piece of width `h` with local parameter `s ∈ [0, 1]`:
//!
//! ```text
//! y(s) = (1−s)·y0 + s·y1 + h²/6 · [((1−s)³ − (1−s))·m0 + (s³ − s)·m1]
//! ```
//!
//! Both bracketed terms vanish exactly at `s = 0` and `s = 1`, so the piece reproduces its end
//! values bit for bit: `C(u_i) = p_i` holds exactly, not just to round-off.

/// A cubic piece between two interpolated values with the spline's second derivatives there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicPiece {
    /// Value at `s = 0`.
    pub y0: f64,
    /// Value at `s = 1`.
    pub y1: f64,
    /// Second derivative (with respect to the global parameter) at `s = 0`.
    pub m0: f64,
    /// Second derivative (with respect to the global parameter) at `s = 1`.
    pub m1: f64,
    /// Width of the piece in the global parameter.
    pub h: f64,
}

impl CubicPiece {
    /// Value at local parameter `s`; exact at `s = 0` and `s = 1`.
    pub fn value(&self, s: f64) -> f64 {
        let r = 1.0 - s;
        let k = self.h * self.h / 6.0;
        r * self.y0 + s * self.y1 + k * ((r * r * r - r) * self.m0 + (s * s * s - s) * self.m1)
    }

    /// First derivative with respect to the global parameter at local parameter `s`.
    pub fn derivative(&self, s: f64) -> f64 {
        let r = 1.0 - s;
        (self.y1 - self.y0) / self.h + self.h / 6.0 * ((1.0 - 3.0 * r * r) * self.m0 + (3.0 * s * s - 1.0) * self.m1)
    }

    /// Second derivative with respect to the global parameter at local parameter `s`.
    pub fn second_derivative(&self, s: f64) -> f64 {
        (1.0 - s) * self.m0 + s * self.m1
    }

    /// Power-basis coefficients `[a0, a1, a2, a3]` in the local parameter:
    /// `y(s) = a0 + a1·s + a2·s² + a3·s³`.
    pub fn power_coefficients(&self) -> [f64; 4] {
        let k = self.h * self.h / 6.0;
        [self.y0, (self.y1 - self.y0) - k * (2.0 * self.m0 + self.m1), 3.0 * k * self.m0, k * (self.m1 - self.m0)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PIECE: CubicPiece = CubicPiece { y0: 1.5, y1: -0.25, m0: 3.0, m1: -7.0, h: 0.4 };

    #[test]
    fn value_is_exact_at_both_ends() {
        assert_eq!(PIECE.value(0.0), PIECE.y0);
        assert_eq!(PIECE.value(1.0), PIECE.y1);
    }

    #[test]
    fn power_coefficients_agree_with_m_form() {
        let a = PIECE.power_coefficients();
        for i in 0..=20 {
            let s = i as f64 / 20.0;
            let power = a[0] + s * (a[1] + s * (a[2] + s * a[3]));
            assert!((power - PIECE.value(s)).abs() < 1e-14, "s = {s}");
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let eps = 1e-6;
        for i in 1..10 {
            let s = i as f64 / 10.0;
            let ds = eps / PIECE.h;
            let fd1 = (PIECE.value(s + ds) - PIECE.value(s - ds)) / (2.0 * eps);
            let fd2 = (PIECE.derivative(s + ds) - PIECE.derivative(s - ds)) / (2.0 * eps);
            assert!((fd1 - PIECE.derivative(s)).abs() < 1e-7, "C' at s = {s}");
            assert!((fd2 - PIECE.second_derivative(s)).abs() < 1e-6, "C'' at s = {s}");
        }
    }
}
