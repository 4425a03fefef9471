//! The normals pass: area-weighted vertex normals of the deformed mesh, gathered per vertex
//! from its incident triangles (`shaders/normals.wgsl`), in chunks that respect the device's
//! binding limits. With instances, each instance's normals are laid out like its positions
//! (at the same byte offsets), one set of dispatches per instance and position buffer.

use wgpu::util::DeviceExt;

use std::sync::Arc;

use super::buffers::{POSITION_STRIDE, check_fits, params_buffer};
use super::chunks::{ChunkLimits, dispatch_grid, normal_chunks};
use super::kernels::Kernel;
use super::{GpuContext, GpuError};
use crate::coeffs::DispatchParams;
use crate::mesh::Faces;
use crate::normals::NormalAdjacency;

/// The normals pass: its kernel, output buffer and dispatches (`dispatches[p]` read position
/// buffer p).
#[derive(Debug)]
pub(crate) struct NormalsStage {
    pub(crate) kernel: Arc<Kernel>,
    pub(crate) buffer: wgpu::Buffer,
    pub(crate) dispatches: Vec<Vec<(wgpu::BindGroup, (u32, u32))>>,
}

impl NormalsStage {
    pub(crate) fn new(
        context: &GpuContext,
        faces: &Faces,
        positions: &[wgpu::Buffer],
        positions_base: u64,
        instance_offsets: &[u64],
        vertex_count: u32,
        limits: &ChunkLimits,
    ) -> Result<NormalsStage, GpuError> {
        let device = &context.device;
        let adjacency = NormalAdjacency::new(faces, vertex_count as usize);
        let entry_bytes = size_of::<u32>() as u64;
        let chunks = normal_chunks(&adjacency.offsets, entry_bytes, limits).ok_or_else(|| {
            GpuError::Input("a vertex has more incident triangles than one storage binding holds".into())
        })?;
        // Positions are read at any index, through two windows of at most one binding each; the
        // second starts at a multiple of 64 vertices (768 bytes), aligned for any device.
        let split =
            (limits.max_binding.min(limits.max_buffer) / POSITION_STRIDE / 64 * 64).min(vertex_count as u64) as u32;
        check_fits(
            "the normals' second position window",
            (vertex_count - split) as u64 * POSITION_STRIDE,
            limits.max_binding,
        )?;
        let last = instance_offsets.last().copied().unwrap_or(0);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd normals"),
            size: last + vertex_count as u64 * POSITION_STRIDE,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let kernel = context.kernels().normals(device, split < vertex_count);
        let tables: Vec<_> = chunks
            .iter()
            .map(|range| {
                let first = adjacency.offsets[range.start as usize];
                let offsets: Vec<u32> =
                    adjacency.offsets[range.start as usize..=range.end as usize].iter().map(|o| o - first).collect();
                let fans = &adjacency.fans[first as usize..adjacency.offsets[range.end as usize] as usize];
                // A binding may not be empty: a chunk without triangles gets one unused entry.
                let fans: &[u32] = if fans.is_empty() { &[0] } else { fans };
                let storage = |label, bytes: &[u8]| {
                    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(label),
                        contents: bytes,
                        usage: wgpu::BufferUsages::STORAGE,
                    })
                };
                let offsets = storage("sweepffd normal offsets", bytemuck::cast_slice(&offsets));
                let fans = storage("sweepffd normal fans", bytemuck::cast_slice(fans));
                let params = params_buffer(
                    device,
                    DispatchParams {
                        vertex_count: range.len() as u32,
                        first_vertex: range.start,
                        window_split: split,
                        _pad: 0,
                    },
                );
                (range.clone(), params, offsets, fans)
            })
            .collect();
        let dispatches = positions
            .iter()
            .map(|positions| {
                let mut dispatches = Vec::with_capacity(instance_offsets.len() * tables.len());
                for &base in instance_offsets {
                    let low = at(positions, positions_base + base, split.max(1));
                    let high = if split < vertex_count {
                        at(positions, positions_base + base + split as u64 * POSITION_STRIDE, vertex_count - split)
                    } else {
                        low.clone()
                    };
                    for (range, params, offsets, fans) in &tables {
                        let first = base + range.start as u64 * POSITION_STRIDE;
                        let group = kernel.bind_group(
                            device,
                            "sweepffd normals",
                            &[
                                params.as_entire_binding(),
                                low.clone(),
                                high.clone(),
                                offsets.as_entire_binding(),
                                fans.as_entire_binding(),
                                at(&buffer, first, range.len() as u32),
                            ],
                        );
                        dispatches.push((group, dispatch_grid(range.len() as u32, limits)));
                    }
                }
                dispatches
            })
            .collect();
        Ok(NormalsStage { kernel, buffer, dispatches })
    }
}

/// The window of `vertices` positions (or normals) of `buffer` starting at byte `first`.
fn at(buffer: &wgpu::Buffer, first: u64, vertices: u32) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: first,
        size: wgpu::BufferSize::new(vertices as u64 * POSITION_STRIDE),
    })
}
