//! Twin of `shaders/band.wgsl`: each vertex in a falloff band follows its own sweep part of the
//! way, its frame blended with its second influence's ([`super::blend`]): the rest position, or a
//! neighbouring sweep's frame at the vertex.

use glam::{Vec2, Vec3, Vec4};

use super::blend::{Influence, blend, rest_frame, sweep_influence};
use super::sweep_eval::{curve_at, rotate};
use crate::coeffs::{BAND_FLAG, BandRecord, CellCoeffs, GpuBinding, UNOWNED};

/// (s, φ) of a band record's second influence, from two unorm16.
pub fn unpack_s_phi(packed: u32) -> Vec2 {
    Vec2::new((packed & 0xffff) as f32, (packed >> 16) as f32) * (1.0 / 65535.0)
}

/// One invocation of the kernel: the new position of the band record's vertex, or `None` when
/// it keeps its rest position (weight 0 against the rest position). `bindings` are the
/// dispatch's, indexed by `band.vertex`.
pub fn band_vertex(
    cells: &[CellCoeffs],
    rest_cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    band: &BandRecord,
) -> Option<Vec3> {
    if band.cell == UNOWNED && band.weight == 0.0 {
        return None;
    }
    let binding = &bindings[band.vertex as usize];
    let cell = (binding.cell & !BAND_FLAG) as usize;
    let rest = &rest_cells[cell];
    let frame = rest_frame(rest, binding.s, binding.phi);
    let local = (frame.radius + binding.d) * frame.direction + Vec3::new(0.0, 0.0, binding.h);
    let rest_center = curve_at(rest, binding.s);
    let rest_offset = rotate(frame.turn, local);
    let own = sweep_influence(&cells[cell], &frame, binding.s, binding.phi, rest_offset);
    let mut second = Influence { center: rest_center, turn: Vec4::new(0.0, 0.0, 0.0, 1.0), offset: rest_offset };
    if band.cell != UNOWNED {
        let at = unpack_s_phi(band.s_phi);
        let other = &rest_cells[band.cell as usize];
        let offset = rest_center + rest_offset - curve_at(other, at.x);
        second = sweep_influence(&cells[band.cell as usize], &rest_frame(other, at.x, at.y), at.x, at.y, offset);
    }
    Some(blend(&second, &own, band.weight))
}

/// Every invocation of the kernel over one dispatch: overwrites the band vertices of `positions`
/// (tightly packed xyz, indexed like `bindings`).
pub fn band(
    cells: &[CellCoeffs],
    rest_cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    bands: &[BandRecord],
    positions: &mut [f32],
) {
    for record in bands {
        if let Some(p) = band_vertex(cells, rest_cells, bindings, record) {
            let i = 3 * record.vertex as usize;
            positions[i..i + 3].copy_from_slice(&p.to_array());
        }
    }
}
