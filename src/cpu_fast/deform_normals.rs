//! The fast fused deform with Jacobian normals (`shaders/deform_normals.wgsl`'s fast twin): Eq. 2
//! (+h) and each vertex's normal carried through the parameter Jacobian from its normal
//! coordinates record ([`crate::cpu::jacobian::coordinates`], made once from the rest normals),
//! vectorized across vertices and parallel over chunks of them, written straight into the
//! outputs. Its results are the f32 twin's ([`crate::cpu::deform::deform_with_normals`]) to
//! rounding (tests bound the worst vertex).

use glam::Vec4;

use crate::parallel::prelude::*;

use super::CHUNK;
use super::Isa;
use crate::coeffs::{BAND_FLAG, CellCoeffs, GpuBinding};
use crate::cpu::deform::deform_vertex_with_normal;

/// Overwrites the positions and normals (both tightly packed xyz, one triple per binding) of
/// the bound vertices outside falloff bands with their positions on the posed sweeps of `cells`
/// and their deformed unit normals (zero where the deformation degenerates) from their normal
/// coordinates `records`; leaves unbound and band vertices ([`BAND_FLAG`]) alone, as the fused
/// kernel does (their normals come from the faces). Runs on [`Isa::detect`], without
/// allocating.
///
/// # Panics
///
/// If `positions` or `normals` is not three floats per binding, `records` not one per binding,
/// or a binding names a cell past `cells`.
pub fn deform_with_normals(
    cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    records: &[Vec4],
    positions: &mut [f32],
    normals: &mut [f32],
) {
    deform_with_normals_with(Isa::detect(), cells, bindings, records, positions, normals);
}

/// [`deform_with_normals`] on `isa` (on [`Isa::Scalar`] if this CPU lacks it).
pub fn deform_with_normals_with(
    isa: Isa,
    cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    records: &[Vec4],
    positions: &mut [f32],
    normals: &mut [f32],
) {
    assert_eq!(positions.len(), 3 * bindings.len(), "three floats per binding");
    assert_eq!(normals.len(), 3 * bindings.len(), "three normal floats per binding");
    assert_eq!(records.len(), bindings.len(), "one normal coordinates record per binding");
    let isa = isa.or_scalar();
    let outputs = positions.par_chunks_mut(3 * CHUNK).zip(normals.par_chunks_mut(3 * CHUNK));
    outputs.zip(bindings.par_chunks(CHUNK).zip(records.par_chunks(CHUNK))).for_each(
        |((positions, normals), (bindings, records))| chunk(isa, cells, bindings, records, positions, normals),
    );
}

/// One task's vertices: whole batches in registers of `isa`, the rest one by one.
fn chunk(
    isa: Isa,
    cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    records: &[Vec4],
    positions: &mut [f32],
    normals: &mut [f32],
) {
    let batched = match isa {
        #[cfg(target_arch = "x86_64")]
        Isa::Avx2Fma => {
            let whole = bindings.len() - bindings.len() % super::deform_avx2::LANES;
            // SAFETY: `or_scalar` returned Avx2Fma, so this CPU has AVX2 and FMA.
            unsafe {
                super::deform_normals_avx2::deform_normals_batches(
                    cells,
                    &bindings[..whole],
                    &records[..whole],
                    &mut positions[..3 * whole],
                    &mut normals[..3 * whole],
                )
            };
            whole
        }
        _ => 0,
    };
    let outputs = positions[3 * batched..].chunks_exact_mut(3).zip(normals[3 * batched..].chunks_exact_mut(3));
    for ((xyz, n), (binding, &record)) in outputs.zip(bindings[batched..].iter().zip(&records[batched..])) {
        assert!(
            binding.cell >= BAND_FLAG || (binding.cell as usize) < cells.len(),
            "binding names cell {} of {}",
            binding.cell,
            cells.len()
        );
        if let Some((p, normal)) = deform_vertex_with_normal(cells, binding, record) {
            xyz.copy_from_slice(&p.to_array());
            n.copy_from_slice(&normal.to_array());
        }
    }
}
