//! The falloff blend on the f64 reference path: a vertex in a band follows its own sweep part of
//! the way, its frame blended with its second influence's. The f32 twin of the GPU kernel is
//! `crate::cpu::band`.
//!
//! Each influence i moves the vertex by a frame: a center c_i, a turn Q_i (the posed frame's
//! orientation times the rest frame's inverse) and an offset o_i from the center, in rest
//! orientation, so that its position is p_i = c_i + Q_i·o_i:
//!
//! ```text
//! own sweep A at (θ, t, d, h):   c = C'_A(t),  Q = R'_A(t)·R_A(t)⁻¹,  o = R_A(t)·((r'_A + d)·cos θ, (r'_A + d)·sin θ, h)
//! rest position:                 c = C_A(t),   Q = 1,                  o = R_A(t)·((r_A + d)·cos θ, (r_A + d)·sin θ, h)
//! neighbour B at (θ_B, t_B, …):  the same as A's, on sweep B
//! ```
//!
//! (primes: the posed sweep), so that p_A is Eq. 2 (+h) exactly, and the rest influence is the
//! vertex at rest. With weight w on the own sweep,
//!
//! ```text
//! v = (1 − w)·c_2 + w·c_1 + nlerp(Q_2, Q_1, w)·((1 − w)·o_2 + w·o_1)
//! nlerp(Q_2, Q_1, w) = normalize((1 − w)·Q_2 + w·(±Q_1)),  the sign making the two agree (shorter arc)
//! ```
//!
//! Against the rest position this is the rest and posed frames blended at w: center and radius
//! linearly, orientation by quaternion interpolation (the normalized linear blend that
//! dual-quaternion skinning uses: smooth and monotonic in w, exact at w = 0 and 1, off slerp's
//! constant angular speed by at most 0.1° for a 45° turn, 0.9° for 90° and 8.1° for a half
//! turn, with no transcendental function on the GPU); so a twisted band turns instead of
//! collapsing onto its axis (the "candy wrapper" of a linear blend of positions). A rigid motion of both
//! influences moves the vertex rigidly.

use glam::{DQuat, DVec3};

use crate::bind::{Binding, UNOWNED, VertexBinding};
use crate::sweep::Sweep;

/// How one influence moves a vertex: p = center + turn·offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Influence {
    /// The posed center c of the vertex's cross-section.
    pub center: DVec3,
    /// The turn Q from the rest to the posed frame.
    pub turn: DQuat,
    /// The vertex's offset o from the center, in the rest frame's orientation.
    pub offset: DVec3,
}

impl Influence {
    /// The vertex bound by `binding` to the sweep whose rest and posed surfaces are given.
    pub fn of_sweep(rest: &Sweep, posed: &Sweep, binding: &VertexBinding) -> Influence {
        let at = rest.locate(binding.t);
        let (rest_segment, posed_segment) = (&rest.segments()[at.segment], &posed.segments()[at.segment]);
        let rest_turn = rest_segment.orientation.value(at.s);
        let rho = posed.radius_field().value(at.segment, at.s, binding.theta) + binding.d;
        let (sin, cos) = binding.theta.sin_cos();
        Influence {
            center: posed_segment.curve.value(at.s),
            turn: posed_segment.orientation.value(at.s) * rest_turn.inverse(),
            offset: rest_turn * DVec3::new(rho * cos, rho * sin, binding.h),
        }
    }

    /// The rest position of the vertex bound by `binding` to `rest`, as an influence.
    pub fn of_rest(rest: &Sweep, binding: &VertexBinding) -> Influence {
        let identity = Influence::of_sweep(rest, rest, binding);
        Influence { turn: DQuat::IDENTITY, ..identity }
    }

    /// The position this influence alone gives.
    pub fn position(&self) -> DVec3 {
        self.center + self.turn * self.offset
    }
}

/// The position of a band vertex with weight `w` on its own influence `own` and 1 − w on
/// `second`: centers and offsets mixed linearly, turns by [`turn_blend`].
pub fn blend(second: &Influence, own: &Influence, w: f64) -> DVec3 {
    let center = second.center.lerp(own.center, w);
    let offset = second.offset.lerp(own.offset, w);
    center + turn_blend(second.turn, own.turn, w) * offset
}

/// The turn between `a` (w = 0) and `b` (w = 1) along the shorter arc: the normalized linear
/// blend of the unit quaternions, b negated when a·b < 0. Exact at both ends.
pub fn turn_blend(a: DQuat, b: DQuat, w: f64) -> DQuat {
    let far = if a.dot(b) < 0.0 { -b } else { b };
    let mixed = a * (1.0 - w) + far * w;
    mixed.normalize()
}

/// The deformed position of a band vertex bound by `own` (its sweep's binding) with weight `w`
/// and second influence `second` ([`Binding::UNOWNED`]: the rest position `rest_position`).
pub fn band_position(
    rest: &[Sweep],
    posed: &[Sweep],
    own: &Binding,
    w: f64,
    second: &Binding,
    rest_position: DVec3,
) -> DVec3 {
    if own.sweep == UNOWNED {
        return rest_position;
    }
    let sweep = own.sweep as usize;
    if second.sweep == UNOWNED && w == 0.0 {
        return rest_position;
    }
    let own_influence = Influence::of_sweep(&rest[sweep], &posed[sweep], &own.params);
    let second_influence = if second.sweep == UNOWNED {
        Influence::of_rest(&rest[sweep], &own.params)
    } else {
        let other = second.sweep as usize;
        Influence::of_sweep(&rest[other], &posed[other], &second.params)
    };
    blend(&second_influence, &own_influence, w)
}
