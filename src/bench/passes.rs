//! Timing GPU passes for the bench: a pipeline's dispatches recorded as one pass, submitted and
//! timed with timestamp queries where the device has them (wall-clock otherwise).

use std::ops::Range;
use std::time::Instant;

use super::GpuTimer;
use crate::coeffs::DispatchParams;
use crate::gpu::buffers::params_buffer;
use crate::gpu::kernels;
use crate::gpu::{GpuContext, GpuError, wait};

/// A pipeline's dispatches, one per chunk.
pub(super) type Dispatches = (kernels::Kernel, Vec<(wgpu::BindGroup, (u32, u32))>);

/// Records with `record`, submits, waits, and returns the timestamped seconds (wall-clock
/// without timestamp queries).
pub(super) fn time(
    context: &GpuContext,
    timer: Option<&GpuTimer>,
    record: impl FnOnce(&mut wgpu::CommandEncoder, Option<&GpuTimer>),
) -> Result<f64, GpuError> {
    let device = &context.device;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd bench") });
    let start = Instant::now();
    record(&mut encoder, timer);
    if let Some(timer) = timer {
        timer.resolve(&mut encoder);
    }
    context.queue.submit([encoder.finish()]);
    wait(context)?;
    let wall = start.elapsed().as_secs_f64();
    match timer {
        Some(timer) => timer.seconds(context),
        None => Ok(wall),
    }
}

pub(super) fn chunk_params(device: &wgpu::Device, range: &Range<u32>) -> wgpu::Buffer {
    params_buffer(device, DispatchParams { vertex_count: range.len() as u32, ..Default::default() })
}

/// Records one pass over all of a pipeline's dispatches.
pub(super) fn encode(encoder: &mut wgpu::CommandEncoder, (kernel, dispatches): &Dispatches, timer: Option<&GpuTimer>) {
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some("sweepffd bench"),
        timestamp_writes: timer.and_then(|t| t.writes(true, true)),
    });
    pass.set_pipeline(&kernel.pipeline);
    for (group, grid) in dispatches {
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(grid.0, grid.1, 1);
    }
}
