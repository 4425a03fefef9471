//! The fast deform: Eq. 2 (+h) for every bound vertex, in f32, vectorized across vertices and
//! parallel over chunks of them, written straight into the output; then the falloff bands by
//! the band kernel's twin. Its results are the f32 twin's (`crate::cpu::deform`,
//! `crate::cpu::band`) to rounding: fused multiply-adds and Horner's rule in s round
//! differently (tests bound the worst vertex).

use crate::parallel::prelude::*;

use super::Isa;
use crate::coeffs::{BAND_FLAG, BandRecord, CellCoeffs, GpuBinding};
use crate::cpu::deform::deform_vertex;

pub use super::deform_normals::{deform_with_normals, deform_with_normals_with};

pub use super::CHUNK;

/// Overwrites the bound vertices of `positions` (tightly packed xyz, one triple per binding)
/// with their positions on the posed sweeps of `cells`; leaves unbound and band vertices
/// ([`crate::coeffs::BAND_FLAG`]) alone, as the deform kernel does. Runs on [`Isa::detect`].
///
/// # Panics
///
/// If `positions` is not three floats per binding, or a binding names a cell past `cells`.
pub fn deform(cells: &[CellCoeffs], bindings: &[GpuBinding], positions: &mut [f32]) {
    deform_with(Isa::detect(), cells, bindings, positions);
}

/// [`deform`] on `isa` (on [`Isa::Scalar`] if this CPU lacks it).
pub fn deform_with(isa: Isa, cells: &[CellCoeffs], bindings: &[GpuBinding], positions: &mut [f32]) {
    assert_eq!(positions.len(), 3 * bindings.len(), "three floats per binding");
    let isa = isa.or_scalar();
    positions
        .par_chunks_mut(3 * CHUNK)
        .zip(bindings.par_chunks(CHUNK))
        .for_each(|(positions, bindings)| deform_chunk(isa, cells, bindings, positions));
}

/// [`deform`], then the band vertices of `bands` by the band kernel's twin (`rest_cells`: the
/// rest rig's records): the whole of the GPU deformer's deform pass.
pub fn deform_with_bands(
    cells: &[CellCoeffs],
    rest_cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    bands: &[BandRecord],
    positions: &mut [f32],
) {
    deform(cells, bindings, positions);
    super::bands::deform_bands(cells, rest_cells, bindings, bands, positions);
}

/// One task's vertices: whole batches in registers of `isa`, the rest one by one.
fn deform_chunk(isa: Isa, cells: &[CellCoeffs], bindings: &[GpuBinding], positions: &mut [f32]) {
    let batched = match isa {
        #[cfg(target_arch = "x86_64")]
        Isa::Avx2Fma => {
            let whole = bindings.len() - bindings.len() % super::deform_avx2::LANES;
            // SAFETY: `or_scalar` returned Avx2Fma, so this CPU has AVX2 and FMA.
            unsafe { super::deform_avx2::deform_batches(cells, &bindings[..whole], &mut positions[..3 * whole]) };
            whole
        }
        _ => 0,
    };
    for (xyz, binding) in positions[3 * batched..].chunks_exact_mut(3).zip(&bindings[batched..]) {
        assert!(
            binding.cell >= BAND_FLAG || (binding.cell as usize) < cells.len(),
            "binding names cell {} of {}",
            binding.cell,
            cells.len()
        );
        if let Some(p) = deform_vertex(cells, binding) {
            xyz.copy_from_slice(&p.to_array());
        }
    }
}
