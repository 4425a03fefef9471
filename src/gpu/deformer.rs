//! [`GpuDeformer`]: binding and Eq. 2 on the GPU, with the output position (and normal) buffer
//! ready to be drawn by the host application.

mod descriptor;
mod set_bands;

pub use descriptor::DeformerDescriptor;

use std::ops::Range;

use self::descriptor::triangle_faces;
use self::set_bands::{BandMember, Rebanding};
use super::bands::{BandPlan, BandSource, BandStage};
use super::binder::Binder;
use super::buffers::{
    BINDING_STRIDE, POSITION_STRIDE, binding_buffer_with, cells_buffer, check_fits, empty_binding_buffer,
    params_buffer, upload_positions, window,
};
use super::chunks::{ChunkLimits, dispatch_grid, uniform_chunks};
use super::kernels::{DeformVariant, Kernel};
use super::normals_pass::NormalsStage;
use super::readback::{read_bytes, wait};
use super::{GpuContext, GpuError};
use crate::bind::falloff::BandWeight;
use crate::coeffs::{BAND_FLAG, BandRecord, DispatchParams, GpuBinding, SweepCoefficients, UNOWNED};
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

/// Deforms one mesh on the GPU by poses of one rig.
///
/// Construction uploads the rest positions (once) and binds every owned vertex on the GPU; the
/// bindings stay on the GPU. Each frame, [`set_pose`](GpuDeformer::set_pose) turns the posed
/// sweeps into a few KB of coefficients and uploads only those, and
/// [`encode`](GpuDeformer::encode) records the deform (and normals) dispatches into the
/// application's command encoder: no allocation, pipeline or bind-group creation, no vertex
/// upload per frame. The [`positions`](GpuDeformer::positions) buffer (and
/// [`normals`](GpuDeformer::normals)) has `VERTEX | STORAGE` usage: draw it directly as a
/// `Float32x3` vertex attribute. Reading it back is a separate, explicit call. New falloff
/// widths need no new deformer: [`set_bands`](GpuDeformer::set_bands) replaces the bands.
///
/// Meshes whose buffers exceed the device's storage binding size or workgroup count are split
/// into chunks transparently; the position buffer is one buffer and must fit `max_buffer_size`.
///
/// ```no_run
/// # fn frame_loop(context: &sweepffd::gpu::GpuContext, rig: &sweepffd::rig::Rig,
/// #     mesh: &sweepffd::mesh::Mesh, poses: &[Vec<Vec<sweepffd::sweep::Key>>])
/// #     -> Result<(), Box<dyn std::error::Error>> {
/// use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuDeformer};
///
/// let owners = rig.owners(mesh, "mesh")?;
/// let bands = rig.band_weights(mesh, &owners); // empty without falloff
/// let bindings = BindingSource::Bind { owners: &owners, bands: &bands };
/// let rest = sweepffd::gpu::rest_positions(&mesh.positions);
/// let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
/// let descriptor = DeformerDescriptor::new(rig.rest(), &rest, bindings).with_triangles(&triangles);
/// let mut deformer = GpuDeformer::new(context, &descriptor)?;
/// for keys in poses {
///     let posed = rig.pose(keys)?; // f64 sweeps on the CPU: a few keys, not millions of vertices
///     deformer.set_pose(&posed)?; // uploads a few KB of coefficients
///     let mut encoder = context.device.create_command_encoder(&Default::default());
///     deformer.encode(&mut encoder); // deform + normals dispatches
///     // ... record the render pass that draws deformer.positions() and deformer.normals() ...
///     context.queue.submit([encoder.finish()]);
/// }
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct GpuDeformer {
    context: GpuContext,
    limits: ChunkLimits,
    kernel: std::sync::Arc<Kernel>,
    vertex_count: u32,
    positions: wgpu::Buffer,
    cells: wgpu::Buffer,
    coefficients: SweepCoefficients,
    variant: DeformVariant,
    /// The rest rig's cell records, which binding and the band kernel read.
    rest_cells: wgpu::Buffer,
    chunks: Vec<DeformChunk>,
    bands: Option<BandStage>,
    rebanding: Rebanding,
    normals: Option<NormalsStage>,
}

/// One dispatch of the deform kernel.
#[derive(Debug)]
struct DeformChunk {
    range: Range<u32>,
    bindings: wgpu::Buffer,
    group: wgpu::BindGroup,
    grid: (u32, u32),
}

impl DeformChunk {
    /// The deform dispatch of the vertices in `range`, whose bindings are in `bindings`.
    fn new(
        device: &wgpu::Device,
        kernel: &Kernel,
        range: Range<u32>,
        bindings: wgpu::Buffer,
        cells: &wgpu::Buffer,
        positions: &wgpu::Buffer,
        limits: &ChunkLimits,
    ) -> DeformChunk {
        let params = params_buffer(device, DispatchParams { vertex_count: range.len() as u32, ..Default::default() });
        let group = kernel.bind_group(
            device,
            "sweepffd deform",
            &[
                params.as_entire_binding(),
                cells.as_entire_binding(),
                bindings.as_entire_binding(),
                window(positions, &range, POSITION_STRIDE),
            ],
        );
        let grid = dispatch_grid(range.len() as u32, limits);
        DeformChunk { range, bindings, group, grid }
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
    /// at once; its first frame runs after the binding on the queue.
    pub async fn new_async(context: &GpuContext, descriptor: &DeformerDescriptor<'_>) -> Result<GpuDeformer, GpuError> {
        descriptor.check()?;
        let DeformerDescriptor { rest, positions, bindings, triangles } = *descriptor;
        let faces = triangles.map(triangle_faces);
        let device = &context.device;
        let device_limits = device.limits();
        if device_limits.max_storage_buffers_per_shader_stage < STORAGE_BUFFERS_NEEDED {
            return Err(GpuError::Input(format!(
                "the device allows {} storage buffers per shader stage; binding needs {STORAGE_BUFFERS_NEEDED}",
                device_limits.max_storage_buffers_per_shader_stage
            )));
        }
        let limits = ChunkLimits::of(&device_limits);
        let vertex_count = positions.len() as u32;
        check_fits("the position buffer", vertex_count as u64 * POSITION_STRIDE, limits.max_buffer)?;

        let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let coefficients = SweepCoefficients::new(rest);
        let positions_buffer = upload_positions(device, positions);
        let variant = DeformVariant::for_cells(coefficients.cells.len(), &device_limits);
        let cells = cells_buffer(device, &coefficients, variant);
        let rest_cells = cells_buffer(device, &coefficients, variant);
        let kernel = context.kernels().deform(device, variant);
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd bind") });
        let binder = match bindings {
            BindingSource::Bind { .. } => Some(Binder::new(context, rest, &coefficients, &rest_cells)),
            BindingSource::Precomputed { .. } => None,
        };
        let band_vertices: Vec<u32> = match bindings {
            BindingSource::Bind { bands, .. } => bands.iter().map(|b| b.vertex).collect(),
            BindingSource::Precomputed { bands, .. } => bands.iter().map(|b| b.vertex).collect(),
        };
        let chunks: Vec<DeformChunk> = uniform_chunks(vertex_count, BINDING_STRIDE, &limits)
            .into_iter()
            .map(|range| {
                let (start, end) = (range.start as usize, range.end as usize);
                let first_band = band_vertices.partition_point(|&v| (v as usize) < start);
                let last_band = band_vertices.partition_point(|&v| (v as usize) < end);
                let in_band = &band_vertices[first_band..last_band];
                let bindings_buffer = match bindings {
                    BindingSource::Bind { owners, .. } => {
                        let buffer = empty_binding_buffer(device, range.len());
                        let mut owners = owners[start..end].to_vec();
                        for &v in in_band {
                            owners[v as usize - start] |= BAND_FLAG;
                        }
                        let binder = binder.as_ref().expect("made for BindingSource::Bind");
                        binder.encode(&mut encoder, &range, &owners, &positions_buffer, &buffer, &limits, None);
                        buffer
                    }
                    BindingSource::Precomputed { bindings: all, .. } => {
                        let mut chunk = all[start..end].to_vec();
                        for &v in in_band {
                            chunk[v as usize - start].cell |= BAND_FLAG;
                        }
                        binding_buffer_with(device, &chunk)
                    }
                };
                DeformChunk::new(device, &kernel, range, bindings_buffer, &cells, &positions_buffer, &limits)
            })
            .collect();
        let bands = (!band_vertices.is_empty()).then(|| {
            let source = match bindings {
                BindingSource::Bind { bands, .. } => BandSource::Bind { weights: bands, positions },
                BindingSource::Precomputed { bands, .. } => BandSource::Records(bands),
            };
            let plan = BandPlan { cells: &cells, positions: &positions_buffer, limits: &limits };
            let windows: Vec<(Range<u32>, &wgpu::Buffer)> =
                chunks.iter().map(|chunk| (chunk.range.clone(), &chunk.bindings)).collect();
            let mut stage = BandStage::new(context, variant, &rest_cells);
            stage.set_records(context, plan, &windows, source, binder.as_ref(), &mut encoder);
            stage
        });
        let (members, bound): (Vec<BandMember>, Vec<bool>) = match bindings {
            BindingSource::Bind { owners, bands } => {
                (bands.iter().map(BandMember::of_weight).collect(), owners.iter().map(|&o| o != UNOWNED).collect())
            }
            BindingSource::Precomputed { bindings, bands } => (
                bands.iter().map(BandMember::of_record).collect(),
                bindings.iter().map(|b| b.cell != UNOWNED).collect(),
            ),
        };
        let rebanding = Rebanding::new(rest, binder, members, &bound);
        let normals = match faces {
            Some(faces) => Some(NormalsStage::new(context, &faces, &positions_buffer, vertex_count, &limits)?),
            None => None,
        };
        let deformer = GpuDeformer {
            context: context.clone(),
            limits,
            kernel,
            vertex_count,
            positions: positions_buffer,
            cells,
            coefficients,
            variant,
            rest_cells,
            chunks,
            bands,
            rebanding,
            normals,
        };
        // Normals of the rest mesh, so the buffer is meaningful before the first pose.
        deformer.encode_normals_pass(&mut encoder, None);
        context.queue.submit([encoder.finish()]);
        // Both scopes are popped on this thread before either is awaited: wgpu's error scopes
        // belong to the thread that pushed them.
        let (validation, out_of_memory) = (validation.pop(), out_of_memory.pop());
        let (validation_error, memory_error) = (validation.await, out_of_memory.await);
        if let Some(error) = validation_error.or(memory_error) {
            return Err(error.into());
        }
        Ok(deformer)
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> u32 {
        self.vertex_count
    }

    /// The deformed positions, tightly packed f32 xyz (12 bytes a vertex); usage
    /// `VERTEX | STORAGE | COPY_SRC | COPY_DST`. Unbound vertices keep their rest position.
    pub fn positions(&self) -> &wgpu::Buffer {
        &self.positions
    }

    /// The unit vertex normals of the deformed mesh, tightly packed f32 xyz, if the deformer
    /// was given faces; usage `VERTEX | STORAGE | COPY_SRC`.
    pub fn normals(&self) -> Option<&wgpu::Buffer> {
        self.normals.as_ref().map(|n| &n.buffer)
    }

    /// Number of deform dispatches (1 unless the mesh exceeds a device limit).
    pub fn chunk_count(&self) -> usize {
        self.chunks.len()
    }

    /// Turns posed sweeps into coefficients (in place, no allocation) and queues their upload:
    /// a few KB. Fails if the sweeps lack the rest rig's structure.
    pub fn set_pose(&mut self, posed: &[Sweep]) -> Result<(), GpuError> {
        self.coefficients.update(posed)?;
        let bytes = bytemuck::cast_slice(&self.coefficients.cells);
        self.context.queue.write_buffer(&self.cells, 0, bytes);
        Ok(())
    }

    /// Records the frame's work into `encoder`: the deform pass, then the normals pass if any.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) {
        self.encode_deform_pass(encoder, None);
        self.encode_normals_pass(encoder, None);
    }

    /// Records the deform pass alone (the deform kernel, then the band kernel for the vertices in
    /// falloff bands), optionally writing timestamps around it.
    pub fn encode_deform_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sweepffd deform"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.kernel.pipeline);
        for chunk in &self.chunks {
            pass.set_bind_group(0, &chunk.group, &[]);
            pass.dispatch_workgroups(chunk.grid.0, chunk.grid.1, 1);
        }
        if let Some(bands) = &self.bands {
            bands.encode(&mut pass);
        }
    }

    /// Records the normals pass alone (nothing without faces), optionally with timestamps.
    pub fn encode_normals_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let Some(normals) = &self.normals else { return };
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sweepffd normals"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&normals.kernel.pipeline);
        for (group, grid) in &normals.dispatches {
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(grid.0, grid.1, 1);
        }
    }

    /// Convenience for tools: sets the pose, records and submits the frame's work.
    pub fn deform(&mut self, posed: &[Sweep]) -> Result<(), GpuError> {
        self.set_pose(posed)?;
        let mut encoder = self
            .context
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd frame") });
        self.encode(&mut encoder);
        self.context.queue.submit([encoder.finish()]);
        self.context.check_alive()
    }

    /// Copies the positions back to the CPU (blocking), tightly packed f32 xyz.
    pub fn read_positions(&self) -> Result<Vec<f32>, GpuError> {
        let bytes = read_bytes(&self.context, &self.positions, 0, self.vertex_count as u64 * POSITION_STRIDE)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// Copies the normals back to the CPU (blocking), or `None` without faces.
    pub fn read_normals(&self) -> Result<Option<Vec<f32>>, GpuError> {
        let Some(normals) = &self.normals else {
            return Ok(None);
        };
        let bytes = read_bytes(&self.context, &normals.buffer, 0, self.vertex_count as u64 * POSITION_STRIDE)?;
        Ok(Some(bytemuck::pod_collect_to_vec(&bytes)))
    }

    /// Copies the band records back to the CPU (blocking), vertices global; empty without
    /// falloff bands.
    pub fn read_band_records(&self) -> Result<Vec<BandRecord>, GpuError> {
        self.bands.as_ref().map_or(Ok(Vec::new()), |bands| bands.read_records(&self.context))
    }

    /// Number of vertices in falloff bands (moved by the band kernel).
    pub fn band_vertex_count(&self) -> usize {
        self.bands.as_ref().map_or(0, BandStage::len)
    }

    /// Device memory that grows with the mesh: bindings, positions and the falloff bands' records,
    /// bytes (normals and the rig's cell records excluded).
    pub fn device_bytes(&self) -> u64 {
        let per_vertex = self.vertex_count as u64 * (BINDING_STRIDE + POSITION_STRIDE);
        per_vertex + self.bands.as_ref().map_or(0, BandStage::device_bytes)
    }

    /// Copies the bindings back to the CPU (blocking), one per vertex; band vertices carry
    /// [`BAND_FLAG`] in their cell.
    pub fn read_bindings(&self) -> Result<Vec<GpuBinding>, GpuError> {
        let mut bindings = Vec::with_capacity(self.vertex_count as usize);
        for chunk in &self.chunks {
            let bytes = read_bytes(&self.context, &chunk.bindings, 0, chunk.range.len() as u64 * BINDING_STRIDE)?;
            bindings.extend(bytemuck::pod_collect_to_vec::<u8, GpuBinding>(&bytes));
        }
        Ok(bindings)
    }

    /// Each deform dispatch's vertex range and binding buffer.
    pub(crate) fn binding_chunks(&self) -> impl Iterator<Item = (&Range<u32>, &wgpu::Buffer)> {
        self.chunks.iter().map(|chunk| (&chunk.range, &chunk.bindings))
    }

    /// The per-frame cell record buffer.
    pub(crate) fn cells(&self) -> &wgpu::Buffer {
        &self.cells
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
    check_bands(weights, band, sweeps, bound)
        .map_err(|()| GpuError::Input("the falloff bands are not sorted, owned and in range".into()))
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
