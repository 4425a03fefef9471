//! The engine-shaped comparisons of the GPU bench, measured in the same rounds as the rest:
//! many small instances against one large mesh, and a rig owning a small share of a mesh against
//! one owning all of it.

use super::GpuTimer;
use super::passes::time;
use crate::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, GpuError, rest_positions};
use crate::rig::Rig;
use crate::sweep::Sweep;
use crate::synthetic::{BendTwistTaper, Tube, straight_sweep, tube_rig};

/// Instances of the `instances_over_single` comparison.
pub const INSTANCES: u32 = 1000;
/// Share of the vertices the partial rig of `partial_over_full` owns.
pub const PARTIAL_SHARE: f64 = 0.03;

/// The deformers of the two comparisons, posed once.
pub(super) struct EngineComparisons {
    instances: GpuDeformer,
    single: GpuDeformer,
    partial: GpuDeformer,
    full: GpuDeformer,
}

/// A deformer of `tube` bound to `rig` with `instances` instances (and normals), every instance
/// bent, twisted and tapered.
fn posed_deformer(context: &GpuContext, tube: &Tube, rig: &Rig, instances: u32) -> Result<GpuDeformer, GpuError> {
    let mesh = tube.mesh();
    let owners = rig.owners(&mesh, "tube")?;
    let positions = rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let source = BindingSource::Bind { owners: &owners, bands: &[] };
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, source).with_triangles(&triangles).with_instances(instances);
    let mut deformer = GpuDeformer::new(context, &descriptor)?;
    let posed: Vec<Sweep> = rig.pose(&BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 }.keys(rig))?;
    for i in 0..instances {
        deformer.set_pose(i, &posed)?;
    }
    Ok(deformer)
}

/// A rig of one sweep owning the middle `share` of `tube`'s rings (at least two).
fn partial_rig(tube: &Tube, share: f64) -> Rig {
    let rings = ((tube.rings as f64 * share).round() as u32).clamp(2, tube.rings);
    let first = (tube.rings - rings) / 2;
    let step = tube.length / (tube.rings - 1) as f64;
    let (z0, z1) = (first as f64 * step, (first + rings - 1) as f64 * step);
    let owned = (first * tube.around..(first + rings) * tube.around).collect();
    Rig::new(vec![straight_sweep(tube, owned, (z0, z1), 8, 16, 0.0)])
        .expect("a straight rig with distinct keys is valid")
}

impl EngineComparisons {
    /// The comparisons at `n` vertices: [`INSTANCES`] instances of a tube of about
    /// n / [`INSTANCES`] vertices against one tube of as many vertices in all; a tube of n
    /// vertices bound to a rig owning [`PARTIAL_SHARE`] of it against one owning all.
    pub(super) fn new(context: &GpuContext, n: usize) -> Result<EngineComparisons, GpuError> {
        let small = Tube::with_vertex_count((n / INSTANCES as usize).max(super::MIN_BENCH_VERTICES), 4.0, 0.5);
        let instances = posed_deformer(context, &small, &tube_rig(&small, 8, 16), INSTANCES)?;
        let total = small.vertex_count() * INSTANCES as usize;
        let large = Tube::with_vertex_count(total, 4.0, 0.5);
        let single = posed_deformer(context, &large, &tube_rig(&large, 8, 16), 1)?;
        let mesh = Tube::with_vertex_count(n, 4.0, 0.5);
        let partial = posed_deformer(context, &mesh, &partial_rig(&mesh, PARTIAL_SHARE), 1)?;
        let full = posed_deformer(context, &mesh, &tube_rig(&mesh, 8, 16), 1)?;
        Ok(EngineComparisons { instances, single, partial, full })
    }

    /// Seconds of the deform pass of every instance and of the single mesh.
    pub(super) fn time_instances(
        &mut self,
        context: &GpuContext,
        timer: Option<&GpuTimer>,
    ) -> Result<(f64, f64), GpuError> {
        let deform = |deformer: &mut GpuDeformer| {
            time(context, timer, |encoder, stamps| deformer.encode_deform_pass(encoder, stamps.pass()))
        };
        Ok((deform(&mut self.instances)?, deform(&mut self.single)?))
    }

    /// Seconds of the deform and normals passes of the partial and the full rig.
    pub(super) fn time_partial(
        &mut self,
        context: &GpuContext,
        timer: Option<&GpuTimer>,
    ) -> Result<(f64, f64), GpuError> {
        let frame = |deformer: &mut GpuDeformer| {
            time(context, timer, |encoder, stamps| {
                deformer.encode_deform_pass(encoder, stamps.opening());
                deformer.encode_normals_pass(encoder, stamps.closing());
            })
        };
        Ok((frame(&mut self.partial)?, frame(&mut self.full)?))
    }
}
