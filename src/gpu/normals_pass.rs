//! The normals pass: area-weighted vertex normals of the deformed mesh, gathered per vertex
//! from its incident triangles (`shaders/normals.wgsl`), in chunks that respect the device's
//! binding limits.

use wgpu::util::DeviceExt;

use std::sync::Arc;

use super::buffers::{POSITION_STRIDE, check_fits, params_buffer, window};
use super::chunks::{ChunkLimits, dispatch_grid, normal_chunks};
use super::kernels::Kernel;
use super::{GpuContext, GpuError};
use crate::coeffs::DispatchParams;
use crate::mesh::Faces;
use crate::normals::NormalAdjacency;

/// The normals pass: its kernel, output buffer and dispatches.
#[derive(Debug)]
pub(crate) struct NormalsStage {
    pub(crate) kernel: Arc<Kernel>,
    pub(crate) buffer: wgpu::Buffer,
    pub(crate) dispatches: Vec<(wgpu::BindGroup, (u32, u32))>,
}

impl NormalsStage {
    pub(crate) fn new(
        context: &GpuContext,
        faces: &Faces,
        positions: &wgpu::Buffer,
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
        let low = window(positions, &(0..split.max(1)), POSITION_STRIDE);
        let high =
            if split < vertex_count { window(positions, &(split..vertex_count), POSITION_STRIDE) } else { low.clone() };
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd normals"),
            size: vertex_count as u64 * POSITION_STRIDE,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let kernel = context.kernels().normals(device, split < vertex_count);
        let dispatches = chunks
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
                let group = kernel.bind_group(
                    device,
                    "sweepffd normals",
                    &[
                        params.as_entire_binding(),
                        low.clone(),
                        high.clone(),
                        offsets.as_entire_binding(),
                        fans.as_entire_binding(),
                        window(&buffer, range, POSITION_STRIDE),
                    ],
                );
                (group, dispatch_grid(range.len() as u32, limits))
            })
            .collect();
        Ok(NormalsStage { kernel, buffer, dispatches })
    }
}
