//! Twin of `shaders/blend.wgsl`: the falloff blend in f32. Each influence moves a vertex by a
//! frame, p = center + turn·offset (turn: rest frame to posed frame; offset in rest orientation);
//! with weight w on the own influence, v = mix(c₂, c₁, w) + nlerp(Q₂, Q₁, w)·mix(o₂, o₁, w). The
//! f64 reference is [`crate::deform::blend`].

use glam::{Vec3, Vec4, Vec4Swizzles};

use super::sweep_eval::{curve_at, direction_at, quat_at, radius_at, rotate};
use crate::coeffs::CellCoeffs;

/// How one influence moves a vertex: p = center + turn·offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Influence {
    /// The posed center.
    pub center: Vec3,
    /// The unit turn from the rest to the posed frame, (x, y, z, w).
    pub turn: Vec4,
    /// The offset from the center, in rest orientation.
    pub offset: Vec3,
}

/// The quaternion product a·b, (x, y, z, w).
pub fn quat_mul(a: Vec4, b: Vec4) -> Vec4 {
    (a.w * b.xyz() + b.w * a.xyz() + a.xyz().cross(b.xyz())).extend(a.w * b.w - a.xyz().dot(b.xyz()))
}

/// The conjugate (the inverse of a unit quaternion).
pub fn quat_conjugate(q: Vec4) -> Vec4 {
    Vec4::new(-q.x, -q.y, -q.z, q.w)
}

/// The turn between unit quaternions a (w = 0) and b (w = 1) along the shorter arc, as their
/// normalized linear blend (as dual-quaternion skinning blends): smooth and monotonic in w, exact
/// at both ends; [`rotate`] normalizes it.
pub fn turn_blend(a: Vec4, b: Vec4, w: f32) -> Vec4 {
    let mut far = b;
    if a.dot(b) < 0.0 {
        far = -b;
    }
    a * (1.0 - w) + far * w
}

/// Where a vertex sits in a rest cell: the cell's unnormalized rest quaternion at s, the
/// vertex's ray direction (cos, sin, 0) in the cell's middle frame, and the rest radius r(θ, t).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RestFrame {
    /// The rest quaternion q0 + s·dq, unnormalized.
    pub turn: Vec4,
    /// (cos δ, sin δ, 0).
    pub direction: Vec3,
    /// r(θ, t) at rest.
    pub radius: f32,
}

/// The rest frame of a vertex at local (s, φ) of `rest`.
pub fn rest_frame(rest: &CellCoeffs, s: f32, phi: f32) -> RestFrame {
    RestFrame {
        turn: quat_at(rest, s),
        direction: direction_at(rest, phi).extend(0.0),
        radius: radius_at(rest, s, phi),
    }
}

/// A sweep's influence on a vertex at local (s, φ) of a cell (its rest frame `frame`) whose
/// offset from the rest center C(s) is `offset`: the posed center, the unit turn R′(t)·R(t)⁻¹ and
/// the offset grown by the change of radius along the vertex's ray, so that the influence alone
/// gives Eq. 2 (+h).
pub fn sweep_influence(posed: &CellCoeffs, frame: &RestFrame, s: f32, phi: f32, offset: Vec3) -> Influence {
    let radial = rotate(frame.turn, frame.direction);
    let growth = radius_at(posed, s, phi) - frame.radius;
    let posed_turn = quat_at(posed, s);
    let scale = 1.0 / (posed_turn.dot(posed_turn) * frame.turn.dot(frame.turn)).sqrt();
    let turn = quat_mul(posed_turn, quat_conjugate(frame.turn)) * scale;
    Influence { center: curve_at(posed, s), turn, offset: offset + growth * radial }
}

/// The blended position with weight w on `own` and 1 − w on `second`: centers and offsets mixed
/// linearly, turns by [`turn_blend`].
pub fn blend(second: &Influence, own: &Influence, w: f32) -> Vec3 {
    let center = second.center * (1.0 - w) + own.center * w;
    let offset = second.offset * (1.0 - w) + own.offset * w;
    center + rotate(turn_blend(second.turn, own.turn, w), offset)
}

#[cfg(test)]
mod tests {
    use glam::Quat;

    use super::*;

    #[test]
    fn turn_blend_turns_monotonically_along_the_shorter_arc() {
        let q = Quat::from_rotation_z(2.5);
        let mut previous = 0.0f32;
        for i in 0..=20 {
            let w = i as f32 / 20.0;
            let turn = Quat::from_vec4(turn_blend(Vec4::W, -Vec4::from(q), w).normalize());
            let angle = turn.angle_between(Quat::IDENTITY);
            assert!(angle >= previous - 1e-6, "w = {w}: {angle} after {previous}");
            previous = angle;
        }
        assert!((previous - 2.5).abs() < 1e-3);
    }

    #[test]
    fn blend_at_the_ends_is_each_influence() {
        let a = Influence {
            center: Vec3::new(1.0, 2.0, 3.0),
            turn: Vec4::from(Quat::from_rotation_x(0.7)),
            offset: Vec3::new(0.2, -0.1, 0.4),
        };
        let b = Influence {
            center: Vec3::new(-1.0, 0.5, 0.0),
            turn: Vec4::from(Quat::from_rotation_y(-1.1)),
            offset: Vec3::new(0.0, 0.3, -0.2),
        };
        let position = |i: &Influence| i.center + rotate(i.turn, i.offset);
        assert!((blend(&b, &a, 1.0) - position(&a)).length() < 1e-6);
        assert!((blend(&b, &a, 0.0) - position(&b)).length() < 1e-6);
    }
}
