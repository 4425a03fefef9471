//! The normal coordinates of Jacobian normals (`shaders/normal_coords.wgsl`): one 16-byte
//! record per vertex of a deform chunk, made once at creation from the rest cells, the
//! bindings and the rest normals, and read by the fused deform kernel every frame.

use std::ops::Range;

use super::super::GpuContext;
use super::super::buffers::{POSITION_STRIDE, params_buffer};
use super::super::chunks::{ChunkLimits, dispatch_grid};
use super::super::kernels::DeformVariant;
use super::super::normals_pass::record;
use crate::coeffs::DispatchParams;

/// Bytes of one record: m in xyz, the mode in w.
pub const COORDINATES_STRIDE: u64 = 16;

/// One chunk's normal coordinates records.
#[derive(Debug)]
pub(super) struct NormalCoordinates {
    pub(super) buffer: wgpu::Buffer,
}

impl NormalCoordinates {
    /// Room for the records of `vertices` vertices.
    pub(super) fn new(device: &wgpu::Device, vertices: u32) -> NormalCoordinates {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd normal coordinates"),
            size: vertices.max(1) as u64 * COORDINATES_STRIDE,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        NormalCoordinates { buffer }
    }

    /// Records the kernel filling the records of the vertices `range` from the rest cells, the
    /// chunk's bindings and the rest normals (the normals buffer of instance 0, laid out as the
    /// positions from byte 0), after the passes that write those.
    pub(super) fn encode(
        &self,
        context: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        variant: DeformVariant,
        (rest_cells, bindings, rest_normals): (&wgpu::Buffer, &wgpu::Buffer, &wgpu::Buffer),
        range: &Range<u32>,
        limits: &ChunkLimits,
    ) {
        let device = &context.device;
        let kernel = context.kernels().normal_coords(device, variant);
        let count = range.len() as u32;
        let params = DispatchParams { vertex_count: count, first_vertex: range.start, window_split: 0, _pad: 0 };
        let normals = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: rest_normals,
            offset: range.start as u64 * POSITION_STRIDE,
            size: wgpu::BufferSize::new(count as u64 * POSITION_STRIDE),
        });
        let group = kernel.bind_group(
            device,
            "sweepffd normal coordinates",
            &[
                params_buffer(device, params).as_entire_binding(),
                rest_cells.as_entire_binding(),
                bindings.as_entire_binding(),
                normals,
                self.buffer.as_entire_binding(),
            ],
        );
        record(encoder, "sweepffd normal coordinates", &kernel, &[(group, dispatch_grid(count, limits))]);
    }
}
