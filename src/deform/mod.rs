//! Deformation (Eq. 2, extended by h) on the f64 reference path: every bound vertex follows its
//! posed sweep. The f32 twin of the GPU kernel is [`crate::cpu::deform`].
//!
//! Data flow: rig → sweep → sweep coefficients → bind → **deform** → normals → output.
//!
//! ```text
//! v = C(t) + R(t)·((r(θ,t) + d)·cos θ, (r(θ,t) + d)·sin θ, h)
//! ```
//!
//! with C, R and r of the posed sweep and (θ, t, d, h) from binding against the rest sweep.

use glam::DVec3;
use rayon::prelude::*;

use crate::bind::{Binding, UNOWNED, VertexBinding};
use crate::sweep::Sweep;

/// The position of a vertex bound by `binding` on the (posed) `sweep`, Eq. 2.
pub fn deform_vertex(sweep: &Sweep, binding: &VertexBinding) -> DVec3 {
    sweep.point(binding.theta, binding.t, binding.d, binding.h)
}

/// Writes the deformed position of every vertex into `out`: bound vertices follow their posed
/// sweep (`posed[binding.sweep]`), unowned vertices keep their `rest` position. In parallel.
pub fn deform_vertices(posed: &[Sweep], bindings: &[Binding], rest: &[DVec3], out: &mut [DVec3]) {
    const CHUNK: usize = 4096;
    out.par_chunks_mut(CHUNK).zip(bindings.par_chunks(CHUNK).zip(rest.par_chunks(CHUNK))).for_each(
        |(out, (bindings, rest))| {
            for ((v, binding), &rest) in out.iter_mut().zip(bindings).zip(rest) {
                *v = if binding.sweep == UNOWNED {
                    rest
                } else {
                    deform_vertex(&posed[binding.sweep as usize], &binding.params)
                };
            }
        },
    );
}
