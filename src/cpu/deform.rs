//! Twin of `shaders/deform.wgsl`: Eq. 2, extended by h, for every bound vertex, in f32:
//! v = C(t) + R(t)·((r(θ,t) + d)·cos θ, (r(θ,t) + d)·sin θ, h).

use crate::parallel::prelude::*;
use glam::Vec3;

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
