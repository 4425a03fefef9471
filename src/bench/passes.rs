//! Timing GPU passes for the bench: a figure's passes recorded [`repeats`] times back to back in
//! one command buffer, submitted, and timed from the start of the first to the end of the last
//! with timestamp queries where the device has them (wall-clock otherwise), divided by the
//! repeats: one dispatch of a 1M-vertex mesh lasts tens of microseconds on a discrete GPU, as
//! long as the gaps between passes.

use std::ops::Range;
use std::time::Instant;

use super::GpuTimer;
use crate::coeffs::DispatchParams;
use crate::gpu::buffers::params_buffer;
use crate::gpu::kernels;
use crate::gpu::{GpuContext, GpuError, wait};

/// A pipeline's dispatches, one per chunk.
pub(super) type Dispatches = (kernels::Kernel, Vec<(wgpu::BindGroup, (u32, u32))>);

/// Times each figure's passes are recorded in one timed command buffer on a GPU.
pub const REPEATS: usize = 10;

/// Times each figure's passes are recorded in one timed command buffer on `context`'s adapter:
/// [`REPEATS`], or once on a CPU adapter, where one pass over the smallest bench mesh lasts
/// milliseconds.
pub fn repeats(context: &GpuContext) -> usize {
    if context.info.device_type == wgpu::DeviceType::Cpu { 1 } else { REPEATS }
}

/// The timestamp writes one repetition of a figure's passes may make: the first repetition's
/// first pass writes the start, the last repetition's last pass the end.
#[derive(Clone, Copy)]
pub(super) struct Stamps<'a> {
    timer: Option<&'a GpuTimer>,
    first: bool,
    last: bool,
}

impl<'a> Stamps<'a> {
    /// For a repetition of a single pass.
    pub(super) fn pass(self) -> Option<wgpu::ComputePassTimestampWrites<'a>> {
        self.timer.and_then(|t| t.writes(self.first, self.last))
    }

    /// For the first of a repetition's passes.
    pub(super) fn opening(self) -> Option<wgpu::ComputePassTimestampWrites<'a>> {
        self.timer.and_then(|t| t.writes(self.first, false))
    }

    /// For the last of a repetition's passes.
    pub(super) fn closing(self) -> Option<wgpu::ComputePassTimestampWrites<'a>> {
        self.timer.and_then(|t| t.writes(false, self.last))
    }
}

/// Records `record` [`repeats`] times, submits, waits, and returns the timestamped seconds of
/// one repetition (wall-clock without timestamp queries).
pub(super) fn time(
    context: &GpuContext,
    timer: Option<&GpuTimer>,
    mut record: impl FnMut(&mut wgpu::CommandEncoder, Stamps),
) -> Result<f64, GpuError> {
    let device = &context.device;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd bench") });
    let start = Instant::now();
    let repeats = repeats(context);
    for k in 0..repeats {
        record(&mut encoder, Stamps { timer, first: k == 0, last: k == repeats - 1 });
    }
    if let Some(timer) = timer {
        timer.resolve(&mut encoder);
    }
    context.queue.submit([encoder.finish()]);
    wait(context)?;
    let wall = start.elapsed().as_secs_f64();
    let seconds = match timer {
        Some(timer) => timer.seconds(context)?,
        None => wall,
    };
    Ok(seconds / repeats as f64)
}

/// An empty compute pass writing the timestamps of `stamps` (around copies, which make none).
pub(super) fn stamp(encoder: &mut wgpu::CommandEncoder, stamps: Option<wgpu::ComputePassTimestampWrites>) {
    encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some("sweepffd bench stamp"),
        timestamp_writes: stamps,
    });
}

pub(super) fn chunk_params(device: &wgpu::Device, range: &Range<u32>) -> wgpu::Buffer {
    params_buffer(device, DispatchParams { vertex_count: range.len() as u32, ..Default::default() })
}

/// Records one pass over all of a pipeline's dispatches.
pub(super) fn encode(encoder: &mut wgpu::CommandEncoder, (kernel, dispatches): &Dispatches, stamps: Stamps) {
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some("sweepffd bench"),
        timestamp_writes: stamps.pass(),
    });
    pass.set_pipeline(&kernel.pipeline);
    for (group, grid) in dispatches {
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(grid.0, grid.1, 1);
    }
}
