//! The orientation R(t) of a sweep's moving cross-section (§3): on [u_i, u_{i+1}],
//! `q(t) = normalize((1−s)·q_i + s·q̃_{i+1})` with `q̃_{i+1} = ±q_{i+1}` chosen so that
//! `q_i · q̃_{i+1} ≥ 0`, and `N(t) = R(t)·e_z`.

use glam::{DQuat, DVec3};

/// The two sign-aligned end quaternions of one knot interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrientationPiece {
    /// q_i, normalized.
    pub start: DQuat,
    /// q̃_{i+1}: q_{i+1} normalized, negated if needed so that `start · end ≥ 0`.
    pub end: DQuat,
}

impl OrientationPiece {
    /// Builds the piece from two normalized key rotations.
    pub fn new(start: DQuat, end: DQuat) -> OrientationPiece {
        let end = if start.dot(end) >= 0.0 { end } else { -end };
        OrientationPiece { start, end }
    }

    /// The interpolated quaternion before normalization, `(1−s)·q_i + s·q̃_{i+1}`. Its squared
    /// norm is at least ½ because the ends are unit and sign-aligned.
    pub fn unnormalized(&self, s: f64) -> DQuat {
        self.start * (1.0 - s) + self.end * s
    }

    /// R(t) as a unit quaternion at local parameter `s`.
    pub fn value(&self, s: f64) -> DQuat {
        self.unnormalized(s).normalize()
    }

    /// Coefficients `[n0, n1, n2]` of `n(s) = n0 + n1·s + n2·s²`, the third column of the
    /// rotation matrix of the unnormalized quaternion `q(s)` (that column times `|q(s)|²`), so
    /// that `N(t) = n(s) / |q(s)|²`. Binding uses it: ⟨v − C(t), N(t)⟩ has the sign of the
    /// quintic ⟨v − C(s), n(s)⟩.
    pub fn normal_numerator(&self) -> [DVec3; 3] {
        let delta = self.end - self.start;
        [
            normal_bilinear(self.start, self.start),
            2.0 * normal_bilinear(self.start, delta),
            normal_bilinear(delta, delta),
        ]
    }
}

/// The symmetric bilinear form B with `B(q, q) = |q|²·R(q/|q|)·e_z`, i.e. the third column
/// `(2(xz + wy), 2(yz − wx), w² − x² − y² + z²)` of the rotation matrix of a unit quaternion.
pub fn normal_bilinear(p: DQuat, q: DQuat) -> DVec3 {
    DVec3::new(
        p.x * q.z + p.z * q.x + p.w * q.y + p.y * q.w,
        p.y * q.z + p.z * q.y - p.w * q.x - p.x * q.w,
        p.w * q.w - p.x * q.x - p.y * q.y + p.z * q.z,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece() -> OrientationPiece {
        let a = DQuat::from_rotation_x(0.3) * DQuat::from_rotation_y(-0.7);
        let b = DQuat::from_rotation_z(2.1) * DQuat::from_rotation_x(1.2);
        OrientationPiece::new(a, -b)
    }

    #[test]
    fn ends_are_sign_aligned() {
        let p = piece();
        assert!(p.start.dot(p.end) >= 0.0);
    }

    #[test]
    fn normal_bilinear_of_a_unit_quaternion_is_its_z_axis() {
        let q = piece().start;
        assert!((normal_bilinear(q, q) - q * DVec3::Z).length() < 1e-15);
    }

    #[test]
    fn normal_numerator_matches_the_normalized_normal() {
        let p = piece();
        let [n0, n1, n2] = p.normal_numerator();
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            let q = p.unnormalized(s);
            let expected = p.value(s) * DVec3::Z;
            let numerator = n0 + n1 * s + n2 * s * s;
            assert!((numerator / q.length_squared() - expected).length() < 1e-14, "s = {s}");
        }
    }
}
