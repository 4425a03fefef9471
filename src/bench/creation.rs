//! Creating a deformer, timed: the host's share (everything `GpuDeformer::new_async` does before
//! it returns: planning, uploads, recording and submitting the binding) and the whole, until
//! the GPU has bound the mesh. The kernels are compiled before, by a small deformer of the same
//! kind ([`compile_kernels`]): the figures are those of every deformer after an application's
//! first.

use std::time::Instant;

use serde::Serialize;

use crate::coeffs::SweepCoefficients;
use crate::gpu::{
    BindingSource, CellRecords, DeformerDescriptor, GpuContext, GpuDeformer, GpuError, rest_positions, wait,
};
use crate::synthetic::{Tube, tube_rig};

/// The creation of the bench's deformers, milliseconds, each one sample, the kernels compiled
/// before (`null` on the CPU).
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

/// Compiles the kernels a deformer of `descriptor` (and one with Jacobian normals) runs, by
/// building a small tube's with the same cell records.
pub(super) fn compile_kernels(context: &GpuContext, descriptor: &DeformerDescriptor) -> Result<(), GpuError> {
    let cells = SweepCoefficients::new(descriptor.rest).cells.len() * descriptor.instances as usize;
    let records =
        CellRecords::from(CellRecords::Auto.variant(cells, &context.device.limits(), context.info.device_type));
    let tube = Tube::with_vertex_count(super::MIN_BENCH_VERTICES, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 4, 8));
    let owners = rig.owners(&mesh, "tube").expect("the tube rig owns the tube");
    let positions = rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let small = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::bind(&owners))
        .with_triangles(&triangles)
        .with_cell_records(records);
    GpuDeformer::new(context, &small)?;
    GpuDeformer::new(context, &small.with_jacobian_normals())?;
    Ok(())
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
