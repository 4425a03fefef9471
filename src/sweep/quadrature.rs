//! Gauss–Legendre quadrature on [0, 1], fixed and adaptive, for the volume integral (Eq. 1).

use std::sync::OnceLock;

/// An n-point Gauss–Legendre rule mapped to [0, 1]; exact for polynomials of degree 2n − 1.
#[derive(Clone, Debug)]
pub struct GaussLegendre {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// Computes the rule by Newton's method on the Legendre polynomial P_n.
    pub fn new(n: usize) -> GaussLegendre {
        let mut nodes = Vec::with_capacity(n);
        let mut weights = Vec::with_capacity(n);
        for i in 0..n {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut derivative = 1.0;
            for _ in 0..100 {
                let (p, dp) = legendre(n, x);
                derivative = dp;
                let dx = p / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            nodes.push(0.5 * (1.0 - x));
            weights.push(1.0 / ((1.0 - x * x) * derivative * derivative));
        }
        GaussLegendre { nodes, weights }
    }

    /// ∫_a^b f.
    pub fn integrate(&self, a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
        let width = b - a;
        let sum: f64 = self.nodes.iter().zip(&self.weights).map(|(x, w)| w * f(a + width * x)).sum();
        sum * width
    }
}

/// P_n(x) and P_n′(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    (p1, n as f64 * (x * p1 - p0) / (x * x - 1.0))
}

/// The 4-point rule, exact for polynomials of degree 7.
pub fn gauss_legendre_4() -> &'static GaussLegendre {
    static RULE: OnceLock<GaussLegendre> = OnceLock::new();
    RULE.get_or_init(|| GaussLegendre::new(4))
}

/// The 10-point rule used by [`integrate_adaptive`].
fn rule10() -> &'static GaussLegendre {
    static RULE: OnceLock<GaussLegendre> = OnceLock::new();
    RULE.get_or_init(|| GaussLegendre::new(10))
}

/// The deepest bisection of [`integrate_adaptive`]: at most 2⁸ = 256 leaf intervals, so at
/// most 5,130 evaluations of the integrand per call (10 for the scale, 10 for the whole, then
/// 20 per split), whatever the integrand does.
pub const MAX_DEPTH: u32 = 8;

/// ∫_a^b f to a relative accuracy of about `rel_tol`: a 10-point Gauss–Legendre estimate is
/// compared with the sum over both halves and the interval is split until they agree to
/// `rel_tol` times `scale` (a bound on the integral of |f|, such as the integral of the
/// magnitudes of the terms of f, so that an integral cancelling to near zero still terminates
/// once the halves agree to round-off), or [`MAX_DEPTH`] is reached.
pub fn integrate_adaptive(a: f64, b: f64, rel_tol: f64, scale: f64, f: &mut impl FnMut(f64) -> f64) -> f64 {
    let whole = rule10().integrate(a, b, &mut *f);
    refine(a, b, whole, rel_tol * scale.abs().max(f64::MIN_POSITIVE), f, 0)
}

/// The integral of |f| over [a, b] by the 10-point rule: a scale for [`integrate_adaptive`].
pub fn magnitude(a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
    rule10().integrate(a, b, |x| f(x).abs())
}

fn refine(a: f64, b: f64, whole: f64, tol: f64, f: &mut impl FnMut(f64) -> f64, depth: u32) -> f64 {
    let mid = 0.5 * (a + b);
    let left = rule10().integrate(a, mid, &mut *f);
    let right = rule10().integrate(mid, b, &mut *f);
    // A non-finite integrand (overflowing input) cannot converge: report it at once.
    if (left + right - whole).abs() <= tol || depth >= MAX_DEPTH || !(left + right).is_finite() {
        return left + right;
    }
    refine(a, mid, left, 0.5 * tol, f, depth + 1) + refine(mid, b, right, 0.5 * tol, f, depth + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_point_rule_matches_the_tabulated_nodes() {
        let rule = gauss_legendre_4();
        let expected = [0.930_568_155_797_026_3, 0.669_990_521_792_428_1];
        let mut nodes = rule.nodes.clone();
        nodes.sort_by(f64::total_cmp);
        assert!((nodes[3] - expected[0]).abs() < 1e-15);
        assert!((nodes[2] - expected[1]).abs() < 1e-15);
    }

    #[test]
    fn n_point_rule_is_exact_to_degree_2n_minus_1() {
        let rule = GaussLegendre::new(5);
        let integral = rule.integrate(0.0, 2.0, |x| x.powi(9));
        assert!((integral - 2f64.powi(10) / 10.0).abs() < 1e-12);
    }

    #[test]
    fn adaptive_integrates_a_peaked_rational_function() {
        // ∫₀¹ 1/(1e-4 + (x − 0.5)²) dx = 2·100·atan(50).
        let mut f = |x: f64| 1.0 / (1e-4 + (x - 0.5) * (x - 0.5));
        let exact = 200.0 * 50f64.atan();
        let scale = magnitude(0.0, 1.0, f);
        let integral = integrate_adaptive(0.0, 1.0, 1e-12, scale, &mut f);
        assert!(((integral - exact) / exact).abs() < 1e-11, "{integral} vs {exact}");
    }

    #[test]
    fn adaptive_stops_at_the_depth_cap_on_noise() {
        // An integrand of pure round-off noise never has agreeing halves; the cap bounds the work.
        let mut calls = 0usize;
        let mut noise = |x: f64| {
            calls += 1;
            (x * 1e17).sin() * 1e-300
        };
        let _ = integrate_adaptive(0.0, 1.0, 1e-12, 1e-310, &mut noise);
        assert!(calls <= 10 + 20 * ((1 << (MAX_DEPTH + 1)) - 1), "{calls} evaluations");
    }
}
