//! Creating a deformer, timed: the host's share (everything `GpuDeformer::new_async` does before
//! it returns: planning, uploads, recording and submitting the binding) and the whole, until
//! the GPU has bound the mesh.

use std::time::Instant;

use serde::Serialize;

use crate::gpu::{DeformerDescriptor, GpuContext, GpuDeformer, GpuError, wait};

/// The creation of the bench's deformers, milliseconds, each one sample (`null` on the CPU).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CreationReport {
    /// The scene's deformer (with triangles), until the GPU is done.
    pub ms: f64,
    /// Its host share: until `GpuDeformer::new_async` returns.
    pub host_ms: f64,
    /// The same deformer with Jacobian normals, until the GPU is done.
    pub jacobian_normals_ms: f64,
    /// Its host share.
    pub jacobian_normals_host_ms: f64,
}

/// A deformer of `descriptor`, with its creation's whole and host milliseconds.
pub(super) fn timed_deformer(
    context: &GpuContext,
    descriptor: &DeformerDescriptor,
) -> Result<(GpuDeformer, f64, f64), GpuError> {
    wait(context)?;
    let start = Instant::now();
    let deformer = pollster::block_on(GpuDeformer::new_async(context, descriptor))?;
    let host = start.elapsed().as_secs_f64() * 1e3;
    wait(context)?;
    Ok((deformer, start.elapsed().as_secs_f64() * 1e3, host))
}
