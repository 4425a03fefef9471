//! Natural cubic spline through values at non-uniform knots: the curve C(t) and the
//! t-direction of the radius function r(θ, t) (§3). "Natural" means zero second derivative at
//! both ends (C″(0) = C″(1) = 0).

use super::cubic::CubicPiece;

/// The tridiagonal system of the natural spline on fixed knots,
/// `h_{i−1}·M_{i−1} + 2(h_{i−1} + h_i)·M_i + h_i·M_{i+1} = 6·[(y_{i+1} − y_i)/h_i − (y_i − y_{i−1})/h_{i−1}]`
/// with `M_0 = M_n = 0`, factorized once (Thomas algorithm; the matrix is strictly diagonally
/// dominant, so no pivoting is needed) and solved for any number of value sets on the same
/// knots (a sweep solves it once per angular node). With two knots the spline is the straight
/// line and every `M_i` is 0.
#[derive(Clone, Debug, PartialEq)]
pub struct NaturalSplineSystem {
    /// h_i = u_{i+1} − u_i.
    widths: Vec<f64>,
    /// The forward-elimination multipliers h_{i−1}/d_{i−1} (index i, from 2).
    multipliers: Vec<f64>,
    /// 1/d_i, the reciprocals of the pivots after elimination (index i, 1..n−1).
    inverse_pivots: Vec<f64>,
}

impl NaturalSplineSystem {
    /// Factorizes the system of `knots` (at least two, strictly increasing; the caller
    /// guarantees it).
    pub fn new(knots: &[f64]) -> NaturalSplineSystem {
        let n = knots.len() - 1;
        let widths: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
        let mut multipliers = vec![0.0; n + 1];
        let mut inverse_pivots = vec![0.0; n + 1];
        for i in 1..n {
            let (h0, h1) = (widths[i - 1], widths[i]);
            let mut pivot = 2.0 * (h0 + h1);
            if i > 1 {
                multipliers[i] = h0 * inverse_pivots[i - 1];
                pivot -= multipliers[i] * h0;
            }
            inverse_pivots[i] = 1.0 / pivot;
        }
        NaturalSplineSystem { widths, multipliers, inverse_pivots }
    }

    /// The second derivatives at the knots of the spline through `values` into `m` (both of
    /// the knots' length).
    pub fn second_derivatives_into(&self, values: &[f64], m: &mut [f64]) {
        let n = self.widths.len();
        m.fill(0.0);
        if n < 2 {
            return;
        }
        // Forward sweep over the interior unknowns M_1 … M_{n−1}, the right-hand side kept in m.
        for i in 1..n {
            let (h0, h1) = (self.widths[i - 1], self.widths[i]);
            m[i] = 6.0 * ((values[i + 1] - values[i]) / h1 - (values[i] - values[i - 1]) / h0);
            if i > 1 {
                m[i] -= self.multipliers[i] * m[i - 1];
            }
        }
        // Back substitution.
        m[n - 1] *= self.inverse_pivots[n - 1];
        for i in (1..n - 1).rev() {
            m[i] = (m[i] - self.widths[i] * m[i + 1]) * self.inverse_pivots[i];
        }
    }

    /// Piece `i` (knot interval i) of the spline with knot values `values` and second
    /// derivatives `m`.
    pub fn piece(&self, values: &[f64], m: &[f64], i: usize) -> CubicPiece {
        CubicPiece { y0: values[i], y1: values[i + 1], m0: m[i], m1: m[i + 1], h: self.widths[i] }
    }
}

/// Second derivatives `M_i` at the knots of the natural cubic spline through
/// `(knots[i], values[i])`; see [`NaturalSplineSystem`]. The caller guarantees
/// `knots.len() == values.len() >= 2` and strictly increasing knots.
pub fn natural_second_derivatives(knots: &[f64], values: &[f64]) -> Vec<f64> {
    let mut m = vec![0.0; knots.len()];
    NaturalSplineSystem::new(knots).second_derivatives_into(values, &mut m);
    m
}

/// The cubic pieces of the natural spline through `(knots[i], values[i])`, one per knot interval.
pub fn natural_spline_pieces(knots: &[f64], values: &[f64]) -> Vec<CubicPiece> {
    let system = NaturalSplineSystem::new(knots);
    let mut m = vec![0.0; knots.len()];
    system.second_derivatives_into(values, &mut m);
    (0..knots.len() - 1).map(|i| system.piece(values, &m, i)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const KNOTS: [f64; 5] = [0.0, 0.1, 0.45, 0.5, 1.0];
    const VALUES: [f64; 5] = [2.0, -1.0, 0.5, 0.75, 3.0];

    #[test]
    fn two_knots_give_a_straight_line() {
        let pieces = natural_spline_pieces(&[0.0, 1.0], &[1.0, 3.0]);
        assert_eq!(pieces.len(), 1);
        assert_eq!(pieces[0].value(0.25), 1.5);
        assert_eq!(pieces[0].second_derivative(0.5), 0.0);
    }

    #[test]
    fn interpolates_and_is_natural_at_the_ends() {
        let pieces = natural_spline_pieces(&KNOTS, &VALUES);
        for (i, piece) in pieces.iter().enumerate() {
            assert_eq!(piece.value(0.0), VALUES[i]);
            assert_eq!(piece.value(1.0), VALUES[i + 1]);
        }
        assert_eq!(pieces[0].second_derivative(0.0), 0.0);
        assert_eq!(pieces[3].second_derivative(1.0), 0.0);
    }

    #[test]
    fn first_and_second_derivatives_are_continuous_at_interior_knots() {
        let pieces = natural_spline_pieces(&KNOTS, &VALUES);
        for pair in pieces.windows(2) {
            let (left, right) = (&pair[0], &pair[1]);
            assert!((left.derivative(1.0) - right.derivative(0.0)).abs() < 1e-12);
            assert!((left.second_derivative(1.0) - right.second_derivative(0.0)).abs() < 1e-12);
        }
    }

    #[test]
    fn reproduces_a_linear_function_exactly_enough() {
        let values: Vec<f64> = KNOTS.iter().map(|u| 3.0 * u - 1.0).collect();
        let m = natural_second_derivatives(&KNOTS, &values);
        assert!(m.iter().all(|mi| mi.abs() < 1e-12), "{m:?}");
    }
}
