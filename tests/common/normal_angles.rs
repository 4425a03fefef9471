//! Angles between normals for the normals tests, in f64 (f32 acos cannot resolve angles below
//! 5e-4 rad): atan2(|a × b|, a · b), zero for two zero vectors, π for one zero vector or a NaN.

use glam::{DVec3, Vec3};

/// Vertex `i` of tightly packed f32 xyz `values`, in f64.
pub fn at(values: &[f32], i: usize) -> DVec3 {
    Vec3::from_slice(&values[3 * i..3 * i + 3]).as_dvec3()
}

/// The angle between `a` and `b`, radians: zero for two zero vectors, π for one (and for a NaN).
pub fn angle(a: DVec3, b: DVec3) -> f64 {
    let angle = match (a == DVec3::ZERO, b == DVec3::ZERO) {
        (true, true) => 0.0,
        (false, false) => a.cross(b).length().atan2(a.dot(b)),
        _ => std::f64::consts::PI,
    };
    if angle.is_nan() { std::f64::consts::PI } else { angle }
}

/// The largest angle between corresponding normals of `a` and `b` (tightly packed xyz), and its
/// vertex.
pub fn worst_angle(a: &[f32], b: &[f32]) -> (f64, usize) {
    (0..a.len() / 3).map(|i| (angle(at(a, i), at(b, i)), i)).fold((0.0, 0), |w, x| if x.0 > w.0 { x } else { w })
}
