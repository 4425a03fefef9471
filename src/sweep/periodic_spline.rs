//! Periodic C² cubic spline through values at M uniform nodes: the θ-direction of the radius
//! function r(θ, t), with nodes θ_j = 2πj/M (§3).

use super::cubic::CubicPiece;

/// Second derivatives at the nodes of the periodic cubic spline through `values` at uniform
/// spacing `h` (the spline wraps from the last node back to the first).
///
/// Solves the cyclic system `M_{j−1} + 4·M_j + M_{j+1} = 6/h²·(y_{j+1} − 2·y_j + y_{j−1})` by the
/// Sherman–Morrison correction of the Thomas algorithm. Needs `values.len() >= 3`.
pub fn periodic_second_derivatives(values: &[f64], h: f64) -> Vec<f64> {
    let n = values.len();
    let rhs: Vec<f64> = (0..n)
        .map(|j| {
            let prev = values[(j + n - 1) % n];
            let next = values[(j + 1) % n];
            6.0 / (h * h) * (next - 2.0 * values[j] + prev)
        })
        .collect();
    // A = T + u·vᵀ with u = (γ, 0, …, 0, 1), v = (1, 0, …, 0, 1/γ): T is tridiagonal (1, 4, 1)
    // with its first and last diagonal entries adjusted so that the corners are absorbed.
    let gamma = -4.0;
    let mut diag = vec![4.0; n];
    diag[0] -= gamma;
    diag[n - 1] -= 1.0 / gamma;
    let x = solve_unit_tridiagonal(&diag, &rhs);
    let mut u = vec![0.0; n];
    u[0] = gamma;
    u[n - 1] = 1.0;
    let z = solve_unit_tridiagonal(&diag, &u);
    let factor = (x[0] + x[n - 1] / gamma) / (1.0 + z[0] + z[n - 1] / gamma);
    x.iter().zip(&z).map(|(xi, zi)| xi - factor * zi).collect()
}

/// Solves a tridiagonal system whose off-diagonal entries are all 1.
fn solve_unit_tridiagonal(diag: &[f64], rhs: &[f64]) -> Vec<f64> {
    let n = diag.len();
    let mut d = diag.to_vec();
    let mut y = rhs.to_vec();
    for i in 1..n {
        let w = 1.0 / d[i - 1];
        d[i] -= w;
        y[i] -= w * y[i - 1];
    }
    let mut x = vec![0.0; n];
    x[n - 1] = y[n - 1] / d[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = (y[i] - x[i + 1]) / d[i];
    }
    x
}

/// The M cubic pieces of the periodic spline through `values` at spacing `h`; piece `j` runs
/// from node `j` to node `(j + 1) mod M`.
pub fn periodic_spline_pieces(values: &[f64], h: f64) -> Vec<CubicPiece> {
    let n = values.len();
    let m = periodic_second_derivatives(values, h);
    (0..n).map(|j| CubicPiece { y0: values[j], y1: values[(j + 1) % n], m0: m[j], m1: m[(j + 1) % n], h }).collect()
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
