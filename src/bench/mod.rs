//! Throughput measurements behind `sweepffd bench` and the criterion benches: binding and
//! deformation against baselines measured in the same run on the same device — a copy kernel
//! moving the deform kernel's bytes (the memory ceiling) and four-influence linear-blend
//! skinning (what real-time applications use today).
//!
//! Every figure is the median of several runs after warm-up; GPU kernel times come from
//! timestamp queries over [`REPEATS`] passes back to back (one on a CPU adapter) where the
//! device supports them, wall-clock otherwise.

mod alternatives;
mod cpu;
mod creation;
mod engine;
mod frame;
mod fused;
mod gpu;
mod passes;
mod scene;
mod size;
mod skinning;
mod timer;
mod traffic;

use serde::Serialize;

pub use alternatives::AlternativeReport;
pub use cpu::CpuBench;
pub use creation::CreationReport;
pub use engine::{INSTANCES, PARTIAL_SHARE};
pub use frame::{FRAME_CPU_FRAMES, FRAME_WARMUP, FrameBench, host_frame_seconds, median_host_frame_ms};
pub use gpu::GpuBench;
pub use passes::{REPEATS, repeats};
pub use scene::{BAND_FRACTION, BenchScene, FalloffKind};
pub use size::{BenchSizeError, MIN_BENCH_VERTICES, check_runs, gpu_vertex_limit, tube_vertex_count};
pub use skinning::{skinning_influences, skinning_joints};
pub use timer::GpuTimer;
pub use traffic::{MemoryReport, PassTraffic};

/// One bench run's results, printed by `sweepffd bench --json` as one JSON line.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchReport {
    /// `"gpu"` or `"cpu"`.
    pub backend: &'static str,
    /// The GPU adapter, or the CPU's thread count.
    pub adapter: String,
    /// Number of vertices.
    pub n: usize,
    /// Where the deformer's kernels read the cell records from, as chosen for the adapter:
    /// `"uniform"` or `"storage"` (`null` on the CPU).
    pub cell_records: Option<&'static str>,
    /// Which vertices an invocation of the deform kernel deforms, as chosen for the adapter:
    /// `"vertices"` or `"cell groups"` (`null` on the CPU).
    pub deform_order: Option<&'static str>,
    /// Vertices bound per second.
    pub bind_verts_per_s: f64,
    /// Vertices deformed per second (deform kernel alone).
    pub deform_verts_per_s: f64,
    /// Vertices per second of the copy baseline.
    pub copy_verts_per_s: f64,
    /// Vertices per second of the linear-blend-skinning baseline.
    pub lbs_verts_per_s: f64,
    /// Deform time over copy time (1 is the memory ceiling).
    pub deform_over_copy: f64,
    /// Deform time over skinning time.
    pub deform_over_lbs: f64,
    /// The CPU backend's fast f32 path against the f64 reference in the same rounds (`null` on
    /// the GPU): there `bind_verts_per_s` and `deform_verts_per_s` are the fast path's.
    pub cpu: Option<CpuPathReport>,
    /// One frame: the rig posed from keys, its coefficients, their upload and the deform
    /// dispatch, waited for, no readback; milliseconds.
    pub frame_ms: f64,
    /// The host's share of a frame: `Rig::pose_into`, `GpuDeformer::set_pose` and
    /// `GpuDeformer::encode` (deform and normals passes) into an encoder made before, median
    /// of [`FRAME_CPU_FRAMES`] frames, milliseconds (`null` on the CPU backend).
    pub frame_cpu_ms: Option<f64>,
    /// The normals pass over the deformed mesh, milliseconds (0 on the CPU backend, which does
    /// not compute normals).
    pub normals_ms: f64,
    /// Reading the positions back to the CPU, milliseconds (`null` on the CPU backend).
    pub readback_ms: Option<f64>,
    /// Device memory for bindings and positions, bytes per vertex (`null` on the CPU).
    pub device_bytes_per_vertex: Option<f64>,
    /// The falloff comparisons (none for a mesh and rig of the user's).
    pub falloff: Vec<FalloffReport>,
    /// Deform time of [`INSTANCES`] instances of an n / [`INSTANCES`]-vertex tube over that of
    /// one tube of as many vertices in all, same rig, same round (`null` on the CPU).
    pub instances_over_single: Option<f64>,
    /// Deform and normals time of an n-vertex tube whose rig owns [`PARTIAL_SHARE`] of its
    /// vertices over that of a rig owning every vertex, same round (`null` on the CPU).
    pub partial_over_full: Option<f64>,
    /// The fused deform + Jacobian normals pass over a copy kernel moving as many bytes (a
    /// binding and a normal coordinates record read, a position and a normal written), same
    /// round (`null` on the CPU).
    pub fused_over_copy: Option<f64>,
    /// The fused pass over the deform pass plus the triangle normals pass it replaces, same
    /// round (`null` on the CPU).
    pub fused_over_separate: Option<f64>,
    /// The 99th percentile of the angle between the Jacobian normals and the triangle normals
    /// of the posed scene, over the vertices whose normals the fused kernel writes, degrees
    /// (`null` on the CPU).
    pub normals_angle_p99_deg: Option<f64>,
    /// The deform pass in the orders and with the cell records the adapter did not choose, same
    /// rounds (empty on the CPU).
    pub alternatives: Vec<AlternativeReport>,
    /// Creating the deformers, milliseconds (`null` on the CPU).
    pub creation: Option<CreationReport>,
    /// Bytes a vertex and rates of the GPU passes against the copy kernel and a whole-buffer
    /// copy measured in the same rounds (`null` on the CPU).
    pub memory: Option<MemoryReport>,
    /// Runs each median is taken over.
    pub runs: usize,
    /// Passes each GPU time is taken over, back to back (1 on the CPU backend).
    pub repeats: usize,
    /// Whether GPU times come from timestamp queries.
    pub timestamps: bool,
}

/// The fast CPU path (`--backend cpu`) against the f64 reference (`--backend reference`),
/// measured in the same run as the report's figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CpuPathReport {
    /// The fast path's instruction set: `"avx2+fma"` or `"scalar"`.
    pub isa: &'static str,
    /// Vertices deformed per second by the f64 reference, in the same rounds as the fast path.
    pub reference_deform_verts_per_s: f64,
    /// Vertices bound per second by the f64 reference (with the falloff bands, as `sweepffd bind`).
    pub reference_bind_verts_per_s: f64,
    /// Reference deform time over fast deform time, same round.
    pub reference_over_fast: f64,
}

/// The deform pass with falloff bands against the same mesh without, in the same rounds.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FalloffReport {
    /// What the bands fade into.
    pub kind: FalloffKind,
    /// Share of the vertices in the bands.
    pub band_fraction: f64,
    /// Vertices per second of the deform pass (deform and band kernels) with the bands.
    pub deform_verts_per_s: f64,
    /// Deform time with the bands over deform time without, same round.
    pub over_plain: f64,
    /// Device memory for bindings, positions and band records, bytes per vertex (`null` on
    /// the CPU).
    pub device_bytes_per_vertex: Option<f64>,
}

/// One round of back-to-back timings, seconds.
#[derive(Clone, Debug)]
struct Round {
    deform: f64,
    falloff: Vec<f64>,
    copy: f64,
    lbs: f64,
    frame: f64,
    normals: f64,
    /// Deform pass of the instances and of the single mesh (GPU only).
    instances: (f64, f64),
    /// Deform and normals passes of the partial and the full rig (GPU only).
    partial: (f64, f64),
    /// The fused deform + Jacobian normals pass and its copy baseline (GPU only).
    fused: f64,
    wide_copy: f64,
    /// A whole-buffer copy (GPU only).
    buffer_copy: f64,
    /// The alternatives' deform passes (GPU only).
    alternatives: Vec<f64>,
}

/// The median of `samples` (which it sorts).
pub fn median(samples: &mut [f64]) -> f64 {
    samples.sort_by(f64::total_cmp);
    let n = samples.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 { samples[n / 2] } else { 0.5 * (samples[n / 2 - 1] + samples[n / 2]) }
}

/// Runs `measure` `warmup` times unrecorded, then `runs` times, and returns the median.
pub fn median_of<E>(warmup: usize, runs: usize, mut measure: impl FnMut() -> Result<f64, E>) -> Result<f64, E> {
    for _ in 0..warmup {
        measure()?;
    }
    let mut samples = (0..runs).map(|_| measure()).collect::<Result<Vec<f64>, E>>()?;
    Ok(median(&mut samples))
}

/// The least of `count` measurements.
pub fn best_of<E>(count: usize, mut measure: impl FnMut() -> Result<f64, E>) -> Result<f64, E> {
    let mut best = f64::INFINITY;
    for _ in 0..count.max(1) {
        best = best.min(measure()?);
    }
    Ok(best)
}

/// Times `work` `warmup` times unrecorded, then `runs` times, and returns the median seconds.
pub fn median_seconds(warmup: usize, runs: usize, mut work: impl FnMut()) -> f64 {
    let result: Result<f64, std::convert::Infallible> = median_of(warmup, runs, || {
        let start = std::time::Instant::now();
        work();
        Ok(start.elapsed().as_secs_f64())
    });
    match result {
        Ok(seconds) => seconds,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
    }
}
