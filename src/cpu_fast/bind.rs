//! The fast bind: §3's binding of every owned vertex in f32 ([`crate::cpu::bind`]), its root
//! finding eight vertices to a register where the CPU has AVX2, parallel over chunks of vertices
//! and written straight into the caller's slice, with no allocation.

use std::f32::consts::TAU;

use glam::Vec3;

use crate::parallel::prelude::*;

use super::Isa;
use crate::coeffs::{GpuBinding, SweepInfo};
use crate::cpu::angle::angle_of;
use crate::cpu::bind::{BindInputs, bind_vertex};
use crate::cpu::position;
use crate::cpu::sweep_eval::{curve_at, quat_at, radius_at, rotate_inverse};

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

/// The end of the twin's [`bind_vertex`] for vertex `v` of sweep `sweep` once its nearest root
/// is known: `nearest` is the first cell of the root's knot interval and its local s, or `None`
/// when there is no root (beyond an end: the nearer of C(0) and C(1)); then θ, the cell and φ,
/// d = |v̂_xy| − r(θ, t) and h = v̂_z with v̂ = R(t)ᵀ·(v − C(t)). `band` is the owner's
/// [`crate::coeffs::BAND_FLAG`], kept in the cell.
pub(super) fn finish(
    inputs: &BindInputs,
    sweep: SweepInfo,
    nearest: Option<(u32, f32)>,
    v: Vec3,
    band: u32,
) -> GpuBinding {
    let (cell, s) = nearest.unwrap_or_else(|| {
        let last = sweep.first_cell + (sweep.segment_count - 1) * sweep.samples;
        let to_start = v - curve_at(&inputs.cells[sweep.first_cell as usize], 0.0);
        let to_end = v - curve_at(&inputs.cells[last as usize], 1.0);
        if to_end.dot(to_end) < to_start.dot(to_start) { (last, 1.0) } else { (sweep.first_cell, 0.0) }
    });
    let interval = &inputs.cells[cell as usize];
    let local = rotate_inverse(quat_at(interval, s), v - curve_at(interval, s));
    let mut theta = 0.0;
    if local.x != 0.0 || local.y != 0.0 {
        theta = interval.curve[0][3] + angle_of(local.x, local.y);
    }
    if theta < 0.0 {
        theta += TAU;
    }
    if theta >= TAU {
        theta -= TAU;
    }
    let x = theta * (sweep.samples as f32 / TAU);
    let j = (x as u32).min(sweep.samples - 1);
    let phi = (x - j as f32).clamp(0.0, 1.0);
    let r = radius_at(&inputs.cells[(cell + j) as usize], s, phi);
    GpuBinding { cell: (cell + j) | band, s, phi, d: local.truncate().length() - r, h: local.z }
}
