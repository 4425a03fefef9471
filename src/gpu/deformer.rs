//! [`GpuDeformer`]: binding and Eq. 2 on the GPU, with the output position (and normal) buffer
//! ready to be drawn by the host application.

mod bounds;
mod cell_groups;
mod descriptor;
pub(crate) mod instances;
mod jacobian_probe;
mod normal_coords;
mod plan;
mod set_bands;
mod uploads;

pub use bounds::BOUNDS_STRIDE;
pub use cell_groups::DeformOrder;
pub use descriptor::{DeformerDescriptor, OutputBuffer};
pub use instances::INSTANCE_ALIGNMENT;

use std::ops::Range;
use std::sync::Arc;

use self::bounds::BoundsStage;
use self::cell_groups::CellGroups;
use self::instances::{InstanceDispatch, Numbering, PosedCells, PositionTargets};
use self::jacobian_probe::{JacobianProbe, ProbeInputs};
use self::normal_coords::NormalCoordinates;
use self::plan::DeformerPlan;
use self::set_bands::{BandMember, Rebanding};
use self::uploads::PoseUploads;
use super::InputError;
use super::bands::{BandPlan, BandSource, BandStage};
use super::binder::Binder;
use super::buffers::{
    BINDING_STRIDE, POSITION_STRIDE, binding_buffer_with, cells_buffer, empty_binding_buffer, upload_positions,
};
use super::chunks::ChunkLimits;
use super::kernels::{DeformVariant, Kernel};
use super::normals_pass::NormalsStage;
use super::readback::{read_bytes, wait};
use super::tangents_pass::{TANGENT_STRIDE, TangentStage};
use super::{GpuContext, GpuError};
use crate::bind::falloff::BandWeight;
use crate::coeffs::{
    BAND_FLAG, BandRecord, CELL_GROUP, CellCoeffs, GpuBinding, PackedBinding, SweepCoefficients, UNOWNED,
};
use crate::normals::NormalAdjacency;
use crate::sweep::Sweep;

/// Storage buffers the bind kernel uses in one stage, the most of any kernel.
const STORAGE_BUFFERS_NEEDED: u32 = 6;

/// How the deformer gets its bindings.
#[derive(Clone, Copy, Debug)]
pub enum BindingSource<'a> {
    /// Bind on the GPU: `owners[i]` is the index of the sweep owning vertex i, or
    /// [`UNOWNED`](crate::coeffs::UNOWNED); `bands` are the falloff weights
    /// ([`crate::bind::falloff::band_weights`], empty without falloff), sorted by vertex. Band
    /// vertices that fade into a neighbouring sweep are bound to it on the GPU too.
    Bind { owners: &'a [u32], bands: &'a [BandWeight] },
    /// Bindings computed before (by the CPU twin, read back from another deformer, or converted
    /// by [`SweepCoefficients::gpu_mesh_bindings`]), with the band records, vertices global and
    /// sorted. The deformer sets [`BAND_FLAG`] on the bindings of band vertices.
    Precomputed { bindings: &'a [GpuBinding], bands: &'a [BandRecord] },
}

impl<'a> BindingSource<'a> {
    /// Bind on the GPU without falloff: `owners[i]` is the sweep owning vertex i, or
    /// [`UNOWNED`](crate::coeffs::UNOWNED) ([`Rig::vertex_owners`](crate::Rig::vertex_owners)).
    pub fn bind(owners: &'a [u32]) -> BindingSource<'a> {
        BindingSource::Bind { owners, bands: &[] }
    }
}

/// Deforms one mesh on the GPU by poses of one rig (Eq. 2), as one or many instances.
///
/// Construction uploads the rest positions (once) and binds every owned vertex on the GPU; the
/// bindings stay on the GPU and are shared by every instance. Each frame,
/// [`set_pose`](GpuDeformer::set_pose) turns an instance's posed sweeps into a few KB of
/// coefficients on the host, and [`encode`](GpuDeformer::encode) uploads every instance's (one
/// copy recorded into the encoder, from a staging buffer) and records the deform (and normals)
/// dispatches into the application's command encoder, every instance in one deform dispatch: no allocation, pipeline or bind-group creation, no vertex
/// upload per frame. The [`positions`](GpuDeformer::positions) buffer (and
/// [`normals`](GpuDeformer::normals)) has `VERTEX | STORAGE` usage: draw it directly as a
/// `Float32x3` vertex attribute. Reading it back is a separate, explicit call. New falloff
/// widths need no new deformer: [`set_bands`](GpuDeformer::set_bands) replaces the bands.
///
/// Meshes whose buffers exceed the device's storage binding size or workgroup count are split
/// into chunks transparently; the position buffer is one buffer and must fit `max_buffer_size`.
///
/// `examples/embed.rs` is the frame loop, complete.
#[derive(Debug)]
pub struct GpuDeformer {
    context: GpuContext,
    limits: ChunkLimits,
    kernel: Arc<Kernel>,
    vertex_count: u32,
    targets: PositionTargets,
    cells: PosedCells,
    /// Every instance's cell records, instance i at i × the rig's cell count: the next encode
    /// uploads them.
    poses: Vec<CellCoeffs>,
    uploads: PoseUploads,
    coefficients: SweepCoefficients,
    variant: DeformVariant,
    /// The order the deform kernel runs in.
    order: DeformOrder,
    /// The rest rig's cell records, which binding and the band kernel read.
    rest_cells: wgpu::Buffer,
    chunks: Vec<DeformChunk>,
    bands: Option<BandStage>,
    rebanding: Rebanding,
    /// The normals stage of each position buffer (none without triangles).
    normals: Vec<NormalsStage>,
    /// The tangents stage of each position buffer (none without rest tangents).
    tangents: Vec<TangentStage>,
    bounds: Option<BoundsStage>,
    /// Bytes of the normal coordinates records (Jacobian normals; the buffers are held by the
    /// deform dispatches' bind groups).
    coordinates_bytes: u64,
    jacobian_normals: bool,
    /// With Jacobian normals, whether the deform kernel writes each vertex's normal.
    by_deform: Option<Vec<bool>>,
    /// The position buffer holding the latest positions.
    current: usize,
}

/// What the deform dispatches of a chunk run and write.
#[derive(Clone, Copy)]
struct ChunkDispatch<'a> {
    kernel: &'a Kernel,
    numbering: Numbering,
    cells: &'a PosedCells,
    targets: &'a PositionTargets,
    /// With Jacobian normals, the chunk's normal coordinates and the normals buffer of each
    /// position buffer, which the fused kernel writes too.
    normals: Option<(&'a wgpu::Buffer, &'a [NormalsStage])>,
    limits: &'a ChunkLimits,
}

/// A deform chunk's first vertex and its cell groups (`GpuDeformer::read_cell_groups`, feature
/// `internals`).
pub type ChunkGroups = (u32, Vec<u32>);

/// The deform dispatches of one chunk of vertices (one per instance group).
#[derive(Debug)]
struct DeformChunk {
    range: Range<u32>,
    bindings: wgpu::Buffer,
    dispatches: Vec<InstanceDispatch>,
    /// The cell groups the dispatches run over, if they do.
    groups: Option<CellGroups>,
}

impl DeformChunk {
    /// The deform dispatches of the vertices in `range`, whose bindings are in `bindings`, for
    /// every instance and position buffer of `dispatch`; over cell groups, `groups` holds the
    /// chunk's groups, one invocation each.
    fn new(
        device: &wgpu::Device,
        dispatch: &ChunkDispatch,
        range: Range<u32>,
        bindings: wgpu::Buffer,
        groups: Option<CellGroups>,
    ) -> DeformChunk {
        let ChunkDispatch { kernel, numbering, cells, targets, normals, limits } = *dispatch;
        let count = groups.as_ref().map_or(range.len() as u32, |groups| groups.count);
        let mut dispatches = InstanceDispatch::plan(
            device,
            cells,
            targets,
            &range,
            count,
            numbering,
            limits,
            |params, cells, parity, group, out| {
                let mut resources = vec![params.as_entire_binding(), cells, bindings.as_entire_binding(), out];
                if let Some((coordinates, stages)) = normals {
                    resources.push(coordinates.as_entire_binding());
                    resources.push(targets.window_of(&stages[parity].buffer, 0, &range, group));
                }
                if let Some(groups) = &groups {
                    resources.push(groups.buffer.as_entire_binding());
                }
                kernel.bind_group(device, "sweepffd deform", &resources)
            },
        );
        if let Some(groups) = &groups {
            for (k, dispatch) in dispatches.iter_mut().enumerate() {
                dispatch.indirect = Some((groups.args.clone(), CellGroups::args_offset(k)));
            }
        }
        DeformChunk { range, bindings, dispatches, groups }
    }

    /// Records the sort of the chunk's vertices into its cell groups, if it has them (after the
    /// passes that write its bindings).
    fn encode_sort(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some(groups) = &self.groups {
            groups.encode_sort(encoder, self.dispatches.iter().map(|dispatch| &dispatch.params));
        }
    }
}

impl GpuDeformer {
    /// Uploads the descriptor's rest positions and sweeps, and binds every vertex (on the GPU
    /// for [`BindingSource::Bind`]); with triangles, also keeps area-weighted vertex normals of
    /// the deformed mesh. Blocks until the GPU is done ([`new_async`](GpuDeformer::new_async)
    /// does not); input errors and wgpu errors are returned.
    pub fn new(context: &GpuContext, descriptor: &DeformerDescriptor) -> Result<GpuDeformer, GpuError> {
        let deformer = pollster::block_on(GpuDeformer::new_async(context, descriptor))?;
        wait(context)?;
        Ok(deformer)
    }

    /// [`new`](GpuDeformer::new) without blocking the host thread: records and submits the
    /// binding, then awaits only wgpu's error scopes, never the GPU. The deformer can be encoded
    /// at once; its first frame runs after the binding on the queue. With Jacobian normals it
    /// does wait for the GPU once: the probe that decides which vertices keep them runs on the
    /// GPU, and its verdicts are read back (one word a vertex).
    pub async fn new_async(context: &GpuContext, descriptor: &DeformerDescriptor<'_>) -> Result<GpuDeformer, GpuError> {
        let plan = DeformerPlan::new(descriptor, &context.device.limits(), context.info.device_type)?;
        let device = &context.device;
        let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd bind") });
        let (mut deformer, probe) = GpuDeformer::build(context, descriptor, plan, &mut encoder)?;
        context.queue.submit([encoder.finish()]);
        let probed = match probe {
            Some((probe, adjacency)) => deformer.apply_probe(probe, &adjacency),
            None => Ok(()),
        };
        // Both scopes are popped on this thread before either is awaited: wgpu's error scopes
        // belong to the thread that pushed them.
        let (validation, out_of_memory) = (validation.pop(), out_of_memory.pop());
        let (validation_error, memory_error) = (validation.await, out_of_memory.await);
        if let Some(error) = validation_error.or(memory_error) {
            return Err(error.into());
        }
        probed?;
        Ok(deformer)
    }

    /// Builds the stages `plan` calls for, recording their passes (binding, the rest normals,
    /// the normal coordinates, the Jacobian probe, the cell-group sorts, the bands) into
    /// `encoder`; with Jacobian normals, returns the probe to read once `encoder` is submitted,
    /// with the mesh's fans.
    fn build(
        context: &GpuContext,
        descriptor: &DeformerDescriptor,
        mut plan: DeformerPlan,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(GpuDeformer, Option<(JacobianProbe, NormalAdjacency)>), GpuError> {
        let device = &context.device;
        let rest_buffer = make_position_buffers(context, descriptor, &mut plan.targets);
        let (coefficients, variant) = (&plan.coefficients, plan.variant);
        let cells = PosedCells::new(device, &coefficients.cells, descriptor.instances, variant);
        let uploads = PoseUploads::new(device, cells.used_bytes, descriptor.pose_uploads);
        let rest_cells = cells_buffer(device, coefficients, variant);
        let kernel = plan.kernel.kernel(context.kernels(), device, variant);
        let binder = match descriptor.bindings {
            BindingSource::Bind { .. } => Some(Binder::new(context, descriptor.rest, coefficients, &rest_cells)),
            BindingSource::Precomputed { .. } => None,
        };
        let (normals, tangents) = surface_stages(context, descriptor, &plan, encoder)?;
        let inputs = ChunkInputs {
            context,
            descriptor,
            plan: &plan,
            kernel: &kernel,
            binder: binder.as_ref(),
            rest_buffer: &rest_buffer,
            rest_cells: &rest_cells,
            cells: &cells,
            normals: &normals,
        };
        let (chunks, coordinates): (Vec<DeformChunk>, Vec<Option<NormalCoordinates>>) =
            plan.ranges.iter().map(|range| inputs.build(range.clone(), encoder)).unzip();
        let coordinates_bytes = coordinates.iter().flatten().map(|c| c.buffer.size()).sum();
        let probe = match (plan.adjacency.take(), &plan.reach, &plan.influence) {
            (Some(adjacency), Some(reach), Some(influence)) => {
                let inputs = ProbeInputs {
                    rest: descriptor.rest,
                    coefficients: &plan.coefficients,
                    chunks: chunks
                        .iter()
                        .zip(&coordinates)
                        .filter_map(|(chunk, c)| c.as_ref().map(|c| (chunk.range.clone(), &chunk.bindings, &c.buffer)))
                        .collect(),
                    rest_positions: &rest_buffer,
                    rest_normals: &normals.first().expect("Jacobian normals need triangles").buffer,
                    vertex_count: plan.vertex_count,
                    limits: &plan.limits,
                };
                let probe = JacobianProbe::encode(context, encoder, &inputs, (&adjacency, reach, influence))?;
                Some((probe, adjacency))
            }
            _ => None,
        };
        let bands = band_stage(context, descriptor, &plan, (&cells, &rest_cells), (&chunks, binder.as_ref()), encoder);
        let members: Vec<BandMember> = match descriptor.bindings {
            BindingSource::Bind { bands, .. } => bands.iter().map(BandMember::of_weight).collect(),
            BindingSource::Precomputed { bands, .. } => bands.iter().map(BandMember::of_record).collect(),
        };
        let rebanding = Rebanding::new(descriptor.rest, binder, members, &plan.bound);
        // The chunks cover the plan's ranges, one each.
        let bounds = descriptor
            .bounds
            .then(|| BoundsStage::new(context, &plan.targets, &plan.ranges, descriptor.positions, &plan.limits));
        let poses = (0..descriptor.instances).flat_map(|_| plan.coefficients.cells.iter().copied()).collect();
        let deformer = GpuDeformer {
            context: context.clone(),
            limits: plan.limits,
            kernel,
            vertex_count: plan.vertex_count,
            targets: plan.targets,
            cells,
            poses,
            uploads,
            coefficients: plan.coefficients,
            variant: plan.variant,
            order: plan.kernel.order(),
            rest_cells,
            chunks,
            bands,
            rebanding,
            normals,
            tangents,
            bounds,
            coordinates_bytes,
            jacobian_normals: descriptor.jacobian_normals,
            by_deform: None,
            current: 0,
        };
        Ok((deformer, probe))
    }

    /// Reads the Jacobian probe's verdicts (once its passes are submitted) and makes the
    /// normals pass skip the vertices whose normals the deform kernel writes.
    fn apply_probe(&mut self, probe: JacobianProbe, adjacency: &NormalAdjacency) -> Result<(), GpuError> {
        let by_deform = probe.by_deform(&self.context)?;
        for stage in &mut self.normals {
            stage.restrict(&self.context.device, adjacency, &by_deform)?;
        }
        self.by_deform = Some(by_deform);
        Ok(())
    }

    internal_fn! {
        /// With Jacobian normals, whether the deform kernel writes each vertex's normal (as the
        /// probe on the GPU decided; [`crate::deform::jacobian_normal_vertices`] is its f64
        /// twin).
        fn jacobian_normal_vertices(&self) -> Option<&[bool]> {
            self.by_deform.as_deref()
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> u32 {
        self.vertex_count
    }

    /// The device limits a deformer needs, for an application to request on its own device:
    /// `Limits::downlevel_defaults()` with 6 storage buffers per shader stage (the bind
    /// kernel's). Meshes and instance counts larger than those limits' bindings are split into
    /// more dispatches; rigs and instances of up to 409 cells in all use the faster uniform
    /// cell records when `max_uniform_buffer_binding_size` reaches 64 KiB. Request the
    /// adapter's own limits for the largest meshes (the position buffer is one buffer).
    pub fn required_limits() -> wgpu::Limits {
        wgpu::Limits {
            max_storage_buffers_per_shader_stage: STORAGE_BUFFERS_NEEDED,
            ..wgpu::Limits::downlevel_defaults()
        }
    }

    /// Number of instances: poses of the one bound mesh deformed together.
    pub fn instance_count(&self) -> u32 {
        self.targets.instances
    }

    /// Byte offset of instance `instance`'s positions (and normals) in [`positions`]
    /// (and [`normals`]): `instance × stride × 12`, the stride being the vertex count for one
    /// instance and the vertex count rounded up to a multiple of
    /// [`INSTANCE_ALIGNMENT`](crate::gpu::INSTANCE_ALIGNMENT) (64) vertices for several, so
    /// that every instance starts on an aligned offset.
    ///
    /// [`positions`]: GpuDeformer::positions
    /// [`normals`]: GpuDeformer::normals
    pub fn instance_offset(&self, instance: u32) -> u64 {
        self.targets.instance_offset(instance)
    }

    /// The latest deformed positions (those of the last [`encode`](GpuDeformer::encode)),
    /// tightly packed f32 xyz (12 bytes a vertex), instance i at
    /// [`instance_offset(i)`](GpuDeformer::instance_offset); usage
    /// `VERTEX | STORAGE | COPY_SRC | COPY_DST`. Unbound vertices keep their rest position. With
    /// previous positions this is one of two buffers, alternating each encode.
    pub fn positions(&self) -> &wgpu::Buffer {
        &self.targets.buffers[self.current]
    }

    /// The positions of the encode before the last (the rest positions before two encodes),
    /// laid out as [`positions`](GpuDeformer::positions): the other buffer of the ping-pong,
    /// no copy made. `None` unless the descriptor asked for
    /// [`with_previous_positions`](DeformerDescriptor::with_previous_positions) (or
    /// [`with_outputs`](DeformerDescriptor::with_outputs): then one of the application's two
    /// buffers).
    pub fn previous_positions(&self) -> Option<&wgpu::Buffer> {
        let parities = self.targets.buffers.len();
        (parities == 2).then(|| &self.targets.buffers[1 - self.current])
    }

    /// The unit vertex normals of the deformed mesh (of the latest positions), tightly packed
    /// f32 xyz, laid out as the positions, if the deformer was given triangles; usage
    /// `VERTEX | STORAGE | COPY_SRC`.
    pub fn normals(&self) -> Option<&wgpu::Buffer> {
        self.normals.get(self.current).map(|n| &n.buffer)
    }

    internal_fn! {
        /// Number of vertices the deform dispatches cover (per instance): the ranges holding bound
        /// vertices, or every vertex with [`full_dispatch`](DeformerDescriptor::full_dispatch).
        fn dispatched_vertex_count(&self) -> u32 {
            self.chunks.iter().map(|chunk| chunk.range.len() as u32).sum()
        }
    }

    internal_fn! {
        /// Number of deform dispatches (1 unless the mesh exceeds a device limit or the bound
        /// vertices lie in several ranges; 0 if none is bound).
        fn chunk_count(&self) -> usize {
            self.chunks.iter().map(|chunk| chunk.dispatches.len()).sum()
        }
    }

    internal_fn! {
        /// Number of normals (and, with tangents, tangent) dispatches a frame records: over the
        /// vertices whose one-ring can move only.
        fn normals_dispatch_count(&self) -> usize {
            let tangents = self.tangents.get(self.current).map_or(0, TangentStage::dispatch_count);
            self.normals.get(self.current).map_or(0, |n| n.dispatches.len()) + tangents
        }
    }

    /// Where the kernels read the cell records from, as [`CellRecords`](crate::gpu::CellRecords)
    /// chose for this rig and adapter.
    pub fn cell_records(&self) -> DeformVariant {
        self.variant
    }

    /// Which vertices an invocation of the deform kernel deforms, as [`DeformOrder`] chose for
    /// this adapter and descriptor: [`DeformOrder::Vertices`], [`DeformOrder::StagedVertices`]
    /// or [`DeformOrder::CellGroups`].
    pub fn deform_order(&self) -> DeformOrder {
        self.order
    }

    /// Number of staging buffers the pose uploads have made so far: as many as encodes were
    /// in flight at once (see [`DeformerDescriptor::with_pose_uploads`]).
    pub fn pose_uploads(&self) -> usize {
        self.uploads.len()
    }

    /// Turns posed sweeps into the coefficients of instance `instance` (in place, no
    /// allocation, no GPU call): the next [`encode`](GpuDeformer::encode) uploads every
    /// instance's. Fails if the sweeps lack the rest rig's structure or the instance does not
    /// exist.
    pub fn set_pose(&mut self, instance: u32, posed: &[Sweep]) -> Result<(), GpuError> {
        if instance >= self.targets.instances {
            return Err(InputError::InstanceOutOfRange { instance, instances: self.targets.instances }.into());
        }
        self.coefficients.update(posed)?;
        let n = self.coefficients.cells.len();
        let at = instance as usize * n;
        self.poses[at..at + n].copy_from_slice(&self.coefficients.cells);
        Ok(())
    }

    /// Records the frame's work into `encoder`: the deform pass (every instance's poses
    /// uploaded by a copy recorded ahead of it, so that every encode deforms with the poses set
    /// before it, however many share a command buffer; deform and band kernels over
    /// every instance), then the normals pass if any. Afterwards
    /// [`positions`](GpuDeformer::positions) is the buffer this frame writes.
    pub fn encode(&mut self, encoder: &mut wgpu::CommandEncoder) {
        self.encode_deform_pass(encoder, None);
        self.encode_normals_pass(encoder, None);
        self.encode_bounds_pass(encoder);
    }

    /// Records the bounds pass alone (nothing without bounds) over the latest positions.
    pub fn encode_bounds_pass(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some(bounds) = &self.bounds {
            bounds.encode(encoder, self.current);
        }
    }

    /// Every instance's axis-aligned bounds of its latest positions, if the descriptor asked
    /// for them: [`BOUNDS_STRIDE`] (32) bytes an instance, f32 min.x, min.y, min.z, 0, max.x,
    /// max.y, max.z, 0, instance i at 32·i; usage `STORAGE | COPY_SRC | INDIRECT`. Written by
    /// each [`encode`](GpuDeformer::encode) (its last pass); exact (the min and max of the
    /// f32 positions, −0 counted below +0).
    pub fn bounds(&self) -> Option<&wgpu::Buffer> {
        self.bounds.as_ref().map(|b| &b.buffer)
    }

    /// Copies every instance's bounds back (blocking): `[min.xyz, 0, max.xyz, 0]` each.
    pub fn read_bounds(&self) -> Result<Option<Vec<[f32; 8]>>, GpuError> {
        let Some(bounds) = &self.bounds else { return Ok(None) };
        let bytes = read_bytes(&self.context, &bounds.buffer, 0, bounds.buffer.size())?;
        Ok(Some(bytemuck::pod_collect_to_vec(&bytes)))
    }

    internal_fn! {
        /// Records the deform pass alone (as [`encode`](GpuDeformer::encode) does: the upload of
        /// the poses, the deform kernel, then the band kernel for the vertices in falloff
        /// bands), optionally writing timestamps around it.
        fn encode_deform_pass(
            &mut self,
            encoder: &mut wgpu::CommandEncoder,
            timestamps: Option<wgpu::ComputePassTimestampWrites>,
        ) {
            let bytes = bytemuck::cast_slice(&self.poses);
            self.uploads.encode(&self.context.device, &self.context.queue, encoder, bytes, &self.cells.buffer);
            let parity = (self.current + 1) % self.targets.buffers.len();
            self.current = parity;
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("sweepffd deform"),
                timestamp_writes: timestamps,
            });
            pass.set_pipeline(&self.kernel.pipeline);
            for chunk in &self.chunks {
                for dispatch in &chunk.dispatches {
                    dispatch.encode(&mut pass, parity);
                }
            }
            if let Some(bands) = &self.bands {
                bands.encode(&mut pass, parity);
            }
        }
    }

    internal_fn! {
        /// Records the normals pass alone (nothing without triangles) over the latest positions,
        /// optionally with timestamps.
        fn encode_normals_pass(
            &self,
            encoder: &mut wgpu::CommandEncoder,
            timestamps: Option<wgpu::ComputePassTimestampWrites>,
        ) {
            let Some(normals) = self.normals.get(self.current) else { return };
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("sweepffd normals"),
                timestamp_writes: timestamps,
            });
            pass.set_pipeline(&normals.kernel.pipeline);
            for (group, grid) in &normals.dispatches {
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(grid.0, grid.1, 1);
            }
            if let Some(tangents) = self.tangents.get(self.current) {
                tangents.encode(&mut pass);
            }
        }
    }

    /// Convenience for tools: sets the pose of instance 0, records and submits the frame's work.
    pub fn deform(&mut self, posed: &[Sweep]) -> Result<(), GpuError> {
        self.set_pose(0, posed)?;
        let mut encoder = self
            .context
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd frame") });
        self.encode(&mut encoder);
        self.context.queue.submit([encoder.finish()]);
        self.context.check_alive()
    }

    /// Copies instance 0's latest positions back to the CPU (blocking), tightly packed f32 xyz.
    pub fn read_positions(&self) -> Result<Vec<f32>, GpuError> {
        self.read_instance(self.positions(), 0)
    }

    /// Copies instance `instance`'s latest positions back to the CPU (blocking).
    pub fn read_instance_positions(&self, instance: u32) -> Result<Vec<f32>, GpuError> {
        self.read_instance(self.positions(), instance)
    }

    /// Copies instance `instance`'s previous positions back (blocking), if kept.
    pub fn read_previous_positions(&self, instance: u32) -> Result<Option<Vec<f32>>, GpuError> {
        self.previous_positions().map(|buffer| self.read_instance(buffer, instance)).transpose()
    }

    /// The unit tangents of the deformed mesh (of the latest positions), f32 xyzw, 16 bytes a
    /// vertex (w the rest tangent's), instance i at `instance_offset(i) / 12 × 16`, if the
    /// descriptor had rest tangents; usage `VERTEX | STORAGE | COPY_SRC`.
    pub fn tangents(&self) -> Option<&wgpu::Buffer> {
        self.tangents.get(self.current).map(TangentStage::buffer)
    }

    /// Copies instance `instance`'s tangents back (blocking), or `None` without rest tangents.
    pub fn read_instance_tangents(&self, instance: u32) -> Result<Option<Vec<[f32; 4]>>, GpuError> {
        let Some(buffer) = self.tangents() else { return Ok(None) };
        if instance >= self.targets.instances {
            return Err(InputError::InstanceOutOfRange { instance, instances: self.targets.instances }.into());
        }
        let first = self.targets.instance_offset(instance) / POSITION_STRIDE * TANGENT_STRIDE;
        let bytes = read_bytes(&self.context, buffer, first, self.vertex_count as u64 * TANGENT_STRIDE)?;
        Ok(Some(bytemuck::pod_collect_to_vec(&bytes)))
    }

    /// Copies instance 0's tangents back (blocking), or `None` without rest tangents.
    pub fn read_tangents(&self) -> Result<Option<Vec<[f32; 4]>>, GpuError> {
        self.read_instance_tangents(0)
    }

    /// Copies instance 0's normals back to the CPU (blocking), or `None` without triangles.
    pub fn read_normals(&self) -> Result<Option<Vec<f32>>, GpuError> {
        self.read_instance_normals(0)
    }

    /// Copies instance `instance`'s normals back (blocking), or `None` without triangles.
    pub fn read_instance_normals(&self, instance: u32) -> Result<Option<Vec<f32>>, GpuError> {
        self.normals().map(|buffer| self.read_instance(buffer, instance)).transpose()
    }

    fn read_instance(&self, buffer: &wgpu::Buffer, instance: u32) -> Result<Vec<f32>, GpuError> {
        if instance >= self.targets.instances {
            return Err(InputError::InstanceOutOfRange { instance, instances: self.targets.instances }.into());
        }
        let size = self.vertex_count as u64 * POSITION_STRIDE;
        // The normals are laid out as the deformer's own positions, from byte 0.
        let is_positions = self.targets.buffers.iter().any(|b| b == buffer);
        let base = if is_positions { 0 } else { self.targets.offset };
        let offset = self.targets.instance_offset(instance) - base;
        let bytes = read_bytes(&self.context, buffer, offset, size)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    internal_fn! {
        /// Copies the band records back to the CPU (blocking), vertices global; empty without
        /// falloff bands.
        fn read_band_records(&self) -> Result<Vec<BandRecord>, GpuError> {
            self.bands.as_ref().map_or(Ok(Vec::new()), |bands| bands.read_records(&self.context))
        }
    }

    /// Number of vertices in falloff bands (moved by the band kernel).
    pub fn band_vertex_count(&self) -> usize {
        self.bands.as_ref().map_or(0, BandStage::len)
    }

    /// Device memory that grows with the mesh, bytes: bindings, positions (both buffers with
    /// previous positions; an app-supplied output's share counted too), the falloff bands' records, and
    /// the normals and tangents with what their passes keep (rest normals and tangents, vertex
    /// and fan lists), and the normal coordinates of Jacobian normals. The rig's cell records, the staging buffers of the pose uploads and the
    /// bounds are excluded: they grow with the rig and the instances, not the vertices.
    pub fn device_bytes(&self) -> u64 {
        let bindings = self.dispatched_vertex_count() as u64 * BINDING_STRIDE;
        let positions = self.targets.bytes() * self.targets.buffers.len() as u64;
        let normals: u64 = self.normals.iter().map(|stage| stage.device_bytes).sum();
        let tangents: u64 = self.tangents.iter().map(|stage| stage.device_bytes).sum();
        let bands = self.bands.as_ref().map_or(0, BandStage::device_bytes);
        let groups: u64 =
            self.chunks.iter().filter_map(|chunk| chunk.groups.as_ref()).map(CellGroups::device_bytes).sum();
        bindings + positions + normals + tangents + bands + self.coordinates_bytes + groups
    }

    internal_fn! {
        /// Copies the cell groups back to the CPU (blocking), those of each deform chunk with its
        /// first vertex (`None` if the deform kernel runs over single vertices): [`CELL_GROUP`]
        /// chunk-relative vertices a group, [`UNOWNED`] in free slots, as
        /// `crate::cpu::cell_order::cell_groups` makes them up to the order of each cell's
        /// vertices.
        ///
        /// [`CELL_GROUP`]: crate::coeffs::CELL_GROUP
        fn read_cell_groups(&self) -> Result<Option<Vec<ChunkGroups>>, GpuError> {
            let mut all = Vec::with_capacity(self.chunks.len());
            for chunk in &self.chunks {
                let Some(groups) = &chunk.groups else { return Ok(None) };
                let bytes = read_bytes(&self.context, &groups.buffer, 0, groups.count as u64 * 4 * CELL_GROUP as u64)?;
                all.push((chunk.range.start, bytemuck::pod_collect_to_vec::<u8, u32>(&bytes)));
            }
            Ok(Some(all))
        }
    }

    /// Copies the bindings back to the CPU (blocking), one per vertex, unpacked from the GPU's
    /// [`PackedBinding`]s (s and φ as stored, to 21 bits); band vertices carry
    /// [`BAND_FLAG`] in their cell; vertices outside every dispatch are unbound ([`UNOWNED`],
    /// as the bind kernel writes it).
    pub fn read_bindings(&self) -> Result<Vec<GpuBinding>, GpuError> {
        let unbound = GpuBinding { cell: UNOWNED, s: 0.0, phi: 0.0, d: 0.0, h: 0.0 };
        let mut bindings = vec![unbound; self.vertex_count as usize];
        for chunk in &self.chunks {
            let bytes = read_bytes(&self.context, &chunk.bindings, 0, chunk.range.len() as u64 * BINDING_STRIDE)?;
            let range = chunk.range.start as usize..chunk.range.end as usize;
            let packed = bytemuck::pod_collect_to_vec::<u8, PackedBinding>(&bytes);
            for (binding, packed) in bindings[range].iter_mut().zip(&packed) {
                *binding = packed.unpack();
            }
        }
        Ok(bindings)
    }

    /// Each deform dispatch's vertex range and binding buffer (for the bench).
    #[cfg(feature = "bench")]
    pub(crate) fn binding_chunks(&self) -> impl Iterator<Item = (&Range<u32>, &wgpu::Buffer)> {
        self.chunks.iter().map(|chunk| (&chunk.range, &chunk.bindings))
    }

    /// Bytes the normals pass reads and writes a frame (for the bench).
    #[cfg(feature = "bench")]
    pub(crate) fn normals_frame_bytes(&self) -> u64 {
        self.normals.get(self.current).map_or(0, NormalsStage::frame_bytes)
    }

    /// The rest rig's cell records, as the bind kernel reads them (for the bench).
    #[cfg(feature = "bench")]
    pub(crate) fn rest_cells(&self) -> &wgpu::Buffer {
        &self.rest_cells
    }

    /// The context the deformer runs on.
    pub fn context(&self) -> &GpuContext {
        &self.context
    }

    /// The device limits the deformer was planned for.
    pub fn limits(&self) -> &ChunkLimits {
        &self.limits
    }
}

/// Fails unless `weights` are sorted by vertex, each vertex `bound` (owned by a sweep), each
/// weight in [0, 1) and each neighbour one of the rig's `sweeps` or [`UNOWNED`] (the rest
/// position).
pub(super) fn check_weights(
    weights: &[BandWeight],
    sweeps: usize,
    bound: impl Fn(usize) -> bool,
) -> Result<(), GpuError> {
    let band = |b: &BandWeight| (b.vertex, b.weight, b.neighbour);
    check_bands(weights, band, sweeps, bound).map_err(|()| InputError::BandsOutOfOrder.into())
}

/// Whether `bands`, each seen as (vertex, weight, second influence), are sorted by vertex, each
/// vertex `bound`, each weight in [0, 1) and each second influence below `seconds` or
/// [`UNOWNED`] (the rest position).
pub(super) fn check_bands<B>(
    bands: &[B],
    band: impl Fn(&B) -> (u32, f64, u32),
    seconds: usize,
    bound: impl Fn(usize) -> bool,
) -> Result<(), ()> {
    let ordered = bands.windows(2).all(|pair| band(&pair[0]).0 < band(&pair[1]).0);
    let valid = |b: &B| {
        let (vertex, weight, second) = band(b);
        bound(vertex as usize) && (0.0..1.0).contains(&weight) && (second == UNOWNED || (second as usize) < seconds)
    };
    if ordered && bands.iter().all(valid) { Ok(()) } else { Err(()) }
}

/// Makes the position buffers `targets` plans (or takes the application's output) and writes
/// the rest positions into every instance of each; returns the buffer the bind kernel reads the
/// rest positions from: instance 0 of the first buffer, or an upload of their own when the
/// application supplies the output.
fn make_position_buffers(
    context: &GpuContext,
    descriptor: &DeformerDescriptor,
    targets: &mut PositionTargets,
) -> wgpu::Buffer {
    let (device, positions) = (&context.device, descriptor.positions);
    let image = targets.rest_image(positions);
    match descriptor.output {
        Some(output) => {
            targets.buffers = output.buffers().cloned().collect();
            for buffer in &targets.buffers {
                context.queue.write_buffer(buffer, output.offset, bytemuck::cast_slice(&image));
            }
            targets.offset = output.offset;
            upload_positions(device, positions)
        }
        None => {
            let count = if descriptor.previous_positions { 2 } else { 1 };
            targets.buffers = (0..count).map(|_| upload_positions(device, &image)).collect();
            targets.buffers[0].clone()
        }
    }
}

/// One normals (and tangents) stage per position buffer, each recording its rest pass now; per
/// frame only the vertices whose one-ring can move are recomputed. None without triangles.
fn surface_stages(
    context: &GpuContext,
    descriptor: &DeformerDescriptor,
    plan: &DeformerPlan,
    encoder: &mut wgpu::CommandEncoder,
) -> Result<(Vec<NormalsStage>, Vec<TangentStage>), GpuError> {
    let (mut normals, mut tangents) = (Vec::new(), Vec::new());
    let Some(adjacency) = &plan.adjacency else { return Ok((normals, tangents)) };
    let (targets, instances, limits) = (&plan.targets, descriptor.instances, &plan.limits);
    for buffer in &targets.buffers {
        let sizes = (plan.vertex_count, targets.stride);
        let positions = (buffer, targets.offset);
        // With Jacobian normals the vertices the probe passes leave the per-frame lists after it.
        let moves = (&plan.bound[..], plan.reach.as_deref());
        let stage = NormalsStage::new(context, encoder, adjacency, positions, sizes, instances, moves, limits)?;
        if let Some(rest_tangents) = descriptor.rest_tangents {
            tangents.push(TangentStage::new(context, encoder, rest_tangents, &stage, sizes, instances, limits)?);
        }
        normals.push(stage);
    }
    Ok((normals, tangents))
}

/// The falloff bands' stage, its records set (none without band vertices).
fn band_stage(
    context: &GpuContext,
    descriptor: &DeformerDescriptor,
    plan: &DeformerPlan,
    (cells, rest_cells): (&PosedCells, &wgpu::Buffer),
    (chunks, binder): (&[DeformChunk], Option<&Binder>),
    encoder: &mut wgpu::CommandEncoder,
) -> Option<BandStage> {
    if plan.band_vertices.is_empty() {
        return None;
    }
    let source = match descriptor.bindings {
        BindingSource::Bind { bands, .. } => BandSource::Bind { weights: bands, positions: descriptor.positions },
        BindingSource::Precomputed { bands, .. } => BandSource::Records(bands),
    };
    let band_plan = BandPlan { cells, targets: &plan.targets, limits: &plan.limits };
    let windows: Vec<(Range<u32>, &wgpu::Buffer)> =
        chunks.iter().map(|chunk| (chunk.range.clone(), &chunk.bindings)).collect();
    let mut stage = BandStage::new(context, plan.variant, rest_cells);
    stage.set_records(context, band_plan, &windows, source, binder, encoder);
    Some(stage)
}

/// What every deform chunk of a deformer is built from.
struct ChunkInputs<'a> {
    context: &'a GpuContext,
    descriptor: &'a DeformerDescriptor<'a>,
    plan: &'a DeformerPlan,
    kernel: &'a Kernel,
    /// The bind kernel's resources, for [`BindingSource::Bind`].
    binder: Option<&'a Binder>,
    /// The rest positions the bind kernel reads.
    rest_buffer: &'a wgpu::Buffer,
    rest_cells: &'a wgpu::Buffer,
    cells: &'a PosedCells,
    normals: &'a [NormalsStage],
}

impl ChunkInputs<'_> {
    /// The chunk of the vertices `range`: its bindings (bound on the GPU or uploaded), its
    /// normal coordinates (Jacobian normals), its cell groups and its deform dispatches.
    fn build(&self, range: Range<u32>, encoder: &mut wgpu::CommandEncoder) -> (DeformChunk, Option<NormalCoordinates>) {
        let (context, plan) = (self.context, self.plan);
        let bindings = self.bindings(&range, encoder);
        let coordinates = self.descriptor.jacobian_normals.then(|| {
            let rest_normals = &self.normals.first().expect("Jacobian normals need triangles").buffer;
            let coordinates = NormalCoordinates::new(&context.device, range.len() as u32);
            let buffers = (self.rest_cells, &bindings, rest_normals);
            coordinates.encode(context, encoder, plan.variant, buffers, &range, &plan.limits);
            coordinates
        });
        let numbering = plan.kernel.numbering;
        let groups = plan.kernel.cell_groups.then(|| {
            let shapes: Vec<(u32, u32)> =
                plan.targets.groups.iter().map(|g| numbering.dispatch_shape(g.len() as u32)).collect();
            let sizes = (range.len() as u32, plan.coefficients.cells.len() as u32);
            CellGroups::new(context, &bindings, sizes, &shapes, &plan.limits)
        });
        let dispatch = ChunkDispatch {
            kernel: self.kernel,
            numbering,
            cells: self.cells,
            targets: &plan.targets,
            normals: coordinates.as_ref().map(|c| (&c.buffer, self.normals)),
            limits: &plan.limits,
        };
        let chunk = DeformChunk::new(&context.device, &dispatch, range, bindings, groups);
        chunk.encode_sort(encoder);
        (chunk, coordinates)
    }

    /// The chunk's bindings, band vertices flagged: bound on the GPU from the owners, or the
    /// precomputed ones uploaded.
    fn bindings(&self, range: &Range<u32>, encoder: &mut wgpu::CommandEncoder) -> wgpu::Buffer {
        let (start, end) = (range.start as usize, range.end as usize);
        let in_band = self.plan.bands_in(range);
        match self.descriptor.bindings {
            BindingSource::Bind { owners, .. } => {
                let buffer = empty_binding_buffer(&self.context.device, range.len());
                let mut owners = owners[start..end].to_vec();
                for &v in in_band {
                    owners[v as usize - start] |= BAND_FLAG;
                }
                let binder = self.binder.expect("made for BindingSource::Bind");
                // Instance 0 of the first position buffer holds the rest positions.
                binder.encode(encoder, range, &owners, self.rest_buffer, &buffer, &self.plan.limits, None);
                buffer
            }
            BindingSource::Precomputed { bindings: all, .. } => {
                let mut chunk = all[start..end].to_vec();
                for &v in in_band {
                    chunk[v as usize - start].cell |= BAND_FLAG;
                }
                binding_buffer_with(&self.context.device, &chunk)
            }
        }
    }
}
