//! GPU throughput of binding and deformation at 100k, 1M and 4M vertices, with the copy and
//! linear-blend-skinning baselines measured on the same device in the same run. Kernel times
//! come from timestamp queries (wall-clock where the device has none).
//!
//! `frame_cpu` is the host's share of a frame on a 36k-vertex tube bound to two sweeps
//! (`Rig::pose_into`, `set_pose`, `encode`; the target is 0.1 ms), against `pose` — the same
//! frame with the sweeps made anew by `Rig::pose` — measured in the same run.
//!
//! `cargo bench --bench gpu`; without a GPU adapter the benches print why and measure nothing.

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use sweepffd::bench::{BenchScene, FrameBench, GpuBench};
use sweepffd::gpu::{GpuContext, GpuError};

/// Criterion's closure for a kernel timed by `measure`: the sum of `iterations` GPU timings.
fn gpu_time(iterations: u64, mut measure: impl FnMut() -> Result<f64, GpuError>) -> Duration {
    (0..iterations).map(|_| Duration::from_secs_f64(measure().expect("the GPU bench runs"))).sum()
}

fn gpu(c: &mut Criterion) {
    let context = match GpuContext::new() {
        Ok(context) => context,
        Err(error) => {
            eprintln!("skipping the GPU benches: {error}");
            return;
        }
    };
    let mut group = c.benchmark_group(format!("gpu {}", context.info.name));
    group.sample_size(10);
    for n in [100_000, 1_000_000, 4_000_000] {
        let mut bench = GpuBench::new(&context, BenchScene::tube(n)).expect("the GPU bench sets up");
        group.throughput(Throughput::Elements(bench.deformer().vertex_count() as u64));
        // Binding first: it reads the rest positions, which deforming overwrites.
        group.bench_function(BenchmarkId::new("bind", n), |b| b.iter_custom(|i| gpu_time(i, || bench.time_bind())));
        group.bench_function(BenchmarkId::new("deform", n), |b| b.iter_custom(|i| gpu_time(i, || bench.time_deform())));
        group.bench_function(BenchmarkId::new("copy_baseline", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_copy()))
        });
        group.bench_function(BenchmarkId::new("skinning_baseline", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_skinning()))
        });
        group.bench_function(BenchmarkId::new("normals", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_normals()))
        });
        group.bench_function(BenchmarkId::new("deform_jacobian_normals", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_fused()))
        });
        group.bench_function(BenchmarkId::new("copy_wide_baseline", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_wide_copy()))
        });
        // Baselines in the same run: one mesh of as many vertices as the instances together, and
        // a rig owning every vertex.
        group.bench_function(BenchmarkId::new("instances_1000", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_instances().map(|t| t.0)))
        });
        group.bench_function(BenchmarkId::new("instances_single_mesh", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_instances().map(|t| t.1)))
        });
        group.bench_function(BenchmarkId::new("partial_rig_3pct", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_partial().map(|t| t.0)))
        });
        group.bench_function(BenchmarkId::new("partial_full_rig", n), |b| {
            b.iter_custom(|i| gpu_time(i, || bench.time_partial().map(|t| t.1)))
        });
    }
    group.finish();
}

/// The host's share of a frame, with `Rig::pose_into` and, as the baseline, with `Rig::pose`.
fn frame_cpu(c: &mut Criterion) {
    let context = match GpuContext::new() {
        Ok(context) => context,
        Err(error) => {
            eprintln!("skipping the frame_cpu bench: {error}");
            return;
        }
    };
    let context = &context;
    let mut group = c.benchmark_group("frame_cpu");
    let scene = FrameBench::two_sweep_tube(36_000);
    let n = scene.vertex_count();
    let mut bench = FrameBench::new(context, scene).expect("the frame bench sets up");
    group.bench_function(BenchmarkId::new("pose_into", n), |b| {
        b.iter_custom(|i| (0..i).map(|f| Duration::from_secs_f64(bench.time_frame(f).expect("a frame runs"))).sum())
    });
    group.bench_function(BenchmarkId::new("pose", n), |b| {
        b.iter_custom(|i| {
            (0..i).map(|f| Duration::from_secs_f64(bench.time_frame_posing_anew(f).expect("a frame runs"))).sum()
        })
    });
    group.finish();
}

criterion_group!(benches, frame_cpu, gpu);
criterion_main!(benches);
