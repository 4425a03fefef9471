//! An application's vertex buffer for the tests of output into the app's buffers: `bytes`
//! bytes of positions from `offset` on, 64 more past them, every byte a sentinel until the
//! deformer writes it.

use sweepffd::gpu::{GpuContext, read_bytes};

/// The byte every test app buffer starts filled with.
pub const SENTINEL: u8 = 0xa5;

/// A `VERTEX | STORAGE | COPY_DST | COPY_SRC` buffer of `offset + bytes + 64` bytes, filled with
/// [`SENTINEL`].
pub fn app_buffer(context: &GpuContext, offset: u64, bytes: u64) -> wgpu::Buffer {
    let buffer = context.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("an app's vertex buffer"),
        size: offset + bytes + 64,
        usage: wgpu::BufferUsages::VERTEX
            | wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    context.queue.write_buffer(&buffer, 0, &vec![SENTINEL; buffer.size() as usize]);
    buffer
}

/// Asserts that nothing outside `offset .. offset + bytes` of `buffer` was written.
pub fn assert_untouched_around(context: &GpuContext, buffer: &wgpu::Buffer, offset: u64, bytes: u64) {
    let all = read_bytes(context, buffer, 0, buffer.size()).unwrap();
    assert!(all[..offset as usize].iter().all(|&b| b == SENTINEL), "bytes before the offset were written");
    assert!(all[(offset + bytes) as usize..].iter().all(|&b| b == SENTINEL), "bytes past the positions were written");
}
