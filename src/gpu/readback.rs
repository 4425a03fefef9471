//! Copying a buffer back to the CPU: an explicit, blocking call, never part of a frame.

use std::sync::mpsc;

use super::{GpuContext, GpuError};

/// The bytes `offset..offset + size` of `buffer` (which needs `COPY_SRC`), read through a
/// temporary mappable buffer. Blocks until the GPU has finished all work before the copy.
pub fn read_bytes(context: &GpuContext, buffer: &wgpu::Buffer, offset: u64, size: u64) -> Result<Vec<u8>, GpuError> {
    let device = &context.device;
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("sweepffd readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd readback") });
    encoder.copy_buffer_to_buffer(buffer, offset, &staging, 0, size);
    context.queue.submit([encoder.finish()]);
    read_staging(context, &staging)
}

/// Every byte of `staging` (a `MAP_READ` buffer whose filling commands are submitted): maps it,
/// waits for the GPU, copies the bytes out and unmaps it.
pub fn read_staging(context: &GpuContext, staging: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let slice = staging.slice(..);
    let (sender, receiver) = mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    wait(context)?;
    receiver
        .recv()
        .map_err(|_| GpuError::DeviceLost("the readback was never completed".to_string()))?
        .map_err(|e| GpuError::Validation(format!("mapping the readback buffer failed: {e}")))?;
    let bytes = slice.get_mapped_range().map_err(|e| GpuError::Validation(e.to_string()))?.to_vec();
    staging.unmap();
    Ok(bytes)
}

/// Waits until the GPU has finished every submitted command.
pub fn wait(context: &GpuContext) -> Result<(), GpuError> {
    context.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::DeviceLost(e.to_string()))?;
    context.check_alive()
}
