//! Instances: one bound mesh deformed by N poses in one dispatch.
//!
//! Data flow: posed sweeps → **cell records of every instance** (copied in by each encode from
//! a staging buffer, [`PoseUploads`](super::uploads::PoseUploads)) → deform and band dispatches
//! over (vertices × instances) → positions, instance i at [`PositionTargets::instance_offset`].

use std::ops::Range;

use wgpu::util::DeviceExt;

use super::super::buffers::POSITION_STRIDE;
use super::super::chunks::{ChunkLimits, dispatch_grid};
use super::super::kernels::DeformVariant;
use crate::coeffs::{CellCoeffs, INSTANCES_PER_INVOCATION, InstanceParams, UNIFORM_CELL_CAPACITY};

/// With several instances each instance's positions start a multiple of this many vertices
/// apart (64 × 12 bytes = 3 × 256), so every instance's windows are aligned on any device.
pub const INSTANCE_ALIGNMENT: u32 = 64;

/// The per-frame cell records of every instance, instance i at i × `per_instance`.
#[derive(Debug)]
pub(crate) struct PosedCells {
    pub(crate) buffer: wgpu::Buffer,
    /// Bytes of the records of every instance.
    pub(crate) used_bytes: u64,
    /// Bytes of the binding (the uniform array's size for the uniform variant).
    binding_bytes: u64,
    /// Cell records of one instance.
    pub(crate) per_instance: u32,
}

impl PosedCells {
    /// `instances` copies of the rest records `rest`.
    pub(crate) fn new(
        device: &wgpu::Device,
        rest: &[CellCoeffs],
        instances: u32,
        variant: DeformVariant,
    ) -> PosedCells {
        let record = size_of::<CellCoeffs>() as u64;
        let used_bytes = rest.len() as u64 * instances as u64 * record;
        let binding_bytes = match variant {
            DeformVariant::Uniform => UNIFORM_CELL_CAPACITY as u64 * record,
            DeformVariant::Storage => used_bytes,
        };
        let mut contents = vec![0u8; binding_bytes as usize];
        let image: &[u8] = bytemuck::cast_slice(rest);
        for instance in 0..instances as usize {
            let at = instance * image.len();
            contents[at..at + image.len()].copy_from_slice(image);
        }
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd posed cells"),
            contents: &contents,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        });
        PosedCells { buffer, used_bytes, binding_bytes, per_instance: rest.len() as u32 }
    }

    /// The binding of the records.
    pub(crate) fn binding(&self) -> wgpu::BindingResource<'_> {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &self.buffer,
            offset: 0,
            size: wgpu::BufferSize::new(self.binding_bytes),
        })
    }
}

/// The deform kernel's outputs: `buffers` (one, or two for previous positions), each holding
/// every instance's positions, instance i at [`instance_offset`](PositionTargets::instance_offset).
#[derive(Debug)]
pub(crate) struct PositionTargets {
    pub(crate) buffers: Vec<wgpu::Buffer>,
    /// Byte offset of instance 0 in each buffer (an app-supplied output's offset, else 0).
    pub(crate) offset: u64,
    pub(crate) vertex_count: u32,
    /// Vertices from one instance's positions to the next's.
    pub(crate) stride: u32,
    pub(crate) instances: u32,
    /// The instances of each dispatch: as many as one storage binding of positions holds.
    pub(crate) groups: Vec<Range<u32>>,
}

impl PositionTargets {
    /// The targets of `instances` instances of `vertex_count` vertices, planned for deform
    /// chunks of at most `max_chunk` vertices.
    pub(crate) fn plan(vertex_count: u32, instances: u32, max_chunk: u32, limits: &ChunkLimits) -> PositionTargets {
        let stride = if instances == 1 { vertex_count } else { vertex_count.next_multiple_of(INSTANCE_ALIGNMENT) };
        // ((g − 1) · stride + max_chunk) · 12 bytes must fit one binding.
        let budget = limits.max_binding / POSITION_STRIDE;
        let fitting = budget.saturating_sub(max_chunk as u64) / stride.max(1) as u64 + 1;
        let per_group = fitting.min(limits.max_workgroups as u64).min(instances as u64).max(1) as u32;
        let groups =
            (0..instances.div_ceil(per_group)).map(|g| g * per_group..((g + 1) * per_group).min(instances)).collect();
        PositionTargets { buffers: Vec::new(), offset: 0, vertex_count, stride, instances, groups }
    }

    /// Bytes of every instance's positions, from instance 0's first.
    pub(crate) fn bytes(&self) -> u64 {
        ((self.instances as u64 - 1) * self.stride as u64 + self.vertex_count as u64) * POSITION_STRIDE
    }

    /// The byte offset of instance `instance`'s first position.
    pub(crate) fn instance_offset(&self, instance: u32) -> u64 {
        self.offset + instance as u64 * self.stride as u64 * POSITION_STRIDE
    }

    /// The window of buffer `parity` covering the vertices `range` of the instances `group`.
    pub(crate) fn window(&self, parity: usize, range: &Range<u32>, group: &Range<u32>) -> wgpu::BindingResource<'_> {
        self.window_of(&self.buffers[parity], self.offset, range, group)
    }

    /// The same window of `buffer`, laid out as the positions (12 bytes a vertex) from byte
    /// `base` on.
    pub(crate) fn window_of<'b>(
        &self,
        buffer: &'b wgpu::Buffer,
        base: u64,
        range: &Range<u32>,
        group: &Range<u32>,
    ) -> wgpu::BindingResource<'b> {
        let first = self.instance_offset(group.start) - self.offset + base + range.start as u64 * POSITION_STRIDE;
        let vertices = (group.len() as u64 - 1) * self.stride as u64 + range.len() as u64;
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer,
            offset: first,
            size: wgpu::BufferSize::new(vertices * POSITION_STRIDE),
        })
    }

    /// Every instance's rest positions, as the buffers hold them at creation.
    pub(crate) fn rest_image(&self, rest: &[[f32; 3]]) -> Vec<[f32; 3]> {
        let mut image = vec![[0.0; 3]; (self.bytes() / POSITION_STRIDE) as usize];
        for instance in 0..self.instances as usize {
            let at = instance * self.stride as usize;
            image[at..at + rest.len()].copy_from_slice(rest);
        }
        image
    }
}

/// How a dispatch over several instances numbers its invocations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Numbering {
    /// One workgroup layer z per instance: every kernel over instances.
    Layered,
    /// Vertex i of instances k·z … k·z + k − 1 at invocation z · count + i (k =
    /// [`INSTANCES_PER_INVOCATION`]), so that only the dispatch's last workgroup is partly
    /// empty and each binding is read once for k instances: `deform_instances_main`.
    Flat,
}

impl Numbering {
    /// Invocations a thread (vertex, or cell group) of a dispatch over `instances` instances
    /// has in one workgroup layer, and the layers: one per instance layer of the flat numbering
    /// in one layer, or one in each of `instances` layers.
    pub(crate) fn dispatch_shape(self, instances: u32) -> (u32, u32) {
        match self {
            Numbering::Layered => (1, instances),
            Numbering::Flat => (instances.div_ceil(INSTANCES_PER_INVOCATION), 1),
        }
    }
}

/// One dispatch over some instances: a bind group per position buffer (`parity`).
#[derive(Debug)]
pub(crate) struct InstanceDispatch {
    groups: Vec<wgpu::BindGroup>,
    grid: (u32, u32, u32),
    /// The dispatch's [`InstanceParams`] (`COPY_DST`: the deform kernel over cell groups gets
    /// its group count copied in on the GPU).
    pub(crate) params: wgpu::Buffer,
    /// Where the dispatch's workgroups are read from instead of `grid`, when the GPU writes them
    /// (the deform kernel over cell groups): a buffer and a byte offset.
    pub(crate) indirect: Option<(wgpu::Buffer, u64)>,
}

impl InstanceDispatch {
    /// The dispatches of a kernel over `count` threads per instance (the vertices `range`, or
    /// their band records), one per instance group; `group_of(params, cells, positions)` makes
    /// the bind group of one position buffer from the dispatch's params, the cells and the
    /// window of the position buffer (the group's parity and instances given too, for windows
    /// of other buffers laid out as the positions), the invocations numbered as `numbering` says.
    #[expect(clippy::too_many_arguments, reason = "the dispatch's inputs, each used once")]
    pub(crate) fn plan<'a>(
        device: &wgpu::Device,
        cells: &'a PosedCells,
        targets: &'a PositionTargets,
        range: &Range<u32>,
        count: u32,
        numbering: Numbering,
        limits: &ChunkLimits,
        group_of: impl Fn(
            &wgpu::Buffer,
            wgpu::BindingResource<'a>,
            usize,
            &Range<u32>,
            wgpu::BindingResource<'a>,
        ) -> wgpu::BindGroup,
    ) -> Vec<InstanceDispatch> {
        targets
            .groups
            .iter()
            .map(|group| {
                let params = InstanceParams {
                    vertex_count: count,
                    cells_per_instance: cells.per_instance,
                    instance_stride: 3 * targets.stride,
                    first_instance: group.start,
                    instance_count: group.len() as u32,
                    ..Default::default()
                };
                let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sweepffd instance params"),
                    contents: bytemuck::bytes_of(&params),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                });
                let groups = (0..targets.buffers.len())
                    .map(|parity| {
                        group_of(&params, cells.binding(), parity, group, targets.window(parity, range, group))
                    })
                    .collect();
                let grid = match numbering {
                    Numbering::Layered => {
                        let (x, y) = dispatch_grid(count, limits);
                        (x, y, group.len() as u32)
                    }
                    // count · instances stays below 2^32: their positions fit one binding.
                    Numbering::Flat => {
                        let invocations = count * numbering.dispatch_shape(group.len() as u32).0;
                        let (x, y) = dispatch_grid(invocations, limits);
                        (x, y, 1)
                    }
                };
                InstanceDispatch { groups, grid, params, indirect: None }
            })
            .collect()
    }

    /// Records the dispatch writing position buffer `parity` (its pipeline already set).
    pub(crate) fn encode(&self, pass: &mut wgpu::ComputePass, parity: usize) {
        pass.set_bind_group(0, &self.groups[parity], &[]);
        match &self.indirect {
            Some((buffer, offset)) => pass.dispatch_workgroups_indirect(buffer, *offset),
            None => pass.dispatch_workgroups(self.grid.0, self.grid.1, self.grid.2),
        }
    }
}
