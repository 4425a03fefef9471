//! Tangents of the deformed mesh (f64 reference): each rest tangent turned by the frame change
//! of its vertex's normal.
//!
//! Data flow: rig → sweep → sweep coefficients → bind → deform → **normals → tangents** →
//! output. The f32 twin of the GPU kernel is `crate::cpu::tangents`; this module is the
//! reference both are tested against.
//!
//! For a vertex with rest normal n₀, deformed normal n and rest tangent t₀ = (x, y, z, w) (as
//! glTF stores it, w = ±1 the bitangent's handedness), the deformed tangent is
//!
//! t = normalize(v − n (n · v)),  v = R(n₀ → n) t₀.xyz,  w copied,
//!
//! where R(n₀ → n) is the minimal rotation taking n₀ to n: about n₀ × n by the angle between
//! them (Rodrigues: R v = c v + k × v + k (k · v) / (1 + c), c = n₀ · n, k = n₀ × n). It turns
//! the tangent plane with the normal and adds no twist about n; a rotation of the surface about
//! its own normal is therefore not seen (the normals do not see it either).
//!
//! Degenerate cases, none of which yields NaN:
//! - n₀ ≈ −n (1 + c ≤ [`OPPOSITE`]): the minimal rotation is not unique; the half turn about
//!   [`any_perpendicular`]`(n₀)` is used.
//! - n₀ or n zero (a vertex whose triangles have no area): no rotation.
//! - v parallel to n, or zero (|v − n (n · v)|² ≤ [`PARALLEL`] |v|²): the tangent is
//!   [`any_perpendicular`]`(n)`, or zero if n is zero as well.
//! - n zero: v is only normalized (zero stays zero).

use crate::parallel::prelude::*;
use glam::{DQuat, DVec3, DVec4};

/// 1 + n₀ · n at or below which the normals count as opposite (angle within about 0.014 rad of
/// π) and the half turn replaces the minimal rotation, in both precisions.
pub const OPPOSITE: f64 = 1e-4;
/// Squared length of the projected tangent, relative to the tangent's, at or below which it is
/// parallel to the normal (an angle under 1e-6 rad) and replaced by [`any_perpendicular`].
pub const PARALLEL: f64 = 1e-12;

/// A unit vector perpendicular to `n`: n × e, normalized, for the coordinate axis e least
/// aligned with n (the first of x, y, z on ties); zero for a zero `n`.
pub fn any_perpendicular(n: DVec3) -> DVec3 {
    let a = n.abs();
    let e = if a.x <= a.y && a.x <= a.z {
        DVec3::X
    } else if a.y <= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    n.cross(e).normalize_or_zero()
}

/// The deformed tangent of one vertex: `rest_tangent`'s xyz turned by the minimal rotation
/// taking `rest_normal` to `normal` (unit or zero), made orthogonal to `normal` and normalized,
/// its w copied. See the module docs for the equation and the degenerate cases.
pub fn deformed_tangent(rest_normal: DVec3, normal: DVec3, rest_tangent: DVec4) -> DVec4 {
    let mut v = rest_tangent.truncate();
    if rest_normal != DVec3::ZERO && normal != DVec3::ZERO {
        let rotation = if 1.0 + rest_normal.dot(normal) > OPPOSITE {
            DQuat::from_rotation_arc(rest_normal, normal)
        } else {
            DQuat::from_axis_angle(any_perpendicular(rest_normal), std::f64::consts::PI)
        };
        v = rotation * v;
    }
    let u = v - normal * normal.dot(v);
    let length2 = u.length_squared();
    let t = if length2 > PARALLEL * v.length_squared() { u / length2.sqrt() } else { any_perpendicular(normal) };
    t.extend(rest_tangent.w)
}

/// [`deformed_tangent`] of every vertex (in parallel with the feature `parallel`); the three
/// slices are read up to the shortest.
pub fn deformed_tangents(rest_normals: &[DVec3], normals: &[DVec3], rest_tangents: &[DVec4]) -> Vec<DVec4> {
    let count = rest_normals.len().min(normals.len()).min(rest_tangents.len());
    (0..count).into_par_iter().map(|i| deformed_tangent(rest_normals[i], normals[i], rest_tangents[i])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_close(a: DVec4, b: DVec4, tolerance: f64) {
        assert!((a - b).abs().max_element() <= tolerance, "{a} vs {b}");
    }

    #[test]
    fn unchanged_normal_only_orthonormalizes() {
        let t = deformed_tangent(DVec3::Z, DVec3::Z, DVec4::new(2.0, 0.0, 1.0, -1.0));
        assert_close(t, DVec4::new(1.0, 0.0, 0.0, -1.0), 1e-15);
    }

    #[test]
    fn quarter_turn_of_the_normal_turns_the_tangent_with_it() {
        // n₀ = z to n = x: a quarter turn about y, which takes x to −z and leaves y alone.
        let t = deformed_tangent(DVec3::Z, DVec3::X, DVec4::new(1.0, 0.0, 0.0, 1.0));
        assert_close(t, DVec4::new(0.0, 0.0, -1.0, 1.0), 1e-15);
        let t = deformed_tangent(DVec3::Z, DVec3::X, DVec4::new(0.0, 1.0, 0.0, 1.0));
        assert_close(t, DVec4::new(0.0, 1.0, 0.0, 1.0), 1e-15);
    }

    #[test]
    fn rotating_rest_and_pose_together_rotates_the_tangent() {
        let q = DQuat::from_axis_angle(DVec3::new(1.0, -2.0, 0.5).normalize(), 1.1);
        let n0 = DVec3::new(0.3, 0.4, 0.866).normalize();
        let n = DVec3::new(-0.5, 0.2, 0.7).normalize();
        let t0 = (DVec3::new(1.0, 0.2, -0.1) - n0 * n0.dot(DVec3::new(1.0, 0.2, -0.1))).normalize().extend(1.0);
        let t = deformed_tangent(n0, n, t0);
        let turned = deformed_tangent(q * n0, q * n, (q * t0.truncate()).extend(1.0));
        assert_close(turned, (q * t.truncate()).extend(1.0), 1e-14);
    }

    #[test]
    fn opposite_normals_give_a_finite_unit_tangent_orthogonal_to_the_normal() {
        let n0 = DVec3::new(0.0, 0.6, 0.8);
        for n in [-n0, (-n0 + DVec3::new(1e-5, 0.0, 0.0)).normalize()] {
            let t = deformed_tangent(n0, n, DVec4::new(1.0, 0.0, 0.0, -1.0));
            assert!(t.is_finite(), "{t}");
            assert!((t.truncate().length() - 1.0).abs() < 1e-12, "{t}");
            assert!(t.truncate().dot(n).abs() < 1e-12, "{t}");
            assert_eq!(t.w, -1.0);
        }
    }

    #[test]
    fn zero_normals_and_parallel_tangents_stay_finite() {
        let t = DVec4::new(0.0, 3.0, 0.0, 1.0);
        assert_close(deformed_tangent(DVec3::ZERO, DVec3::Z, t), DVec4::new(0.0, 1.0, 0.0, 1.0), 1e-15);
        assert_close(deformed_tangent(DVec3::Z, DVec3::ZERO, t), DVec4::new(0.0, 1.0, 0.0, 1.0), 1e-15);
        let parallel = deformed_tangent(DVec3::Y, DVec3::Y, t);
        assert_close(parallel, any_perpendicular(DVec3::Y).extend(1.0), 0.0);
        assert_eq!(deformed_tangent(DVec3::ZERO, DVec3::ZERO, DVec4::new(0.0, 0.0, 0.0, 1.0)), DVec4::W);
    }

    #[test]
    fn any_perpendicular_is_unit_and_perpendicular() {
        for n in [DVec3::X, DVec3::new(0.3, -0.9, 0.1).normalize(), DVec3::new(1.0, 1.0, 1.0).normalize()] {
            let p = any_perpendicular(n);
            assert!((p.length() - 1.0).abs() < 1e-15 && p.dot(n).abs() < 1e-15, "{n}: {p}");
        }
        assert_eq!(any_perpendicular(DVec3::ZERO), DVec3::ZERO);
    }
}
