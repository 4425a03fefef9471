//! Twin of `shaders/blend.wgsl`: the falloff blend in f32. Each influence moves a vertex by a
//! frame, p = center + turn·offset (turn: rest frame to posed frame; offset in rest orientation);
//! with weight w on the own influence, v = mix(c₂, c₁, w) + slerp(Q₂, Q₁, w)·mix(o₂, o₁, w). The
//! f64 reference is [`crate::deform::blend`].

use glam::{Vec3, Vec4, Vec4Swizzles};

use super::angle::angle_of;
use super::sweep_eval::{cos_sin_small, curve_at, direction_at, quat_at, radius_at, rotate};
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

/// q^w for a unit quaternion q along the shorter arc, w ∈ [0, 1]: with q = ±(u, cos β),
/// β = angle_of(|cos β|, |u|) ∈ [0, π/2], q^w = (u·sin(wβ)/|u|, cos(wβ)); sin and cos of wβ from
/// those of wβ/2 (at most π/4) by the polynomials of [`direction_at`].
pub fn quat_power(q_in: Vec4, w: f32) -> Vec4 {
    let mut q = q_in;
    if q.w < 0.0 {
        q = -q;
    }
    let len = q.xyz().length();
    if len == 0.0 {
        return Vec4::new(0.0, 0.0, 0.0, 1.0);
    }
    let beta = angle_of(q.w, len);
    let half = cos_sin_small(0.5 * w * beta);
    let sin_wb = 2.0 * half.x * half.y;
    let cos_wb = half.x * half.x - half.y * half.y;
    (q.xyz() * (sin_wb / len)).extend(cos_wb)
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
/// linearly, turns by slerp along the shorter arc. `second_is_rest`: the second turn is the
/// identity, and slerp(1, Q, w) = Q^w.
pub fn blend(second: &Influence, own: &Influence, w: f32, second_is_rest: bool) -> Vec3 {
    let center = second.center * (1.0 - w) + own.center * w;
    let offset = second.offset * (1.0 - w) + own.offset * w;
    let turn = if second_is_rest {
        quat_power(own.turn, w)
    } else {
        quat_mul(second.turn, quat_power(quat_mul(quat_conjugate(second.turn), own.turn), w))
    };
    center + rotate(turn, offset)
}

#[cfg(test)]
mod tests {
    use glam::Quat;

    use super::*;

    #[test]
    fn quat_power_matches_slerp_from_identity_up_to_a_half_turn() {
        let axis = Vec3::new(0.3, -0.5, 0.8).normalize();
        let mut worst = 0.0f32;
        // Up to just below a half turn, where the shorter arc is unique; the angle between two
        // rotations is measured by how far they move unit vectors (acos loses precision).
        for i in 0..36 {
            let angle = i as f64 / 36.0 * std::f64::consts::PI;
            let q = glam::DQuat::from_axis_angle(axis.as_dvec3(), angle);
            for w in [0.0, 0.1, 0.25, 0.5, 0.77, 1.0] {
                let expected = glam::DQuat::IDENTITY.slerp(q, w);
                let power = Quat::from_vec4(quat_power(Vec4::from(q.as_quat()), w as f32)).as_dquat();
                for v in [glam::DVec3::X, glam::DVec3::Y, glam::DVec3::Z] {
                    worst = worst.max((power * v - expected * v).length() as f32);
                }
            }
        }
        assert!(worst < 1e-6, "worst {worst:e}");
    }

    #[test]
    fn quat_power_takes_the_shorter_arc_of_a_negated_quaternion() {
        let q = Quat::from_rotation_z(2.0);
        let half = quat_power(-Vec4::from(q), 0.5);
        assert!(Quat::from_vec4(half).angle_between(Quat::from_rotation_z(1.0)) < 1e-6);
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
        assert!((blend(&b, &a, 1.0, false) - position(&a)).length() < 1e-6);
        assert!((blend(&b, &a, 0.0, false) - position(&b)).length() < 1e-6);
        let rest = Influence { turn: Vec4::W, ..b };
        assert!((blend(&rest, &a, 0.0, true) - position(&rest)).length() < 1e-6);
        assert!((blend(&rest, &a, 0.5, true) - blend(&rest, &a, 0.5, false)).length() < 1e-6);
    }
}
