// The falloff blend: a vertex in a band follows its own sweep part of the way. Each influence
// moves the vertex by a frame: p = center + turn offset, with the turn from the rest frame to the
// posed frame and the offset in rest orientation. With weight w on the own influence:
// v = mix(c2, c1, w) + slerp(Q2, Q1, w) mix(o2, o1, w)   (README, "Falloff").
// Composed after sweep_eval.wgsl and angle.wgsl. Twin: src/cpu/blend.rs.

struct Influence {
    center: vec3<f32>,
    turn: vec4<f32>,
    offset: vec3<f32>,
}

// The quaternion product a b, (x, y, z, w).
fn quat_mul(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz));
}

fn quat_conjugate(q: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(-q.xyz, q.w);
}

// q^w for a unit quaternion q along the shorter arc, w in [0, 1]: with q = +-(u, cos beta),
// beta = angle_of(|cos beta|, |u|) in [0, pi / 2], q^w = (u sin(w beta) / |u|, cos(w beta)); sin and
// cos of w beta from those of w beta / 2 (at most pi / 4) by the polynomials of direction_at, so
// that no transcendental of driver-defined precision runs.
fn quat_power(q_in: vec4<f32>, w: f32) -> vec4<f32> {
    var q = q_in;
    if (q.w < 0.0) {
        q = -q;
    }
    let len = length(q.xyz);
    if (len == 0.0) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let beta = angle_of(q.w, len);
    let half = cos_sin_small(0.5 * w * beta);
    let sin_wb = 2.0 * half.x * half.y;
    let cos_wb = half.x * half.x - half.y * half.y;
    return vec4<f32>(q.xyz * (sin_wb / len), cos_wb);
}

// Where a vertex sits in a rest cell: the cell's unnormalized rest quaternion at s, the vertex's
// ray direction (cos, sin, 0) in the cell's middle frame, and the rest radius r(theta, t).
struct RestFrame {
    turn: vec4<f32>,
    direction: vec3<f32>,
    radius: f32,
}

fn rest_frame(rest: CellCoeffs, s: f32, phi: f32) -> RestFrame {
    return RestFrame(quat_at(rest, s), vec3<f32>(direction_at(rest, phi), 0.0), radius_at(rest, s, phi));
}

// A sweep's influence on a vertex at local (s, phi) of a cell (its rest frame `frame`), whose
// offset from the rest center C(s) is `offset`: the posed center, the unit turn R'(t) R(t)^-1 and
// the offset grown by the change of radius along the vertex's ray, so that the influence alone
// gives Eq. 2 (+h).
fn sweep_influence(posed: CellCoeffs, frame: RestFrame, s: f32, phi: f32, offset: vec3<f32>) -> Influence {
    let radial = rotate(frame.turn, frame.direction);
    let growth = radius_at(posed, s, phi) - frame.radius;
    let posed_turn = quat_at(posed, s);
    let scale = inverseSqrt(dot(posed_turn, posed_turn) * dot(frame.turn, frame.turn));
    let turn = quat_mul(posed_turn, quat_conjugate(frame.turn)) * scale;
    return Influence(curve_at(posed, s), turn, offset + growth * radial);
}

// The blended position with weight w on `own` and 1 - w on `second`: centers and offsets mixed
// linearly, turns by slerp along the shorter arc. `second_is_rest`: the second turn is the
// identity, and slerp(1, Q, w) = Q^w.
fn blend(second: Influence, own: Influence, w: f32, second_is_rest: bool) -> vec3<f32> {
    let center = second.center * (1.0 - w) + own.center * w;
    let offset = second.offset * (1.0 - w) + own.offset * w;
    var turn: vec4<f32>;
    if (second_is_rest) {
        turn = quat_power(own.turn, w);
    } else {
        turn = quat_mul(second.turn, quat_power(quat_mul(quat_conjugate(second.turn), own.turn), w));
    }
    return center + rotate(turn, offset);
}
