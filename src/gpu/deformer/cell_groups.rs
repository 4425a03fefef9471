//! Cell groups: the deform kernel's vertices grouped by the cell they are bound in, so that one
//! invocation deforms [`CELL_GROUP`] vertices with one read of their cell's record.
//!
//! Data flow: bindings (bind kernel) → **counting sort by (block, cell)**
//! (`shaders/cell_order.wgsl`, on the GPU in the creation's encoder, and again by `set_bands`)
//! → the groups and the deform dispatches' indirect arguments → the deform kernel over groups
//! (`shaders/deform_groups.wgsl`, `shaders/deform_normals_groups.wgsl`) every frame →
//! positions (and normals), in the mesh's vertex order.
//!
//! Why: on a CPU adapter (lavapipe) every lane gathers its 37 floats of cell record one float at
//! a time, which costs more than the rest of the kernel; in groups the record is gathered once a
//! group. Sorting within blocks of consecutive vertices keeps the groups near the vertex order,
//! so the bindings are read and the positions written close to where they were a moment before.
//! On a discrete GPU the records sit in the L1 cache however many lanes read them, while the
//! groups add a 4-byte index a vertex and leave the vertex order within each block, so
//! [`DeformOrder::Auto`] keeps one vertex an invocation there, its positions stored whole
//! ([`DeformOrder::StagedVertices`]).

use std::sync::Arc;

use wgpu::util::DeviceExt;

use super::super::GpuContext;
use super::super::chunks::{ChunkLimits, dispatch_grid};
use super::super::kernels::Kernel;
use crate::coeffs::SCAN_RUN;
use crate::coeffs::{CELL_GROUP, CellOrderParams};
use crate::cpu::cell_order::{block_size, bucket_count, group_slots};

/// Which vertices an invocation of the deform kernel deforms.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DeformOrder {
    /// [`CellGroups`](DeformOrder::CellGroups) on a CPU adapter (lavapipe, llvmpipe, SwiftShader),
    /// [`StagedVertices`](DeformOrder::StagedVertices) on any other.
    #[default]
    Auto,
    /// One vertex, in the mesh's order, its position stored by the invocation.
    Vertices,
    /// One vertex, in the mesh's order, a workgroup's positions staged in workgroup memory and
    /// stored as whole words: a warp's stores then fill whole cache lines, where storing each
    /// vertex's 12 bytes fills every third word of three (`shaders/deform.wgsl`,
    /// `deform_staged_main`). The single-instance deform kernel only; several instances and
    /// the fused Jacobian normals store each vertex's own ([`Vertices`](DeformOrder::Vertices)).
    StagedVertices,
    /// [`CELL_GROUP`] vertices bound in one cell, reading its record once: the groups are made
    /// at creation (a counting sort on the GPU, 4 bytes a slot).
    CellGroups,
}

impl DeformOrder {
    /// `"auto"`, `"vertices"`, `"staged vertices"` or `"cell groups"`, as `sweepffd info` and
    /// the bench name it.
    pub fn name(self) -> &'static str {
        match self {
            DeformOrder::Auto => "auto",
            DeformOrder::Vertices => "vertices",
            DeformOrder::StagedVertices => "staged vertices",
            DeformOrder::CellGroups => "cell groups",
        }
    }

    /// The order this asks for on an adapter of `device_type`: itself, or for
    /// [`Auto`](DeformOrder::Auto) the adapter's.
    pub fn on_type(self, device_type: wgpu::DeviceType) -> DeformOrder {
        match (self, device_type) {
            (DeformOrder::Auto, wgpu::DeviceType::Cpu) => DeformOrder::CellGroups,
            (DeformOrder::Auto, _) => DeformOrder::StagedVertices,
            (order, _) => order,
        }
    }

    /// Whether the deform kernel runs over cell groups on the adapter `info` describes.
    pub fn groups_on(self, info: &wgpu::AdapterInfo) -> bool {
        self.on_type(info.device_type) == DeformOrder::CellGroups
    }
}

/// One chunk's cell groups, and the passes that sort its vertices into them.
#[derive(Debug)]
pub(super) struct CellGroups {
    /// [`CELL_GROUP`] chunk-relative vertices a group (see `shaders/deform_groups.wgsl`).
    pub(super) buffer: wgpu::Buffer,
    /// Groups the buffer has room for.
    pub(super) count: u32,
    /// Written by the sort: the groups in use (a `u32`), then the indirect arguments (three
    /// `u32`) of each deform dispatch, at [`args_offset`](Self::args_offset).
    pub(super) args: wgpu::Buffer,
    cursors: wgpu::Buffer,
    kernels: Arc<[Kernel; 7]>,
    /// The bind group and grid of each pass.
    passes: Vec<(wgpu::BindGroup, (u32, u32))>,
}

impl CellGroups {
    /// The groups of the `vertices` vertices bound by `bindings` over `cells` cells a pose,
    /// sorted by [`encode_sort`](Self::encode_sort), for deform dispatches k of `shapes[k].0`
    /// invocations a group in each of `shapes[k].1` workgroup layers.
    pub(super) fn new(
        context: &GpuContext,
        bindings: &wgpu::Buffer,
        (vertices, cells): (u32, u32),
        shapes: &[(u32, u32)],
        limits: &ChunkLimits,
    ) -> CellGroups {
        let device = &context.device;
        let kernels = context.kernels().cell_order(device);
        // At most CELL_GROUP slots a vertex, 16 bytes as the binding's 16: the chunk's
        // bindings fit one storage binding, so do its groups.
        let slots = group_slots(vertices, cells) as u32;
        let storage = wgpu::BufferUsages::STORAGE;
        let buffer = empty(device, "sweepffd cell groups", slots.max(CELL_GROUP) as u64 * 4, storage | COPY_SRC);
        // One counter a bucket (a block's cell): about one a vertex at most.
        let buckets = bucket_count(vertices, cells);
        let cursors = empty(device, "sweepffd cell group cursors", buckets.max(1) * 4, storage | COPY_DST);
        let params = CellOrderParams {
            vertex_count: vertices,
            cell_count: cells,
            slot_count: slots,
            block_size: block_size(cells),
            max_workgroups: limits.max_workgroups,
            dispatch_count: shapes.len() as u32,
            ..Default::default()
        };
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd cell order params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let args_size = CellGroups::args_offset(shapes.len());
        let indirect = storage | wgpu::BufferUsages::INDIRECT | COPY_SRC;
        let args = empty(device, "sweepffd cell groups in use and dispatches", args_size, indirect);
        let shapes: Vec<u32> =
            shapes.iter().flat_map(|&(per_group, layers)| [per_group, layers]).chain([0, 0]).collect();
        let shapes = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd cell groups' dispatch shapes"),
            contents: bytemuck::cast_slice(&shapes),
            usage: wgpu::BufferUsages::STORAGE,
        });
        // The scan's runs of buckets (SCAN_RUN in shaders/cell_order.wgsl).
        let runs = buckets.div_ceil(SCAN_RUN as u64);
        let run_starts = empty(device, "sweepffd cell group runs", runs.max(1) * 4, storage);
        let resources = [
            params.as_entire_binding(),
            bindings.as_entire_binding(),
            cursors.as_entire_binding(),
            buffer.as_entire_binding(),
            args.as_entire_binding(),
            shapes.as_entire_binding(),
            run_starts.as_entire_binding(),
        ];
        let passes = kernels
            .iter()
            .zip(pass_grids(vertices, slots, runs as u32, limits))
            .map(|(kernel, grid)| (kernel.bind_group(device, "sweepffd cell order", &resources), grid))
            .collect();
        CellGroups { buffer, count: slots / CELL_GROUP, args, cursors, kernels, passes }
    }

    /// The byte offset of deform dispatch `k`'s indirect arguments in [`args`](Self::args).
    pub(super) fn args_offset(k: usize) -> u64 {
        4 + 12 * k as u64
    }

    /// Records the sort of the chunk's vertices into the groups, after the passes that write
    /// the bindings (binding, or new falloff bands), and the copy of the groups in use into the
    /// `vertex_count` of each of the deform dispatches' `params` (an [`InstanceParams`] each);
    /// the dispatches themselves are indirect, from [`args`](Self::args).
    ///
    /// [`InstanceParams`]: crate::coeffs::InstanceParams
    pub(super) fn encode_sort<'p>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        params: impl IntoIterator<Item = &'p wgpu::Buffer>,
    ) {
        encoder.clear_buffer(&self.cursors, 0, None);
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("sweepffd cell order"),
                timestamp_writes: None,
            });
            for (kernel, (group, grid)) in self.kernels.iter().zip(&self.passes) {
                pass.set_pipeline(&kernel.pipeline);
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(grid.0, grid.1, 1);
            }
        }
        for params in params {
            encoder.copy_buffer_to_buffer(&self.args, 0, params, 0, 4);
        }
    }

    /// Device memory the groups keep.
    pub(super) fn device_bytes(&self) -> u64 {
        self.buffer.size() + self.cursors.size() + self.args.size()
    }
}

const COPY_SRC: wgpu::BufferUsages = wgpu::BufferUsages::COPY_SRC;
const COPY_DST: wgpu::BufferUsages = wgpu::BufferUsages::COPY_DST;

/// An unmapped buffer of `size` bytes.
fn empty(device: &wgpu::Device, label: &str, size: u64, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size, usage, mapped_at_creation: false })
}

/// The grid of each pass of the sort, in the order of its kernels (`cell_order_*_main` in
/// `shaders/cell_order.wgsl`): clear every slot, count, the runs' sums, the scan over the runs
/// (one workgroup), the offsets, the scatter, and the fill of the groups.
fn pass_grids(vertices: u32, slots: u32, runs: u32, limits: &ChunkLimits) -> [(u32, u32); 7] {
    let per_vertex = dispatch_grid(vertices, limits);
    let per_run = dispatch_grid(runs, limits);
    let per_slot = dispatch_grid(slots, limits);
    [per_slot, per_vertex, per_run, (1, 1), per_run, per_vertex, dispatch_grid(slots / CELL_GROUP, limits)]
}
