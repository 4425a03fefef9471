//! How close the GPU passes come to the hardware: the bytes each pass moves a vertex, the rate
//! it moves them at, and that rate as a share of two ceilings measured in the same rounds: the
//! copy kernel (moving the deform kernel's bytes with no arithmetic) and a whole-buffer copy
//! (`copy_buffer_to_buffer`, the copy engine's rate, bytes read plus bytes written).

use serde::Serialize;

use super::GpuTimer;
use super::passes::{Stamps, stamp, time};
use crate::gpu::{GpuContext, GpuError};

/// Bytes a whole-buffer copy moves at most: it measures a rate, which a few hundred megabytes
/// reach on any device.
const MAX_COPY_BYTES: u64 = 1 << 28;

/// One pass's traffic.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PassTraffic {
    /// `"deform"`, `"copy kernel"`, `"lbs"`, `"bands (rest)"`, `"bands (sweep)"`, `"normals"`,
    /// `"fused"` or `"bind"`.
    pub pass: String,
    /// Bytes the pass reads and writes a vertex of the mesh, each buffer counted once (a lower
    /// bound: gathers and partial cache lines move more).
    pub bytes_per_vertex: f64,
    /// Gigabytes (10⁹ bytes) a second: bytes a vertex × vertices ÷ the pass's time.
    pub gb_per_s: f64,
    /// That rate over the copy kernel's, same round.
    pub of_copy_kernel: f64,
    /// That rate over the whole-buffer copy's, same round.
    pub of_buffer_copy: f64,
}

/// The ceilings and every pass's traffic (`null` on the CPU).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MemoryReport {
    /// `copy_buffer_to_buffer` of one buffer into another, bytes read plus written, GB/s.
    pub buffer_copy_gb_per_s: f64,
    /// The copy kernel, GB/s.
    pub copy_kernel_gb_per_s: f64,
    /// Each pass.
    pub passes: Vec<PassTraffic>,
}

/// A pass's bytes a vertex and its time in each round, with the ceilings' times in the same
/// rounds.
#[derive(Clone)]
pub(super) struct PassTimes {
    pub pass: &'static str,
    pub bytes_per_vertex: f64,
    pub seconds: Vec<f64>,
}

impl MemoryReport {
    /// The report of `passes` over `n` vertices, given the copy kernel's bytes a vertex and its
    /// time, and the whole-buffer copy's rate (bytes a second), each round.
    pub(super) fn new(n: f64, copy: &PassTimes, buffer_copy: &[f64], passes: &[PassTimes]) -> MemoryReport {
        let rate = |p: &PassTimes, round: usize| p.bytes_per_vertex * n / p.seconds[round];
        let rounds = copy.seconds.len();
        let median = |f: &dyn Fn(usize) -> f64| super::median(&mut (0..rounds).map(f).collect::<Vec<_>>());
        let passes = passes
            .iter()
            .map(|p| PassTraffic {
                pass: p.pass.to_string(),
                bytes_per_vertex: p.bytes_per_vertex,
                gb_per_s: median(&|r| rate(p, r)) * 1e-9,
                of_copy_kernel: median(&|r| rate(p, r) / rate(copy, r)),
                of_buffer_copy: median(&|r| rate(p, r) / buffer_copy[r]),
            })
            .collect();
        MemoryReport {
            buffer_copy_gb_per_s: median(&|r| buffer_copy[r]) * 1e-9,
            copy_kernel_gb_per_s: median(&|r| rate(copy, r)) * 1e-9,
            passes,
        }
    }
}

/// Two buffers for the whole-buffer copy.
pub(super) struct BufferCopy {
    from: wgpu::Buffer,
    to: wgpu::Buffer,
}

impl BufferCopy {
    /// Buffers of `bytes` (at most [`MAX_COPY_BYTES`] and the device's largest buffer).
    pub(super) fn new(context: &GpuContext, bytes: u64) -> BufferCopy {
        let limit = context.device.limits().max_buffer_size;
        let size = bytes.min(MAX_COPY_BYTES).min(limit) / 4 * 4;
        let buffer = |label, usage| {
            context.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        BufferCopy {
            from: buffer("sweepffd bench copy source", wgpu::BufferUsages::COPY_SRC),
            to: buffer("sweepffd bench copy target", wgpu::BufferUsages::COPY_DST),
        }
    }

    /// Bytes one copy reads and writes.
    pub(super) fn bytes(&self) -> f64 {
        2.0 * self.from.size() as f64
    }

    /// Seconds of one copy.
    pub(super) fn seconds(&self, context: &GpuContext, timer: Option<&GpuTimer>) -> Result<f64, GpuError> {
        let size = self.from.size();
        time(context, timer, |encoder, stamps: Stamps| {
            if let Some(writes) = stamps.opening() {
                stamp(encoder, Some(writes));
            }
            encoder.copy_buffer_to_buffer(&self.from, 0, &self.to, 0, size);
            if let Some(writes) = stamps.closing() {
                stamp(encoder, Some(writes));
            }
        })
    }
}
