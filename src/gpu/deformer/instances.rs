//! Instances: one bound mesh deformed by N poses in one dispatch.
//!
//! Data flow: posed sweeps → **cell records of every instance** (copied in by each encode from
//! a staging buffer, [`PoseUploads`](super::uploads::PoseUploads)) → deform and band dispatches
//! over (vertices × instances) → positions, instance i at [`PositionTargets::instance_offset`].
//!
//! The instanced deform kernel reads the records through one binding when they fit, else
//! through uniform windows of a few whole instances each ([`CellLayout`]), one dispatch a
//! window.

use std::ops::Range;

use wgpu::util::DeviceExt;

use super::super::buffers::POSITION_STRIDE;
use super::super::chunks::{ChunkLimits, dispatch_grid};
use super::super::kernels::DeformVariant;
use crate::coeffs::{CellCoeffs, INSTANCES_PER_INVOCATION, InstanceParams, UNIFORM_CELL_CAPACITY};

/// With several instances each instance's positions start a multiple of this many vertices
/// apart (64 × 12 bytes = 3 × 256), so every instance's windows are aligned on any device.
pub const INSTANCE_ALIGNMENT: u32 = 64;

/// With cell windows, each instance's cell records start a multiple of this many records apart
/// (8 × 160 bytes = 5 × 256), so that a uniform window can start at any instance on any device.
pub(crate) const CELL_ALIGNMENT: u32 = 8;

/// How the per-frame cell records of every instance are laid out and read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CellLayout {
    /// Where the kernels read them from.
    pub(crate) variant: DeformVariant,
    /// Records from one instance's first to the next's: the rig's cell count, rounded up to
    /// [`CELL_ALIGNMENT`] with windows.
    pub(crate) stride: u32,
    /// With the instanced deform kernel reading every instance's records from a storage buffer
    /// too large for one uniform binding: the instances of each uniform window it reads instead.
    pub(crate) window_instances: Option<u32>,
}

impl CellLayout {
    /// The layout of `instances` instances of `cells` records each on a device with `limits`.
    /// With several instances whose records overflow a uniform binding but one instance's fit
    /// it, the plain instanced kernel (`flat`) reads uniform windows of as many instances as fit:
    /// on lavapipe a storage read of the records costs about 1.7 times a uniform one, and the
    /// records are most of what the kernel reads.
    pub(crate) fn new(cells: usize, instances: u32, flat: bool, limits: &wgpu::Limits) -> CellLayout {
        let variant = DeformVariant::for_cells(cells * instances as usize, limits);
        let padded = cells.next_multiple_of(CELL_ALIGNMENT as usize);
        let windowed = flat
            && instances > 1
            && variant == DeformVariant::Storage
            && DeformVariant::for_cells(padded, limits) == DeformVariant::Uniform;
        match windowed {
            true => CellLayout {
                variant,
                stride: padded as u32,
                window_instances: Some(UNIFORM_CELL_CAPACITY / padded as u32),
            },
            false => CellLayout { variant, stride: cells as u32, window_instances: None },
        }
    }

    /// The records of `instances` instances, each a copy of `rest` at its stride (zeros between).
    pub(crate) fn image(&self, rest: &[CellCoeffs], instances: u32) -> Vec<CellCoeffs> {
        let mut image = vec![CellCoeffs::default(); self.stride as usize * instances as usize];
        for instance in image.chunks_exact_mut(self.stride as usize) {
            instance[..rest.len()].copy_from_slice(rest);
        }
        image
    }
}

/// The per-frame cell records of every instance, instance i at i × the layout's stride.
#[derive(Debug)]
pub(crate) struct PosedCells {
    pub(crate) buffer: wgpu::Buffer,
    /// Bytes of the records of every instance.
    pub(crate) used_bytes: u64,
    /// Bytes of the binding (the uniform array's size for the uniform variant).
    binding_bytes: u64,
    pub(crate) layout: CellLayout,
}

impl PosedCells {
    /// The records `image` of every instance (see [`CellLayout::image`]), laid out as `layout`.
    pub(crate) fn new(device: &wgpu::Device, image: &[CellCoeffs], layout: CellLayout) -> PosedCells {
        let record = size_of::<CellCoeffs>() as u64;
        let used_bytes = image.len() as u64 * record;
        let window = UNIFORM_CELL_CAPACITY as u64 * record;
        let binding_bytes = match layout.variant {
            DeformVariant::Uniform => window,
            DeformVariant::Storage => used_bytes,
        };
        // The last window reaches a whole uniform array past its first instance's records.
        let instances = image.len() as u64 / layout.stride.max(1) as u64;
        let last_window = layout.window_instances.map_or(0, |w| {
            let first = instances.saturating_sub(1) / w as u64 * w as u64;
            first * layout.stride as u64 * record + window
        });
        let mut contents = vec![0u8; binding_bytes.max(last_window) as usize];
        contents[..used_bytes as usize].copy_from_slice(bytemuck::cast_slice(image));
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd posed cells"),
            contents: &contents,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        });
        PosedCells { buffer, used_bytes, binding_bytes, layout }
    }

    /// The uniform window of the records from instance `first` on.
    fn window(&self, first: u32) -> wgpu::BindingResource<'_> {
        let record = size_of::<CellCoeffs>() as u64;
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &self.buffer,
            offset: first as u64 * self.layout.stride as u64 * record,
            size: wgpu::BufferSize::new(UNIFORM_CELL_CAPACITY as u64 * record),
        })
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

/// One dispatch over some instances: a bind group per position buffer (`parity`).
#[derive(Debug)]
pub(crate) struct InstanceDispatch {
    groups: Vec<wgpu::BindGroup>,
    grid: (u32, u32, u32),
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
        // The instanced kernel's uniform windows split each group further.
        let windows = cells.layout.window_instances.filter(|_| numbering == Numbering::Flat);
        let groups: Vec<Range<u32>> = match windows {
            Some(w) => targets
                .groups
                .iter()
                .flat_map(|g| g.clone().step_by(w as usize).map(move |first| first..(first + w).min(g.end)))
                .collect(),
            None => targets.groups.clone(),
        };
        groups
            .iter()
            .map(|group| {
                // A window's records start at its first instance's.
                let (cells_binding, first_instance) = match windows {
                    Some(_) => (cells.window(group.start), 0),
                    None => (cells.binding(), group.start),
                };
                let params = InstanceParams {
                    vertex_count: count,
                    cells_per_instance: cells.layout.stride,
                    instance_stride: 3 * targets.stride,
                    first_instance,
                    instance_count: group.len() as u32,
                    ..Default::default()
                };
                let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sweepffd instance params"),
                    contents: bytemuck::bytes_of(&params),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let groups = (0..targets.buffers.len())
                    .map(|parity| {
                        let positions = targets.window(parity, range, group);
                        group_of(&params, cells_binding.clone(), parity, group, positions)
                    })
                    .collect();
                let grid = match numbering {
                    Numbering::Layered => {
                        let (x, y) = dispatch_grid(count, limits);
                        (x, y, group.len() as u32)
                    }
                    // count · instances stays below 2^32: their positions fit one binding.
                    Numbering::Flat => {
                        let invocations = count * (group.len() as u32).div_ceil(INSTANCES_PER_INVOCATION);
                        let (x, y) = dispatch_grid(invocations, limits);
                        (x, y, 1)
                    }
                };
                InstanceDispatch { groups, grid }
            })
            .collect()
    }

    /// Records the dispatch writing position buffer `parity` (its pipeline already set).
    pub(crate) fn encode(&self, pass: &mut wgpu::ComputePass, parity: usize) {
        pass.set_bind_group(0, &self.groups[parity], &[]);
        pass.dispatch_workgroups(self.grid.0, self.grid.1, self.grid.2);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instances_overflowing_a_uniform_binding_get_aligned_windows_of_whole_instances() {
        let limits = wgpu::Limits::default();
        // 49 cells: padded to 56, 7 instances a window; every window starts 256-byte aligned.
        let layout = CellLayout::new(49, 23, true, &limits);
        assert_eq!(layout, CellLayout { variant: DeformVariant::Storage, stride: 56, window_instances: Some(7) });
        assert_eq!(layout.stride as usize * size_of::<CellCoeffs>() % 256, 0);
        let rest: Vec<CellCoeffs> = (0..49).map(|i| CellCoeffs { dq: [i as f32; 4], ..Default::default() }).collect();
        let image = layout.image(&rest, 23);
        assert_eq!(image.len(), 23 * 56);
        assert!(image[56..56 + 49] == rest[..] && image[49..56].iter().all(|c| *c == CellCoeffs::default()));
        // Few instances fit one uniform binding, the fused kernel and one instance read as
        // before, and an instance too large for a window reads storage.
        for (cells, instances, flat) in [(49, 8, true), (49, 23, false), (49, 1, true), (410, 2, true)] {
            let layout = CellLayout::new(cells, instances, flat, &limits);
            assert_eq!((layout.stride, layout.window_instances), (cells as u32, None), "{cells} × {instances}");
        }
        // A device without 64 KiB uniform bindings reads storage.
        let small = wgpu::Limits { max_uniform_buffer_binding_size: 16 << 10, ..limits };
        assert_eq!(CellLayout::new(49, 23, true, &small).window_instances, None);
    }
}
