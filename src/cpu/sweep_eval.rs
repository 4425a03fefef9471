//! Twin of `shaders/sweep_eval.wgsl`: C(t), R(t), r(θ, t) and (cos θ, sin θ) from the
//! per-frame coefficients (§3, Eq. 2), in f32.

use glam::{Vec2, Vec3, Vec4, Vec4Swizzles};

use crate::coeffs::CellCoeffs;

/// C at local parameter s of the cell's knot interval.
pub fn curve_at(cell: &CellCoeffs, s: f32) -> Vec3 {
    let c = cell.curve.map(|c| Vec4::from_array(c).xyz());
    c[0] + s * (c[1] + s * (c[2] + s * c[3]))
}

/// R(t)·Rz(θ_mid) as the unnormalized quaternion a0 + a1·s + a2·s² + a3·s³; [`rotate`]
/// normalizes it.
pub fn quat_at(cell: &CellCoeffs, s: f32) -> Vec4 {
    let a = cell.rotation.map(Vec4::from_array);
    a[0] + s * (a[1] + s * (a[2] + s * a[3]))
}

/// The derivative in s of [`quat_at`].
pub fn quat_derivative_at(cell: &CellCoeffs, s: f32) -> Vec4 {
    let a = cell.rotation.map(Vec4::from_array);
    a[1] + s * (2.0 * a[2] + s * 3.0 * a[3])
}

/// v rotated by the unit quaternion q/|q|: v + w·t + u × t with q = (u, w) and
/// t = 2(u × v)/|q|², the usual formula for q/|q| with the normalization folded in.
pub fn rotate(q: Vec4, v: Vec3) -> Vec3 {
    let t = (2.0 / q.dot(q)) * q.xyz().cross(v);
    v + q.w * t + q.xyz().cross(t)
}

/// v rotated by the inverse of q/|q| (the transpose of R).
pub fn rotate_inverse(q: Vec4, v: Vec3) -> Vec3 {
    rotate(Vec4::new(-q.x, -q.y, -q.z, q.w), v)
}

/// r at local parameters (s, φ) of the cell: Horner in φ over the four powers of s at once
/// (`radius[q]` holds the coefficients of φ^q for s⁰..s³), then a dot product with the powers of s.
pub fn radius_at(cell: &CellCoeffs, s: f32, phi: f32) -> f32 {
    let c = cell.radius.map(Vec4::from_array);
    let along_s = c[0] + phi * (c[1] + phi * (c[2] + phi * c[3]));
    along_s.dot(Vec4::new(1.0, s, s * s, s * s * s))
}

/// (cos δ, sin δ) for the vertex's angle θ_mid + δ in its cell, δ = (2φ − 1)·π/M, |δ| ≤ π/3:
/// near-minimax polynomials (sin to δ⁷, cos to δ⁸, fitted on [−π/3, π/3]) accurate to 2e-8 before
/// f32 rounding, so no transcendental runs per vertex per frame.
pub fn direction_at(cell: &CellCoeffs, phi: f32) -> Vec2 {
    cos_sin_small((2.0 * phi - 1.0) * cell.curve[0][3])
}

/// (cos δ, sin δ) for |δ| ≤ π/3, by the polynomials of [`direction_at`].
#[expect(clippy::excessive_precision, reason = "the WGSL twin spells the same literals")]
pub fn cos_sin_small(delta: f32) -> Vec2 {
    let d2 = delta * delta;
    let sin_d = delta
        * (0.9999998635311992
            + d2 * (-0.16666500356755126 + d2 * (0.008327856912345286 + d2 * -0.0001917176645069119)));
    let cos_d = 0.9999999991674327
        + d2 * (-0.4999999619760431
            + d2 * (0.04166638875586918 + d2 * (-0.0013881774166947518 + d2 * 2.4056512057197938e-05)));
    Vec2::new(cos_d, sin_d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    #[test]
    fn direction_polynomial_matches_cos_and_sin_at_the_coarsest_step() {
        // M = 3 gives the widest cells, |δ| up to π/3.
        let mut cell = CellCoeffs::default();
        cell.curve[0][3] = PI / 3.0;
        for i in 0..=50 {
            let phi = i as f32 / 50.0;
            let delta = (2.0 * phi - 1.0) * PI / 3.0;
            let direction = direction_at(&cell, phi);
            assert!((direction - Vec2::new(delta.cos(), delta.sin())).length() < 3e-7, "δ = {delta}");
        }
    }

    #[test]
    fn rotate_inverse_undoes_rotate_for_an_unnormalized_quaternion() {
        let q = Vec4::new(0.3, -0.4, 0.2, 0.7);
        let v = Vec3::new(1.0, -2.0, 0.5);
        assert!((rotate_inverse(q, rotate(q, v)) - v).length() < 1e-6);
        let unit = glam::Quat::from_vec4(q.normalize());
        assert!((rotate(q, v) - unit * v).length() < 1e-6);
    }
}
