//! The buffers of the GPU engine and windows onto them: each per-vertex stream is tightly
//! packed, and a chunk of vertices binds the window of each stream that covers it.

use std::ops::Range;

use wgpu::util::DeviceExt;

use super::GpuError;
use super::kernels::DeformVariant;
use crate::coeffs::{CellCoeffs, DispatchParams, GpuBinding, PackedBinding, SweepCoefficients, UNIFORM_CELL_CAPACITY};

/// Bytes per vertex of the position and normal buffers (tightly packed f32 xyz).
pub const POSITION_STRIDE: u64 = 12;
/// Bytes per vertex of the binding buffers ([`PackedBinding`](crate::coeffs::PackedBinding)).
pub const BINDING_STRIDE: u64 = size_of::<PackedBinding>() as u64;

/// `Err(TooLarge)` when `needed` bytes exceed `limit`.
pub(crate) fn check_fits(what: &'static str, needed: u64, limit: u64) -> Result<(), GpuError> {
    if needed > limit { Err(GpuError::TooLarge { what, needed, limit }) } else { Ok(()) }
}

/// The window of a per-vertex stream covering `range`.
pub(crate) fn window<'a>(buffer: &'a wgpu::Buffer, range: &Range<u32>, stride: u64) -> wgpu::BindingResource<'a> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: range.start as u64 * stride,
        size: wgpu::BufferSize::new(range.len() as u64 * stride),
    })
}

/// A uniform buffer holding one dispatch's constants.
pub(crate) fn params_buffer(device: &wgpu::Device, params: DispatchParams) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sweepffd dispatch params"),
        contents: bytemuck::bytes_of(&params),
        usage: wgpu::BufferUsages::UNIFORM,
    })
}

/// Rest positions, tightly packed f32, in the output buffer (unbound vertices keep them).
pub(crate) fn upload_positions(device: &wgpu::Device, positions: &[[f32; 3]]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sweepffd positions"),
        contents: bytemuck::cast_slice(positions),
        usage: wgpu::BufferUsages::VERTEX
            | wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
    })
}

/// The cell records, padded to the uniform array's size for the uniform variant.
pub(crate) fn cells_buffer(
    device: &wgpu::Device,
    coefficients: &SweepCoefficients,
    variant: DeformVariant,
) -> wgpu::Buffer {
    let mut cells = coefficients.cells.clone();
    if variant == DeformVariant::Uniform {
        cells.resize(UNIFORM_CELL_CAPACITY as usize, CellCoeffs::default());
    }
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sweepffd cells"),
        contents: bytemuck::cast_slice(&cells),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
    })
}

/// A binding buffer holding `bindings`, packed.
pub(crate) fn binding_buffer_with(device: &wgpu::Device, bindings: &[GpuBinding]) -> wgpu::Buffer {
    let packed: Vec<PackedBinding> = bindings.iter().map(PackedBinding::pack).collect();
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sweepffd bindings"),
        contents: bytemuck::cast_slice(&packed),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
    })
}

/// A binding buffer for `vertices` vertices, to be filled by the bind kernel.
pub(crate) fn empty_binding_buffer(device: &wgpu::Device, vertices: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("sweepffd bindings"),
        size: vertices as u64 * BINDING_STRIDE,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
