//! The falloff bands on the GPU: the band records of each deform dispatch, the rest cells, and
//! the band kernel (`shaders/band.wgsl`) that moves the vertices with w < 1 after the deform
//! kernel has moved the rest.
//!
//! When the deformer binds on the GPU, the bind kernel also binds every band vertex that fades
//! into a neighbouring sweep to that sweep (a compact dispatch over those vertices only), and
//! `shaders/band_pack.wgsl` packs the result into the records. The records can be replaced
//! later without touching the primary bindings ([`GpuDeformer::set_bands`]).
//!
//! [`GpuDeformer::set_bands`]: super::GpuDeformer::set_bands

use std::ops::Range;
use std::sync::Arc;

use wgpu::util::DeviceExt;

use super::GpuContext;
use super::binder::Binder;
use super::buffers::{empty_binding_buffer, params_buffer, upload_positions};
use super::chunks::{ChunkLimits, dispatch_grid};
use super::deformer::instances::{InstanceDispatch, Numbering, PosedCells, PositionTargets};
use super::kernels::{DeformVariant, Kernel};
use super::readback::read_bytes;
use crate::bind::falloff::BandWeight;
use crate::coeffs::{BandRecord, DispatchParams};

/// Bytes of one band record.
pub const BAND_STRIDE: u64 = size_of::<BandRecord>() as u64;

/// Where the band records come from.
#[derive(Clone, Copy, Debug)]
pub(crate) enum BandSource<'a> {
    /// Weights from the CPU; the second influences are bound on the GPU from `positions`.
    Bind { weights: &'a [BandWeight], positions: &'a [[f32; 3]] },
    /// Finished records, vertices global.
    Records(&'a [BandRecord]),
}

/// The band dispatch of one deform chunk.
#[derive(Debug)]
struct BandChunk {
    first_vertex: u32,
    count: u32,
    records: wgpu::Buffer,
    dispatches: Vec<InstanceDispatch>,
}

/// The band kernel and its per-chunk records.
#[derive(Debug)]
pub(crate) struct BandStage {
    kernel: Arc<Kernel>,
    /// `shaders/band_pack.wgsl`, taken from the context's cache the first time second influences
    /// are bound.
    pack: Option<Arc<Kernel>>,
    rest_cells: wgpu::Buffer,
    chunks: Vec<BandChunk>,
}

/// The deformer's buffers the band dispatches bind.
pub(crate) struct BandPlan<'a> {
    pub cells: &'a PosedCells,
    pub targets: &'a PositionTargets,
    pub limits: &'a ChunkLimits,
}

impl BandStage {
    /// The band kernel for cell records of `variant`, reading the rest rig's from `rest_cells`;
    /// no band records yet.
    pub(crate) fn new(context: &GpuContext, variant: DeformVariant, rest_cells: &wgpu::Buffer) -> BandStage {
        BandStage {
            kernel: context.kernels().band(&context.device, variant),
            pack: None,
            rest_cells: rest_cells.clone(),
            chunks: Vec::new(),
        }
    }

    /// Replaces the band records with those of `source` for the deform chunks `chunks` (each a
    /// vertex range and its binding buffer), recording any GPU binding of second influences
    /// into `encoder` (`binder` is needed for [`BandSource::Bind`]).
    pub(crate) fn set_records(
        &mut self,
        context: &GpuContext,
        plan: BandPlan,
        chunks: &[(Range<u32>, &wgpu::Buffer)],
        source: BandSource,
        binder: Option<&Binder>,
        encoder: &mut wgpu::CommandEncoder,
    ) {
        let vertex_of = |i: usize| match source {
            BandSource::Bind { weights, .. } => weights[i].vertex,
            BandSource::Records(records) => records[i].vertex,
        };
        let total = match source {
            BandSource::Bind { weights, .. } => weights.len(),
            BandSource::Records(records) => records.len(),
        };
        if matches!(source, BandSource::Bind { .. }) && total > 0 && self.pack.is_none() {
            self.pack = Some(context.kernels().band_pack(&context.device));
        }
        let device = &context.device;
        self.chunks.clear();
        let mut next = 0usize;
        for (range, bindings) in chunks {
            let start = next;
            while next < total && vertex_of(next) < range.end {
                next += 1;
            }
            if next == start {
                continue;
            }
            let records: Vec<BandRecord> = match source {
                BandSource::Bind { weights, .. } => {
                    weights[start..next].iter().map(|w| BandRecord::unbound(w, range.start)).collect()
                }
                BandSource::Records(all) => {
                    all[start..next].iter().map(|r| BandRecord { vertex: r.vertex - range.start, ..*r }).collect()
                }
            };
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sweepffd band records"),
                contents: bytemuck::cast_slice(&records),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            });
            if let (BandSource::Bind { weights, positions }, Some(binder), Some(pack)) = (source, binder, &self.pack) {
                bind_second_influences(
                    device,
                    binder,
                    pack,
                    &weights[start..next],
                    positions,
                    &buffer,
                    plan.limits,
                    encoder,
                );
            }
            let count = (next - start) as u32;
            let dispatches = self.dispatches(device, &plan, (range, count), bindings, &buffer);
            self.chunks.push(BandChunk { first_vertex: range.start, count, records: buffer, dispatches });
        }
    }

    /// The band dispatches of the `count` band vertices of the deform chunk `range`, whose
    /// bindings are `bindings` and band records `records`, for every instance and position buffer.
    fn dispatches(
        &self,
        device: &wgpu::Device,
        plan: &BandPlan,
        (range, count): (&Range<u32>, u32),
        bindings: &wgpu::Buffer,
        records: &wgpu::Buffer,
    ) -> Vec<InstanceDispatch> {
        let (kernel, rest_cells) = (&self.kernel, &self.rest_cells);
        let (cells, targets, limits) = (plan.cells, plan.targets, plan.limits);
        InstanceDispatch::plan(
            device,
            cells,
            targets,
            range,
            count,
            Numbering::Layered,
            limits,
            |params, cells, _, _, out| {
                let resources = [
                    params.as_entire_binding(),
                    cells,
                    bindings.as_entire_binding(),
                    out,
                    rest_cells.as_entire_binding(),
                    records.as_entire_binding(),
                ];
                kernel.bind_group(device, "sweepffd band", &resources)
            },
        )
    }

    /// Records the band dispatches writing position buffer `parity` into a compute pass, after
    /// the deform dispatches.
    pub(crate) fn encode(&self, pass: &mut wgpu::ComputePass, parity: usize) {
        if self.chunks.is_empty() {
            return;
        }
        pass.set_pipeline(&self.kernel.pipeline);
        for chunk in &self.chunks {
            for dispatch in &chunk.dispatches {
                dispatch.encode(pass, parity);
            }
        }
    }

    /// Number of band records (vertices with w < 1).
    pub(crate) fn len(&self) -> usize {
        self.chunks.iter().map(|c| c.count as usize).sum()
    }

    /// Device memory of the records, bytes: 16 per band vertex. The rest cells, like the posed
    /// ones, are the rig's (a few KB) and not counted.
    pub(crate) fn device_bytes(&self) -> u64 {
        self.len() as u64 * BAND_STRIDE
    }

    /// Copies the records back (blocking), vertices global.
    pub(crate) fn read_records(&self, context: &super::GpuContext) -> Result<Vec<BandRecord>, super::GpuError> {
        let mut records = Vec::with_capacity(self.len());
        for chunk in &self.chunks {
            let bytes = read_bytes(context, &chunk.records, 0, chunk.count as u64 * BAND_STRIDE)?;
            let part: Vec<BandRecord> = bytemuck::pod_collect_to_vec(&bytes);
            records.extend(part.into_iter().map(|r| BandRecord { vertex: r.vertex + chunk.first_vertex, ..r }));
        }
        Ok(records)
    }
}

/// Binds the band vertices of `weights` to the sweeps they fade into (the bind kernel on a
/// compact copy of their rest positions; the rest-position ones stay unbound) and packs the
/// result into `records`.
#[expect(clippy::too_many_arguments, reason = "one per resource of the two dispatches")]
fn bind_second_influences(
    device: &wgpu::Device,
    binder: &Binder,
    pack: &Kernel,
    weights: &[BandWeight],
    positions: &[[f32; 3]],
    records: &wgpu::Buffer,
    limits: &ChunkLimits,
    encoder: &mut wgpu::CommandEncoder,
) {
    let compact: Vec<[f32; 3]> = weights.iter().map(|w| positions[w.vertex as usize]).collect();
    let owners: Vec<u32> = weights.iter().map(|w| w.neighbour).collect();
    let compact_positions = upload_positions(device, &compact);
    // At most one deform chunk's vertices: their bindings fit one binding by construction.
    let count = weights.len() as u32;
    let seconds = empty_binding_buffer(device, weights.len());
    binder.encode(encoder, &(0..count), &owners, &compact_positions, &seconds, limits, None);
    let params = params_buffer(device, DispatchParams { vertex_count: count, ..Default::default() });
    let group = pack.bind_group(
        device,
        "sweepffd band pack",
        &[params.as_entire_binding(), seconds.as_entire_binding(), records.as_entire_binding()],
    );
    let mut pass = encoder
        .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("sweepffd band pack"), timestamp_writes: None });
    pass.set_pipeline(&pack.pipeline);
    pass.set_bind_group(0, &group, &[]);
    let (x, y) = dispatch_grid(count, limits);
    pass.dispatch_workgroups(x, y, 1);
}
