// Normals through the deformation: the partial derivatives of Eq. 2 (extended by h) in the
// cell's parameters (phi, s, d), or (phi, h, d) beyond an end of the sweep, and the cofactor
// product that carries a vertex's normal coordinates to its deformed normal (Nanson's formula,
// see src/deform/jacobian.rs). Composed after layout.wgsl, the cells and sweep_eval.wgsl.
// Twin: src/cpu/jacobian.rs.

// The modes of a normal coordinates record (its w): the Jacobian in (phi, s, d), in
// (phi, h, d) beyond an end, or the frame alone (a vertex on the axis, where phi has no
// meaning: xyz is then the rest normal in the rest cell's frame).
const NORMAL_JACOBIAN: f32 = 0.0;
const NORMAL_BEYOND_END: f32 = 1.0;
const NORMAL_FRAME: f32 = 2.0;
// Below this |det| relative to the product of the columns' lengths the rest frame is singular.
const SINGULAR_FRAME: f32 = 1e-4;

// A vertex's deformed position and the columns of its parameter Jacobian.
struct PointFrame {
    position: vec3<f32>,
    along_phi: vec3<f32>,
    along_axis: vec3<f32>,
    direction: vec3<f32>,
}

// Whether the binding lies beyond an end of its sweep: s at the sweep's first or last knot
// (curve[1].w: 1 on the first knot interval, + 2 on the last) and h != 0.
fn is_beyond_end(cell: CellCoeffs, binding: GpuBinding) -> bool {
    let ends = u32(cell.curve[1].w);
    let at_start = binding.s == 0.0 && (ends & 1u) != 0u;
    let at_end = binding.s == 1.0 && (ends & 2u) != 0u;
    return binding.h != 0.0 && (at_start || at_end);
}

// The position and the parameter Jacobian's columns d/dphi, d/ds (or d/dh beyond_end), d/dd:
// with c = R (cos, sin, 0), e = R e_z, rho = r + d and the angular velocity w of R,
// d/dphi = r_phi c + rho (2 pi / M) e x c, d/ds = C' + r_s c + w x (rho c + h e), d/dd = c.
fn point_frame(cell: CellCoeffs, binding: GpuBinding, beyond_end: bool) -> PointFrame {
    let s = binding.s;
    let phi = binding.phi;
    let r = cell.radius;
    let powers = vec4<f32>(1.0, s, s * s, s * s * s);
    let along_s = r[0] + phi * (r[1] + phi * (r[2] + phi * r[3]));
    let along_s_phi = r[1] + phi * (2.0 * r[2] + phi * 3.0 * r[3]);
    let rho = dot(along_s, powers) + binding.d;
    let r_s = dot(along_s, vec4<f32>(0.0, 1.0, 2.0 * s, 3.0 * s * s));
    let r_phi = dot(along_s_phi, powers);
    let cos_sin = direction_at(cell, phi);
    let q = quat_at(cell, s);
    let local = vec3<f32>(rho * cos_sin.x, rho * cos_sin.y, binding.h);
    let position = curve_at(cell, s) + rotate(q, local);
    let direction = rotate(q, vec3<f32>(cos_sin, 0.0));
    let normal = rotate(q, vec3<f32>(0.0, 0.0, 1.0));
    let along_phi = r_phi * direction + (2.0 * cell.curve[0].w * rho) * cross(normal, direction);
    var along_axis = normal;
    if (!beyond_end) {
        let c = cell.curve;
        let velocity = c[1].xyz + s * (2.0 * c[2].xyz + s * 3.0 * c[3].xyz);
        let dq = quat_derivative_at(cell, s);
        let spin = (2.0 / dot(q, q)) * (q.w * dq.xyz - dq.w * q.xyz - cross(dq.xyz, q.xyz));
        along_axis = velocity + r_s * direction + cross(spin, local_offset(direction, normal, rho, binding.h));
    }
    return PointFrame(position, along_phi, along_axis, direction);
}

// rho c + h e: the vertex's offset from C(s).
fn local_offset(direction: vec3<f32>, normal: vec3<f32>, rho: f32, h: f32) -> vec3<f32> {
    return rho * direction + h * normal;
}

// cof(A) m for the matrix A of the frame's columns a, b, c: m.x b x c + m.y c x a + m.z a x b.
fn cofactor_times(frame: PointFrame, m: vec3<f32>) -> vec3<f32> {
    let a = frame.along_phi;
    let b = frame.along_axis;
    let c = frame.direction;
    return m.x * cross(b, c) + m.y * cross(c, a) + m.z * cross(a, b);
}

// The normal coordinates record of rest normal n at the binding on its rest cell:
// m = sign(det) DP0^T n, normalized, with its mode (src/deform/jacobian.rs).
fn normal_coordinates(cell: CellCoeffs, binding: GpuBinding, n: vec3<f32>) -> vec4<f32> {
    let beyond_end = is_beyond_end(cell, binding);
    let frame = point_frame(cell, binding, beyond_end);
    let a = frame.along_phi;
    let b = frame.along_axis;
    let c = frame.direction;
    let det = dot(a, cross(b, c));
    if (abs(det) <= SINGULAR_FRAME * length(a) * length(b) * length(c)) {
        return vec4<f32>(rotate_inverse(quat_at(cell, binding.s), n), NORMAL_FRAME);
    }
    let m = sign(det) * vec3<f32>(dot(a, n), dot(b, n), dot(c, n));
    let mode = select(NORMAL_JACOBIAN, NORMAL_BEYOND_END, beyond_end);
    return vec4<f32>(normalize_or_zero(m), mode);
}

// The deformed unit normal (zero where the deformation degenerates) of a vertex whose frame on
// its posed cell is `frame`, from its normal coordinates record.
fn deformed_normal(cell: CellCoeffs, binding: GpuBinding, frame: PointFrame, coordinates: vec4<f32>) -> vec3<f32> {
    if (coordinates.w == NORMAL_FRAME) {
        return normalize_or_zero(rotate(quat_at(cell, binding.s), coordinates.xyz));
    }
    return normalize_or_zero(cofactor_times(frame, coordinates.xyz));
}

fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let length2 = dot(v, v);
    if (length2 > 0.0) {
        return v * inverseSqrt(length2);
    }
    return vec3<f32>(0.0);
}
