// The falloff blend: a vertex in a band follows its own sweep part of the way. Each influence
// moves the vertex by a frame: p = center + turn offset, with the turn from the rest frame to the
// posed frame and the offset in rest orientation. With weight w on the own influence:
// v = mix(c2, c1, w) + nlerp(Q2, Q1, w) mix(o2, o1, w)   (README, "Falloff").
// Composed after sweep_eval.wgsl. Twin: src/cpu/blend.rs.

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

// The turn between unit quaternions a (w = 0) and b (w = 1) along the shorter arc, as their
// normalized linear blend (as dual-quaternion skinning blends): smooth and monotonic in w, exact at
// both ends; rotate() normalizes it.
fn turn_blend(a: vec4<f32>, b: vec4<f32>, w: f32) -> vec4<f32> {
    var far = b;
    if (dot(a, b) < 0.0) {
        far = -b;
    }
    return a * (1.0 - w) + far * w;
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
// linearly, turns by turn_blend.
fn blend(second: Influence, own: Influence, w: f32) -> vec3<f32> {
    let center = second.center * (1.0 - w) + own.center * w;
    let offset = second.offset * (1.0 - w) + own.offset * w;
    return center + rotate(turn_blend(second.turn, own.turn, w), offset);
}
