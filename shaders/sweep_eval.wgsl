// Evaluating a sweep at a vertex's (s, phi) from its cell's coefficients: C(t), R(t),
// r(theta, t) and (cos theta, sin theta) (paper section 3, Eq. 2).
// Twin: src/cpu/sweep_eval.rs.

// C at local parameter s of the cell's knot interval.
fn curve_at(cell: CellCoeffs, s: f32) -> vec3<f32> {
    let c = cell.curve;
    return c[0].xyz + s * (c[1].xyz + s * (c[2].xyz + s * c[3].xyz));
}

// R(t) Rz(theta_mid) as the unnormalized quaternion a0 + a1 s + a2 s^2 + a3 s^3; rotate()
// normalizes it.
fn quat_at(cell: CellCoeffs, s: f32) -> vec4<f32> {
    let a = cell.rotation;
    return a[0] + s * (a[1] + s * (a[2] + s * a[3]));
}

// The derivative in s of quat_at.
fn quat_derivative_at(cell: CellCoeffs, s: f32) -> vec4<f32> {
    let a = cell.rotation;
    return a[1] + s * (2.0 * a[2] + s * 3.0 * a[3]);
}

// v rotated by the unit quaternion q / |q|: v + w t + u x t with q = (u, w) and
// t = 2 (u x v) / |q|^2, which is the usual formula for q / |q| with the normalization folded in.
fn rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let t = (2.0 / dot(q, q)) * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// v rotated by the inverse of q / |q| (the transpose of R).
fn rotate_inverse(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    return rotate(vec4<f32>(-q.xyz, q.w), v);
}

// r at local parameters (s, phi) of the cell: Horner in phi over the four powers of s at once
// (radius[q] holds the coefficients of phi^q for s^0..s^3), then a dot product with the powers of s.
fn radius_at(cell: CellCoeffs, s: f32, phi: f32) -> f32 {
    let c = cell.radius;
    let along_s = c[0] + phi * (c[1] + phi * (c[2] + phi * c[3]));
    return dot(along_s, vec4<f32>(1.0, s, s * s, s * s * s));
}

// (cos delta, sin delta) for the vertex's angle theta_mid + delta in its cell, delta = (2 phi - 1) pi / M,
// |delta| <= pi / 3: near-minimax polynomials (sin to delta^7, cos to delta^8, fitted on [-pi/3, pi/3])
// accurate to 2e-8 before f32 rounding, so that no transcendental function runs per vertex per frame.
fn direction_at(cell: CellCoeffs, phi: f32) -> vec2<f32> {
    return cos_sin_small((2.0 * phi - 1.0) * cell.curve[0].w);
}

// (cos delta, sin delta) for |delta| <= pi / 3, by the polynomials of direction_at.
fn cos_sin_small(delta: f32) -> vec2<f32> {
    let d2 = delta * delta;
    let sin_d = delta * (0.9999998635311992 + d2 * (-0.16666500356755126 + d2 * (0.008327856912345286 + d2 * -0.0001917176645069119)));
    let cos_d = 0.9999999991674327 + d2 * (-0.4999999619760431 + d2 * (0.04166638875586918 + d2 * (-0.0013881774166947518 + d2 * 2.4056512057197938e-05)));
    return vec2<f32>(cos_d, sin_d);
}
