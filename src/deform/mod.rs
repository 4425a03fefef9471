//! Deformation (Eq. 2, extended by h) on the f64 reference path: every bound vertex follows its
//! posed sweep, and a vertex in a falloff band follows it part of the way ([`blend`]). The f32
//! twins of the GPU kernels are `crate::cpu::deform` and `crate::cpu::band`.
//!
//! Data flow: rig → sweep → sweep coefficients → bind → **deform** → normals → output.
//!
//! ```text
//! v = C(t) + R(t)·((r(θ,t) + d)·cos θ, (r(θ,t) + d)·sin θ, h)
//! ```
//!
//! with C, R and r of the posed sweep and (θ, t, d, h) from binding against the rest sweep.

pub mod blend;
pub mod jacobian;
mod probe;
mod reference;
#[cfg(test)]
mod tests;

use crate::parallel::prelude::*;
use glam::DVec3;

use crate::bind::{BandBinding, Binding, MeshBindings, UNOWNED, VertexBinding};

use crate::sweep::Sweep;
pub(crate) use probe::probe_sweep;
pub use probe::{PROBE, PROBE_TOLERANCE_DEG, jacobian_normal_vertices};

/// The position of a vertex bound by `binding` on the (posed) `sweep`, Eq. 2.
pub fn deform_vertex(sweep: &Sweep, binding: &VertexBinding) -> DVec3 {
    sweep.point(binding.theta, binding.t, binding.d, binding.h)
}

/// Writes the deformed position of every vertex into `out`: bound vertices follow their posed
/// sweep (`posed[binding.sweep]`), unowned vertices keep their `rest` position, and band
/// vertices blend their two influences ([`blend::band_position`]; `rest_sweeps` are the rig's
/// rest sweeps). In parallel, without allocating.
pub fn deform_vertices(
    rest_sweeps: &[Sweep],
    posed: &[Sweep],
    bindings: &MeshBindings,
    rest: &[DVec3],
    out: &mut [DVec3],
) {
    deform_chunks(rest_sweeps, posed, &bindings.vertices, &bindings.bands, rest, out);
}

/// [`deform_vertices`] for bindings without falloff bands ([`crate::bind::bind_vertices`]):
/// every bound vertex follows its posed sweep fully.
pub fn deform_hard(posed: &[Sweep], bindings: &[Binding], rest: &[DVec3], out: &mut [DVec3]) {
    deform_chunks(posed, posed, bindings, &[], rest, out);
}

fn deform_chunks(
    rest_sweeps: &[Sweep],
    posed: &[Sweep],
    vertices: &[Binding],
    bands: &[BandBinding],
    rest: &[DVec3],
    out: &mut [DVec3],
) {
    const CHUNK: usize = 4096;
    out.par_chunks_mut(CHUNK).enumerate().for_each(|(chunk, out)| {
        let first = chunk * CHUNK;
        let range = first..first + out.len();
        for ((v, binding), &rest) in out.iter_mut().zip(&vertices[range.clone()]).zip(&rest[range.clone()]) {
            *v = if binding.sweep == UNOWNED {
                rest
            } else {
                deform_vertex(&posed[binding.sweep as usize], &binding.params)
            };
        }
        let start = bands.partition_point(|band| (band.vertex as usize) < range.start);
        let end = bands.partition_point(|band| (band.vertex as usize) < range.end);
        for band in &bands[start..end] {
            let vertex = band.vertex as usize;
            out[vertex - first] =
                blend::band_position(rest_sweeps, posed, &vertices[vertex], band.weight, &band.second, rest[vertex]);
        }
    });
}
