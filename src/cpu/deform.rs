//! Twin of `shaders/deform.wgsl`: Eq. 2, extended by h, for every bound vertex, in f32:
//! v = C(t) + R(t)·((r(θ,t) + d)·cos θ, (r(θ,t) + d)·sin θ, h).

use crate::parallel::prelude::*;
use glam::{Vec3, Vec4};

use super::jacobian::{NORMAL_BEYOND_END, deformed_normal, point_frame};
use super::sweep_eval::{curve_at, direction_at, quat_at, radius_at, rotate};
use crate::coeffs::{BAND_FLAG, CellCoeffs, GpuBinding};

/// One invocation of the kernel: the new position of a vertex, or `None` if it is unbound (and
/// keeps its rest position) or in a falloff band (and is moved by [`super::band`]).
pub fn deform_vertex(cells: &[CellCoeffs], binding: &GpuBinding) -> Option<Vec3> {
    // Unbound vertices keep their rest position; vertices in falloff bands (BAND_FLAG, which
    // UNOWNED also has) are moved by the band kernel.
    if binding.cell >= BAND_FLAG {
        return None;
    }
    let cell = &cells[binding.cell as usize];
    let rho = radius_at(cell, binding.s, binding.phi) + binding.d;
    let direction = direction_at(cell, binding.phi);
    let local = Vec3::new(rho * direction.x, rho * direction.y, binding.h);
    let p = curve_at(cell, binding.s) + rotate(quat_at(cell, binding.s), local);
    Some(p)
}

/// Every invocation of the kernel: overwrites the bound vertices of `positions` (tightly
/// packed xyz, one triple per binding), in parallel.
pub fn deform(cells: &[CellCoeffs], bindings: &[GpuBinding], positions: &mut [f32]) {
    const CHUNK: usize = 4096;
    positions.par_chunks_mut(3 * CHUNK).zip(bindings.par_chunks(CHUNK)).for_each(|(positions, bindings)| {
        for (xyz, binding) in positions.chunks_exact_mut(3).zip(bindings) {
            if let Some(p) = deform_vertex(cells, binding) {
                xyz.copy_from_slice(&p.to_array());
            }
        }
    });
}

/// One invocation of `shaders/deform_normals.wgsl`: the new position and Jacobian normal of a
/// vertex whose normal coordinates record is `record`, or `None` if it is unbound or in a
/// falloff band (whose normals the normals pass computes).
pub fn deform_vertex_with_normal(cells: &[CellCoeffs], binding: &GpuBinding, record: Vec4) -> Option<(Vec3, Vec3)> {
    if binding.cell >= BAND_FLAG {
        return None;
    }
    let cell = &cells[binding.cell as usize];
    let frame = point_frame(cell, binding, record.w == NORMAL_BEYOND_END);
    Some((frame.position, deformed_normal(cell, binding, &frame, record)))
}

/// Every invocation of `shaders/deform_normals.wgsl`: overwrites the positions and normals of
/// the bound vertices outside falloff bands (both tightly packed xyz), in parallel.
pub fn deform_with_normals(
    cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    records: &[Vec4],
    positions: &mut [f32],
    normals: &mut [f32],
) {
    const CHUNK: usize = 4096;
    let outputs = positions.par_chunks_mut(3 * CHUNK).zip(normals.par_chunks_mut(3 * CHUNK));
    outputs.zip(bindings.par_chunks(CHUNK).zip(records.par_chunks(CHUNK))).for_each(
        |((positions, normals), (bindings, records))| {
            let outputs = positions.chunks_exact_mut(3).zip(normals.chunks_exact_mut(3));
            for ((xyz, n), (binding, &record)) in outputs.zip(bindings.iter().zip(records)) {
                if let Some((p, normal)) = deform_vertex_with_normal(cells, binding, record) {
                    xyz.copy_from_slice(&p.to_array());
                    n.copy_from_slice(&normal.to_array());
                }
            }
        },
    );
}
