//! Periodic C² cubic spline through values at M uniform nodes: the θ-direction of the radius
//! function r(θ, t), with nodes θ_j = 2πj/M (§3).

use super::cubic::CubicPiece;

/// The cyclic system `M_{j−1} + 4·M_j + M_{j+1} = 6/h²·(y_{j+1} − 2·y_j + y_{j−1})` of the
/// periodic spline on M uniform nodes at spacing `h`, factorized once and solved for any
/// number of value sets on the same nodes (a sweep solves it 4× per knot interval).
///
/// A = T + u·vᵀ with u = (γ, 0, …, 0, 1), v = (1, 0, …, 0, 1/γ): T is tridiagonal (1, 4, 1)
/// with its first and last diagonal entries adjusted so that the corners are absorbed, solved
/// by the Thomas algorithm, and the Sherman–Morrison correction along z = T⁻¹u restores A.
#[derive(Clone, Debug, PartialEq)]
pub struct PeriodicSplineSystem {
    h: f64,
    /// 1/d_i, the reciprocals of T's pivots after forward elimination.
    inverse_pivots: Vec<f64>,
    /// T⁻¹u.
    z: Vec<f64>,
    /// 1/(1 + vᵀz).
    inverse_denominator: f64,
}

/// γ of the Sherman–Morrison split.
const GAMMA: f64 = -4.0;

impl PeriodicSplineSystem {
    /// Factorizes the system for `n >= 3` nodes at spacing `h`.
    pub fn new(n: usize, h: f64) -> PeriodicSplineSystem {
        let mut inverse_pivots = vec![0.0; n];
        let mut pivot = 4.0 - GAMMA;
        for (i, inverse) in inverse_pivots.iter_mut().enumerate() {
            if i > 0 {
                pivot = if i == n - 1 { 4.0 - 1.0 / GAMMA } else { 4.0 } - 1.0 / pivot;
            }
            *inverse = 1.0 / pivot;
        }
        let mut system = PeriodicSplineSystem { h, inverse_pivots, z: vec![0.0; n], inverse_denominator: 0.0 };
        let mut u = vec![0.0; n];
        u[0] = GAMMA;
        u[n - 1] = 1.0;
        let mut z = vec![0.0; n];
        system.solve_tridiagonal(&mut u, &mut z);
        system.inverse_denominator = 1.0 / (1.0 + z[0] + z[n - 1] / GAMMA);
        system.z = z;
        system
    }

    /// Solves T·x = y (y is overwritten by the forward elimination).
    fn solve_tridiagonal(&self, y: &mut [f64], x: &mut [f64]) {
        let n = y.len();
        for i in 1..n {
            y[i] -= self.inverse_pivots[i - 1] * y[i - 1];
        }
        x[n - 1] = y[n - 1] * self.inverse_pivots[n - 1];
        for i in (0..n - 1).rev() {
            x[i] = (y[i] - x[i + 1]) * self.inverse_pivots[i];
        }
    }

    /// The second derivatives at the nodes of the spline through `values` into `m`, using
    /// `scratch` (both of the system's length).
    pub fn second_derivatives_into(&self, values: &[f64], scratch: &mut [f64], m: &mut [f64]) {
        let n = values.len();
        let k = 6.0 / (self.h * self.h);
        for (j, rhs) in scratch.iter_mut().enumerate() {
            let prev = values[(j + n - 1) % n];
            let next = values[(j + 1) % n];
            *rhs = k * (next - 2.0 * values[j] + prev);
        }
        self.solve_tridiagonal(scratch, m);
        let factor = (m[0] + m[n - 1] / GAMMA) * self.inverse_denominator;
        for (mj, zj) in m.iter_mut().zip(&self.z) {
            *mj -= factor * zj;
        }
    }

    /// Piece `j` (from node `j` to node `(j + 1) mod M`) of the spline with node values
    /// `values` and second derivatives `m`.
    pub fn piece(&self, values: &[f64], m: &[f64], j: usize) -> CubicPiece {
        let n = values.len();
        CubicPiece { y0: values[j], y1: values[(j + 1) % n], m0: m[j], m1: m[(j + 1) % n], h: self.h }
    }
}

/// Second derivatives at the nodes of the periodic cubic spline through `values` at uniform
/// spacing `h` (the spline wraps from the last node back to the first). Needs
/// `values.len() >= 3`.
pub fn periodic_second_derivatives(values: &[f64], h: f64) -> Vec<f64> {
    let n = values.len();
    let (mut scratch, mut m) = (vec![0.0; n], vec![0.0; n]);
    PeriodicSplineSystem::new(n, h).second_derivatives_into(values, &mut scratch, &mut m);
    m
}

/// The M cubic pieces of the periodic spline through `values` at spacing `h`; piece `j` runs
/// from node `j` to node `(j + 1) mod M`.
pub fn periodic_spline_pieces(values: &[f64], h: f64) -> Vec<CubicPiece> {
    let n = values.len();
    let system = PeriodicSplineSystem::new(n, h);
    let (mut scratch, mut m) = (vec![0.0; n], vec![0.0; n]);
    system.second_derivatives_into(values, &mut scratch, &mut m);
    (0..n).map(|j| system.piece(values, &m, j)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn constant_values_give_a_constant_spline() {
        let m = periodic_second_derivatives(&[2.0; 5], TAU / 5.0);
        assert!(m.iter().all(|mi| mi.abs() < 1e-14), "{m:?}");
    }

    #[test]
    fn smallest_m_of_three_is_c2_across_every_node() {
        let values = [1.0, 0.5, 2.0];
        let pieces = periodic_spline_pieces(&values, TAU / 3.0);
        check_c2_periodic(&pieces);
    }

    #[test]
    fn wraps_c2_through_the_seam() {
        let values = [1.0, 1.3, 0.7, 0.9, 1.8, 1.1, 0.4, 1.0];
        let pieces = periodic_spline_pieces(&values, TAU / 8.0);
        for (j, piece) in pieces.iter().enumerate() {
            assert_eq!(piece.value(0.0), values[j]);
        }
        check_c2_periodic(&pieces);
    }

    #[test]
    fn sampled_cosine_is_reproduced_closely() {
        let n = 32;
        let h = TAU / n as f64;
        let values: Vec<f64> = (0..n).map(|j| (j as f64 * h).cos()).collect();
        let pieces = periodic_spline_pieces(&values, h);
        for (j, piece) in pieces.iter().enumerate() {
            let theta = (j as f64 + 0.5) * h;
            assert!((piece.value(0.5) - theta.cos()).abs() < 1e-5);
        }
    }

    #[test]
    fn one_factorization_solves_many_value_sets() {
        let system = PeriodicSplineSystem::new(6, TAU / 6.0);
        let (mut scratch, mut m) = ([0.0; 6], [0.0; 6]);
        for shift in 0..3 {
            let values: Vec<f64> = (0..6).map(|j| ((j + shift) as f64 * 0.9).sin() + 2.0).collect();
            system.second_derivatives_into(&values, &mut scratch, &mut m);
            let h2 = (TAU / 6.0).powi(2);
            for j in 0..6 {
                let lhs = m[(j + 5) % 6] + 4.0 * m[j] + m[(j + 1) % 6];
                let rhs = 6.0 / h2 * (values[(j + 1) % 6] - 2.0 * values[j] + values[(j + 5) % 6]);
                assert!((lhs - rhs).abs() < 1e-12, "row {j}: {lhs} vs {rhs}");
            }
        }
    }

    fn check_c2_periodic(pieces: &[CubicPiece]) {
        let n = pieces.len();
        for j in 0..n {
            let (left, right) = (&pieces[j], &pieces[(j + 1) % n]);
            assert!((left.value(1.0) - right.value(0.0)).abs() < 1e-14);
            assert!((left.derivative(1.0) - right.derivative(0.0)).abs() < 1e-12, "C¹ at node {j}");
            assert!((left.second_derivative(1.0) - right.second_derivative(0.0)).abs() < 1e-12);
        }
    }
}
