// Evaluating a sweep at a vertex's (s, phi) from its cell's coefficients: C(t), R(t),
// r(theta, t) and (cos theta, sin theta) (paper section 3, Eq. 2).
// Twin: src/cpu/sweep_eval.rs.

// C at local parameter s of the cell's knot interval.
fn curve_at(cell: CellCoeffs, s: f32) -> vec3<f32> {
    let c = cell.curve;
    return c[0].xyz + s * (c[1].xyz + s * (c[2].xyz + s * c[3].xyz));
}

// R(t) as the unnormalized quaternion (1 - s) q_k + s q~_{k+1}; rotate() divides by its norm.
fn quat_at(cell: CellCoeffs, s: f32) -> vec4<f32> {
    return mix(cell.q0, cell.q1, s);
}

// v rotated by the unit quaternion q / |q|:
// ((w^2 - |u|^2) v + 2 (u.v) u + 2 w (u x v)) / |q|^2.
fn rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let u = q.xyz;
    let w = q.w;
    let scaled = (w * w - dot(u, u)) * v + 2.0 * dot(u, v) * u + 2.0 * w * cross(u, v);
    return scaled / dot(q, q);
}

// v rotated by the inverse of q / |q| (the transpose of R).
fn rotate_inverse(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    return rotate(vec4<f32>(-q.xyz, q.w), v);
}

// r at local parameters (s, phi) of the cell.
fn radius_at(cell: CellCoeffs, s: f32, phi: f32) -> f32 {
    let powers = vec4<f32>(1.0, phi, phi * phi, phi * phi * phi);
    let r0 = dot(cell.radius[0], powers);
    let r1 = dot(cell.radius[1], powers);
    let r2 = dot(cell.radius[2], powers);
    let r3 = dot(cell.radius[3], powers);
    return r0 + s * (r1 + s * (r2 + s * r3));
}

// (cos theta, sin theta) for theta = theta_mid + delta, delta = (2 phi - 1) pi / M, |delta| <= pi / 3:
// Taylor polynomials of sin (to delta^9) and cos (to delta^10), both accurate to 5e-8, so that no
// transcendental function runs per vertex per frame.
fn direction_at(cell: CellCoeffs, phi: f32) -> vec2<f32> {
    let cos_mid = cell.curve[0].w;
    let sin_mid = cell.curve[1].w;
    let delta = (2.0 * phi - 1.0) * cell.curve[2].w;
    let d2 = delta * delta;
    let sin_d = delta * (1.0 - d2 * (1.0 / 6.0) * (1.0 - d2 * (1.0 / 20.0) * (1.0 - d2 * (1.0 / 42.0) * (1.0 - d2 * (1.0 / 72.0)))));
    let cos_d = 1.0 - d2 * 0.5 * (1.0 - d2 * (1.0 / 12.0) * (1.0 - d2 * (1.0 / 30.0) * (1.0 - d2 * (1.0 / 56.0) * (1.0 - d2 * (1.0 / 90.0)))));
    return vec2<f32>(cos_mid * cos_d - sin_mid * sin_d, sin_mid * cos_d + cos_mid * sin_d);
}
