//! Twin of `shaders/sweep_eval.wgsl`: C(t), R(t), r(θ, t) and (cos θ, sin θ) from the
//! per-frame coefficients (§3, Eq. 2), in f32.

use glam::{Vec2, Vec3, Vec4, Vec4Swizzles};

use crate::coeffs::CellCoeffs;

/// C at local parameter s of the cell's knot interval.
pub fn curve_at(cell: &CellCoeffs, s: f32) -> Vec3 {
    let c = cell.curve.map(|c| Vec4::from_array(c).xyz());
    c[0] + s * (c[1] + s * (c[2] + s * c[3]))
}

/// R(t) as the unnormalized quaternion (1 − s)·q_k + s·q̃_{k+1}; [`rotate`] divides by its norm.
pub fn quat_at(cell: &CellCoeffs, s: f32) -> Vec4 {
    Vec4::from_array(cell.q0).lerp(Vec4::from_array(cell.q1), s)
}

/// v rotated by the unit quaternion q/|q|: ((w² − |u|²)·v + 2(u·v)·u + 2w·(u × v)) / |q|².
pub fn rotate(q: Vec4, v: Vec3) -> Vec3 {
    let u = q.xyz();
    let w = q.w;
    let scaled = (w * w - u.dot(u)) * v + 2.0 * u.dot(v) * u + 2.0 * w * u.cross(v);
    scaled / q.dot(q)
}

/// v rotated by the inverse of q/|q| (the transpose of R).
pub fn rotate_inverse(q: Vec4, v: Vec3) -> Vec3 {
    rotate(Vec4::new(-q.x, -q.y, -q.z, q.w), v)
}

/// r at local parameters (s, φ) of the cell.
pub fn radius_at(cell: &CellCoeffs, s: f32, phi: f32) -> f32 {
    let powers = Vec4::new(1.0, phi, phi * phi, phi * phi * phi);
    let r0 = Vec4::from_array(cell.radius[0]).dot(powers);
    let r1 = Vec4::from_array(cell.radius[1]).dot(powers);
    let r2 = Vec4::from_array(cell.radius[2]).dot(powers);
    let r3 = Vec4::from_array(cell.radius[3]).dot(powers);
    r0 + s * (r1 + s * (r2 + s * r3))
}

/// (cos θ, sin θ) for θ = θ_mid + δ, δ = (2φ − 1)·π/M, |δ| ≤ π/3: Taylor polynomials of sin (to
/// δ⁹) and cos (to δ¹⁰), both accurate to 5e-8, so no transcendental runs per vertex per frame.
pub fn direction_at(cell: &CellCoeffs, phi: f32) -> Vec2 {
    let cos_mid = cell.curve[0][3];
    let sin_mid = cell.curve[1][3];
    let delta = (2.0 * phi - 1.0) * cell.curve[2][3];
    let d2 = delta * delta;
    let sin_d = delta
        * (1.0 - d2 * (1.0 / 6.0) * (1.0 - d2 * (1.0 / 20.0) * (1.0 - d2 * (1.0 / 42.0) * (1.0 - d2 * (1.0 / 72.0)))));
    let cos_d = 1.0
        - d2 * 0.5
            * (1.0
                - d2 * (1.0 / 12.0)
                    * (1.0 - d2 * (1.0 / 30.0) * (1.0 - d2 * (1.0 / 56.0) * (1.0 - d2 * (1.0 / 90.0)))));
    Vec2::new(cos_mid * cos_d - sin_mid * sin_d, sin_mid * cos_d + cos_mid * sin_d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    #[test]
    fn direction_polynomial_matches_cos_and_sin_at_the_coarsest_step() {
        // M = 3 gives the widest cells, |δ| up to π/3.
        for j in 0..3 {
            let mid = (2 * j + 1) as f32 * PI / 3.0;
            let mut cell = CellCoeffs::default();
            (cell.curve[0][3], cell.curve[1][3], cell.curve[2][3]) = (mid.cos(), mid.sin(), PI / 3.0);
            for i in 0..=50 {
                let phi = i as f32 / 50.0;
                let theta = mid + (2.0 * phi - 1.0) * PI / 3.0;
                let direction = direction_at(&cell, phi);
                assert!((direction - Vec2::new(theta.cos(), theta.sin())).length() < 3e-7, "θ = {theta}");
            }
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
