//! Twin of `shaders/jacobian.wgsl`: the parameter Jacobian of Eq. 2 (extended by h) from a
//! cell's coefficients, and the normal coordinates that carry a vertex's rest normal to its
//! deformed one through it (the f64 reference: [`crate::deform::jacobian`]), in f32.

use glam::{Vec3, Vec4, Vec4Swizzles};

use super::sweep_eval::{curve_at, direction_at, quat_at, quat_derivative_at, rotate, rotate_inverse};
use crate::coeffs::{CellCoeffs, GpuBinding};

/// Mode of a normal coordinates record (its w): through the Jacobian in (φ, s, d).
pub const NORMAL_JACOBIAN: f32 = 0.0;
/// Mode: through the Jacobian in (φ, h, d), beyond an end of the sweep.
pub const NORMAL_BEYOND_END: f32 = 1.0;
/// Mode: through the frame alone (a vertex on the axis); xyz is the rest normal in the rest
/// cell's frame.
pub const NORMAL_FRAME: f32 = 2.0;
/// Below this |det| relative to the product of the columns' lengths the rest frame is singular.
pub const SINGULAR_FRAME: f32 = 1e-4;

/// A vertex's deformed position and the columns of its parameter Jacobian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointFrame {
    /// Eq. 2.
    pub position: Vec3,
    /// ∂/∂φ.
    pub along_phi: Vec3,
    /// ∂/∂s, or ∂/∂h beyond an end.
    pub along_axis: Vec3,
    /// ∂/∂d: the unit direction of the vertex's ray.
    pub direction: Vec3,
}

/// Whether `binding` lies beyond an end of its sweep: s at the sweep's first or last knot
/// ([`CellCoeffs::ends`]) and h ≠ 0.
pub fn is_beyond_end(cell: &CellCoeffs, binding: &GpuBinding) -> bool {
    let ends = cell.curve[1][3] as u32;
    let at_start = binding.s == 0.0 && (ends & 1) != 0;
    let at_end = binding.s == 1.0 && (ends & 2) != 0;
    binding.h != 0.0 && (at_start || at_end)
}

/// The position and the parameter Jacobian's columns at `binding` on `cell`.
pub fn point_frame(cell: &CellCoeffs, binding: &GpuBinding, beyond_end: bool) -> PointFrame {
    let (s, phi) = (binding.s, binding.phi);
    let r = cell.radius.map(Vec4::from_array);
    let powers = Vec4::new(1.0, s, s * s, s * s * s);
    let along_s = r[0] + phi * (r[1] + phi * (r[2] + phi * r[3]));
    let along_s_phi = r[1] + phi * (2.0 * r[2] + phi * 3.0 * r[3]);
    let rho = along_s.dot(powers) + binding.d;
    let r_s = along_s.dot(Vec4::new(0.0, 1.0, 2.0 * s, 3.0 * s * s));
    let r_phi = along_s_phi.dot(powers);
    let cos_sin = direction_at(cell, phi);
    let q = quat_at(cell, s);
    let local = Vec3::new(rho * cos_sin.x, rho * cos_sin.y, binding.h);
    let position = curve_at(cell, s) + rotate(q, local);
    let direction = rotate(q, cos_sin.extend(0.0));
    let normal = rotate(q, Vec3::Z);
    let along_phi = r_phi * direction + (2.0 * cell.curve[0][3] * rho) * normal.cross(direction);
    let mut along_axis = normal;
    if !beyond_end {
        let c = cell.curve.map(|c| Vec4::from_array(c).xyz());
        let velocity = c[1] + s * (2.0 * c[2] + s * 3.0 * c[3]);
        let dq = quat_derivative_at(cell, s);
        let spin = (2.0 / q.dot(q)) * (q.w * dq.xyz() - dq.w * q.xyz() - dq.xyz().cross(q.xyz()));
        along_axis = velocity + r_s * direction + spin.cross(rho * direction + binding.h * normal);
    }
    PointFrame { position, along_phi, along_axis, direction }
}

/// cof(A)·m for the matrix A of the frame's columns a, b, c: m₁ b×c + m₂ c×a + m₃ a×b.
pub fn cofactor_times(frame: &PointFrame, m: Vec3) -> Vec3 {
    let (a, b, c) = (frame.along_phi, frame.along_axis, frame.direction);
    m.x * b.cross(c) + m.y * c.cross(a) + m.z * a.cross(b)
}

/// The normal coordinates record of rest normal `n` at `binding` on its rest `cell`:
/// m = sign(det)·DP₀ᵀ·n normalized, with its mode in w.
pub fn normal_coordinates(cell: &CellCoeffs, binding: &GpuBinding, n: Vec3) -> Vec4 {
    let beyond_end = is_beyond_end(cell, binding);
    let frame = point_frame(cell, binding, beyond_end);
    let (a, b, c) = (frame.along_phi, frame.along_axis, frame.direction);
    let det = a.dot(b.cross(c));
    if det.abs() <= SINGULAR_FRAME * a.length() * b.length() * c.length() {
        return rotate_inverse(quat_at(cell, binding.s), n).extend(NORMAL_FRAME);
    }
    let m = det.signum() * Vec3::new(a.dot(n), b.dot(n), c.dot(n));
    let mode = if beyond_end { NORMAL_BEYOND_END } else { NORMAL_JACOBIAN };
    m.normalize_or_zero().extend(mode)
}

/// The deformed unit normal (zero where the deformation degenerates) of a vertex whose frame
/// on its posed `cell` is `frame`, from its normal coordinates record.
pub fn deformed_normal(cell: &CellCoeffs, binding: &GpuBinding, frame: &PointFrame, coordinates: Vec4) -> Vec3 {
    if coordinates.w == NORMAL_FRAME {
        return rotate(quat_at(cell, binding.s), coordinates.xyz()).normalize_or_zero();
    }
    cofactor_times(frame, coordinates.xyz()).normalize_or_zero()
}

/// Every invocation of `shaders/normal_coords.wgsl`: the normal coordinates record of each
/// vertex from the rest cells, its binding and its rest normal (tightly packed xyz); band
/// vertices included, unbound vertices zero.
pub fn coordinates(rest_cells: &[CellCoeffs], bindings: &[GpuBinding], rest_normals: &[f32]) -> Vec<Vec4> {
    bindings
        .iter()
        .enumerate()
        .map(|(i, binding)| {
            if binding.cell == crate::coeffs::UNOWNED {
                return Vec4::ZERO;
            }
            let n = Vec3::from_slice(&rest_normals[3 * i..3 * i + 3]);
            let own = GpuBinding { cell: binding.cell & !crate::coeffs::BAND_FLAG, ..*binding };
            normal_coordinates(&rest_cells[own.cell as usize], &own, n)
        })
        .collect()
}
