//! Timing compute passes with timestamp queries.

use crate::gpu::{GpuContext, GpuError, read_bytes};

/// Two timestamps around one compute pass, resolved and read back.
#[derive(Debug)]
pub struct GpuTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
}

impl GpuTimer {
    /// A timer, or `None` if the device lacks timestamp queries.
    pub fn new(context: &GpuContext) -> Option<GpuTimer> {
        if !context.has_timestamps() {
            return None;
        }
        let device = &context.device;
        let queries = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("sweepffd timer"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd timer resolve"),
            size: 16,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Some(GpuTimer { queries, resolve })
    }

    /// Timestamp writes for a pass: `first` writes the start, `last` the end (both for a single
    /// pass; a run of passes gives the first and the last their part).
    pub fn writes(&self, first: bool, last: bool) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        (first || last).then_some(wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: first.then_some(0),
            end_of_pass_write_index: last.then_some(1),
        })
    }

    /// Records the resolution of both timestamps; call after the timed passes.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..2, &self.resolve, 0);
    }

    /// The seconds between the two timestamps, once the work has been submitted.
    pub fn seconds(&self, context: &GpuContext) -> Result<f64, GpuError> {
        let bytes = read_bytes(context, &self.resolve, 0, 16)?;
        let ticks: [u64; 2] = bytemuck::pod_read_unaligned(&bytes);
        let period = context.queue.get_timestamp_period() as f64;
        Ok(ticks[1].saturating_sub(ticks[0]) as f64 * period * 1e-9)
    }
}
