//! Per-instance axis-aligned bounds of the deformed vertices, computed on the GPU each frame
//! after the deform (and band) kernels: `shaders/bounds.wgsl` reduces each dispatch's vertices
//! into per-instance atomics on order-preserving u32 encodings (exact min and max), seeded each
//! frame by a buffer copy with the bounds of the vertices no dispatch covers (computed once at
//! creation); `shaders/bounds_finalize.wgsl` decodes them to f32.
//!
//! Data flow: deform → **bounds** → output (culling, indirect draws, the app's own passes).

use std::ops::Range;
use std::sync::Arc;

use wgpu::util::DeviceExt;

use super::super::GpuContext;
use super::super::buffers::params_buffer;
use super::super::chunks::{ChunkLimits, dispatch_grid};
use super::super::kernels::Kernel;
use super::instances::PositionTargets;
use crate::coeffs::{DispatchParams, InstanceParams};
use crate::cpu::bounds::{EMPTY, reduce};

/// Bytes of one instance's bounds: min.xyz, 0, max.xyz, 0 as f32.
pub const BOUNDS_STRIDE: u64 = 32;

/// One reduction dispatch: its bind group and grid (x, y, instances).
type Dispatch = (wgpu::BindGroup, (u32, u32, u32));

/// The bounds kernels, their buffers and dispatches.
#[derive(Debug)]
pub(crate) struct BoundsStage {
    reduce: Arc<Kernel>,
    finalize: Arc<Kernel>,
    seed: wgpu::Buffer,
    extremes: wgpu::Buffer,
    pub(crate) buffer: wgpu::Buffer,
    /// `dispatches[p]` read position buffer p: (bind group, grid x, y, z).
    dispatches: Vec<Vec<Dispatch>>,
    finalize_dispatch: (wgpu::BindGroup, (u32, u32)),
}

impl BoundsStage {
    /// The bounds of `targets`' instances over the vertex ranges `ranges` (each instance's
    /// dispatches), seeded with the bounds of the rest positions `rest` outside them.
    pub(crate) fn new(
        context: &GpuContext,
        targets: &PositionTargets,
        ranges: &[Range<u32>],
        rest: &[[f32; 3]],
        limits: &ChunkLimits,
    ) -> BoundsStage {
        let device = &context.device;
        let (reduce_kernel, finalize) = (context.kernels().bounds(device), context.kernels().bounds_finalize(device));
        let mut outside = EMPTY;
        let mut next = 0usize;
        for range in ranges.iter().chain([&(targets.vertex_count..targets.vertex_count)]) {
            reduce(bytemuck::cast_slice(&rest[next..range.start as usize]), &mut outside);
            next = range.end as usize;
        }
        let seeds: Vec<u32> = (0..targets.instances).flat_map(|_| outside).collect();
        let seed = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd bounds seed"),
            contents: bytemuck::cast_slice(&seeds),
            usage: wgpu::BufferUsages::COPY_SRC,
        });
        let bytes = targets.instances as u64 * BOUNDS_STRIDE;
        let storage = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let extremes = storage("sweepffd bounds extremes", wgpu::BufferUsages::COPY_DST);
        let buffer = storage("sweepffd bounds", wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::INDIRECT);
        let dispatches = (0..targets.buffers.len())
            .map(|parity| {
                let mut dispatches = Vec::new();
                for range in ranges {
                    for group in &targets.groups {
                        let params = InstanceParams {
                            vertex_count: range.len() as u32,
                            cells_per_instance: 0,
                            instance_stride: 3 * targets.stride,
                            first_instance: group.start,
                            ..Default::default()
                        };
                        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                            label: Some("sweepffd bounds params"),
                            contents: bytemuck::bytes_of(&params),
                            usage: wgpu::BufferUsages::UNIFORM,
                        });
                        let bind_group = reduce_kernel.bind_group(
                            device,
                            "sweepffd bounds",
                            &[
                                params.as_entire_binding(),
                                targets.window(parity, range, group),
                                extremes.as_entire_binding(),
                            ],
                        );
                        let (x, y) = dispatch_grid(range.len() as u32, limits);
                        dispatches.push((bind_group, (x, y, group.len() as u32)));
                    }
                }
                dispatches
            })
            .collect();
        let params = params_buffer(device, DispatchParams { vertex_count: targets.instances, ..Default::default() });
        let finalize_group = finalize.bind_group(
            device,
            "sweepffd bounds finalize",
            &[params.as_entire_binding(), extremes.as_entire_binding(), buffer.as_entire_binding()],
        );
        let finalize_dispatch = (finalize_group, dispatch_grid(targets.instances, limits));
        BoundsStage { reduce: reduce_kernel, finalize, seed, extremes, buffer, dispatches, finalize_dispatch }
    }

    /// Records the seed copy, the reduction over position buffer `parity` and the finalize.
    pub(crate) fn encode(&self, encoder: &mut wgpu::CommandEncoder, parity: usize) {
        encoder.copy_buffer_to_buffer(&self.seed, 0, &self.extremes, 0, self.seed.size());
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sweepffd bounds"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.reduce.pipeline);
        for (group, (x, y, z)) in &self.dispatches[parity] {
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(*x, *y, *z);
        }
        pass.set_pipeline(&self.finalize.pipeline);
        let (group, (x, y)) = &self.finalize_dispatch;
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(*x, *y, 1);
    }
}
