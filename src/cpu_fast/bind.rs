//! The fast bind: §3's binding of every owned vertex in f32 (`crate::cpu::bind`), its root
//! finding eight vertices to a register where the CPU has AVX2, parallel over chunks of vertices
//! and written straight into the caller's slice, with no allocation.

use crate::parallel::prelude::*;

use super::Isa;
use crate::coeffs::GpuBinding;
use crate::cpu::bind::{BindInputs, bind_vertex};
use crate::cpu::position;

/// Vertices per parallel task.
pub const CHUNK: usize = 4 * 1024;

/// Writes the binding of each vertex of `positions` (tightly packed xyz) owned by `owners[i]`
/// ([`crate::coeffs::UNOWNED`]: unbound; [`crate::coeffs::BAND_FLAG`] kept in the cell) into
/// `out[i]`. Runs on [`Isa::detect`].
///
/// # Panics
///
/// If `positions` is not three floats per owner, `out` not one binding per owner, or an owner
/// names a sweep past `inputs.sweeps`.
pub fn bind(inputs: &BindInputs, owners: &[u32], positions: &[f32], out: &mut [GpuBinding]) {
    bind_with(Isa::detect(), inputs, owners, positions, out);
}

/// [`bind`] on `isa` (on [`Isa::Scalar`] if this CPU lacks it).
pub fn bind_with(isa: Isa, inputs: &BindInputs, owners: &[u32], positions: &[f32], out: &mut [GpuBinding]) {
    assert_eq!(positions.len(), 3 * owners.len(), "three floats per owner");
    assert_eq!(out.len(), owners.len(), "one binding per owner");
    let isa = isa.or_scalar();
    out.par_chunks_mut(CHUNK).enumerate().for_each(|(chunk, out)| {
        let first = chunk * CHUNK;
        let (owners, positions) = (&owners[first..first + out.len()], &positions[3 * first..3 * (first + out.len())]);
        match isa {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `or_scalar` returned Avx2Fma, so this CPU has AVX2 and FMA.
            Isa::Avx2Fma => unsafe { super::bind_avx2::bind_batches(inputs, owners, positions, out) },
            _ => {
                for (i, binding) in out.iter_mut().enumerate() {
                    *binding = bind_vertex(inputs, owners[i], position(positions, i));
                }
            }
        }
    });
}
