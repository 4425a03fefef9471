//! CPU throughput of binding and deformation on a synthetic tube (the fast f32 path of
//! `--backend cpu`, the f64 reference path of `--backend reference` and the f32 twin of the GPU
//! kernels), with a memory-copy and a four-influence linear-blend-skinning baseline measured in
//! the same run, the fused deform with Jacobian normals (fast and twin) beside them, and of the
//! falloff bands of binding, with the normals' adjacency build as the baseline.
//!
//! `cargo bench --features internals --bench cpu`; criterion reports vertices per second (throughput elements).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use sweepffd::bench::{skinning_influences, skinning_joints};
use sweepffd::bind::falloff::band_weights;
use sweepffd::bind::{UNOWNED, bind_vertices};
use sweepffd::coeffs::{GpuBinding, SweepCoefficients, bind_segments};
use sweepffd::cpu;
use sweepffd::cpu_fast;
use sweepffd::deform::deform_vertices;
use sweepffd::mesh::Mesh;
use sweepffd::normals::NormalAdjacency;
use sweepffd::rig::Rig;
use sweepffd::sweep::Sweep;
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

struct Scene {
    mesh: Mesh,
    rig: Rig,
    owners: Vec<u32>,
    posed: Vec<Sweep>,
}

fn scene(vertices: usize) -> Scene {
    let tube = Tube::with_vertex_count(vertices, 4.0, 0.5);
    let mesh = tube.mesh();
    let rig = tube_rig(&tube, 8, 16);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let pose = BendTwistTaper { bend: 1.5, twist: 2.0, taper: 0.5 };
    let posed = rig.pose(&pose.keys(&rig)).unwrap();
    Scene { mesh, rig, owners, posed }
}

/// The rest vertex normals of `mesh` (the normals kernel's twin), tightly packed.
fn rest_normals(mesh: &Mesh) -> Vec<f32> {
    let positions = cpu::packed(&mesh.positions);
    let mut normals = vec![0.0; positions.len()];
    cpu::normals::normals(&positions, &NormalAdjacency::new(&mesh.faces, mesh.positions.len()), &mut normals);
    normals
}

fn bind(c: &mut Criterion) {
    let mut group = c.benchmark_group("bind");
    group.sample_size(10);
    for n in [100_000, 1_000_000, 4_000_000] {
        let scene = scene(n);
        group.throughput(Throughput::Elements(scene.mesh.positions.len() as u64));
        group.bench_function(BenchmarkId::new("f64", n), |b| {
            b.iter(|| bind_vertices(scene.rig.rest(), &scene.owners, &scene.mesh.positions, &|_| {}))
        });
        let coefficients = SweepCoefficients::new(scene.rig.rest());
        let tables = bind_segments(scene.rig.rest());
        let inputs =
            cpu::bind::BindInputs { cells: &coefficients.cells, bind_segments: &tables, sweeps: &coefficients.sweeps };
        let positions = cpu::packed(&scene.mesh.positions);
        group.bench_function(BenchmarkId::new("f32_twin", n), |b| {
            b.iter(|| cpu::bind::bind(&inputs, &scene.owners, &positions))
        });
        let mut out = vec![GpuBinding::default(); scene.owners.len()];
        group.bench_function(BenchmarkId::new("fast", n), |b| {
            b.iter(|| cpu_fast::bind::bind(&inputs, &scene.owners, &positions, &mut out))
        });
    }
    group.finish();
}

fn deform(c: &mut Criterion) {
    let mut group = c.benchmark_group("deform");
    for n in [100_000, 1_000_000, 4_000_000] {
        let scene = scene(n);
        let count = scene.mesh.positions.len();
        group.throughput(Throughput::Elements(count as u64));
        let bindings = scene.rig.bind_mesh(&scene.mesh, &scene.owners, &|_| {});
        let mut out = vec![DVec3::ZERO; count];
        group.bench_function(BenchmarkId::new("f64", n), |b| {
            b.iter(|| deform_vertices(scene.rig.rest(), &scene.posed, &bindings, &scene.mesh.positions, &mut out))
        });
        let mut coefficients = SweepCoefficients::new(scene.rig.rest());
        let positions = cpu::packed(&scene.mesh.positions);
        let gpu_bindings = cpu::bind::bind_to(scene.rig.rest(), &scene.owners, &positions);
        coefficients.update(&scene.posed).unwrap();
        let mut out32 = positions.clone();
        group.bench_function(BenchmarkId::new("f32_twin", n), |b| {
            b.iter(|| cpu::deform::deform(&coefficients.cells, &gpu_bindings, &mut out32))
        });
        group.bench_function(BenchmarkId::new("fast", n), |b| {
            b.iter(|| cpu_fast::deform::deform(&coefficients.cells, &gpu_bindings, &mut out32))
        });
        // Fused with the Jacobian normals, on the fast path and on the twin.
        let rest_normals = rest_normals(&scene.mesh);
        let records =
            cpu::jacobian::coordinates(&SweepCoefficients::new(scene.rig.rest()).cells, &gpu_bindings, &rest_normals);
        let mut normals32 = rest_normals.clone();
        group.bench_function(BenchmarkId::new("fast_normals", n), |b| {
            b.iter(|| {
                cpu_fast::deform::deform_with_normals(
                    &coefficients.cells,
                    &gpu_bindings,
                    &records,
                    &mut out32,
                    &mut normals32,
                )
            })
        });
        group.bench_function(BenchmarkId::new("f32_twin_normals", n), |b| {
            b.iter(|| {
                cpu::deform::deform_with_normals(
                    &coefficients.cells,
                    &gpu_bindings,
                    &records,
                    &mut out32,
                    &mut normals32,
                )
            })
        });
        // Baseline: four-influence linear-blend skinning (the f32 twin of the GPU baseline).
        let (joints, influences) = (skinning_joints(), skinning_influences(count));
        group.bench_function(BenchmarkId::new("lbs_baseline", n), |b| {
            b.iter(|| cpu::skinning::skinning(&joints, &positions, &influences, &mut out32))
        });
        // Baseline: moving the bytes the f64 path reads and writes, with no arithmetic.
        let source = scene.mesh.positions.clone();
        group.bench_function(BenchmarkId::new("copy_baseline", n), |b| b.iter(|| out.copy_from_slice(&source)));
    }
    group.finish();
}

fn falloff(c: &mut Criterion) {
    let mut group = c.benchmark_group("falloff");
    group.sample_size(10);
    for n in [100_000, 1_000_000] {
        // A tube of quads, length 4: its lower half is one sweep's with W = 1, so the band
        // (1 ≤ z < 2) is a quarter of the mesh.
        let mesh = Tube::with_vertex_count(n, 4.0, 0.5).mesh();
        let owners: Vec<u32> = mesh.positions.iter().map(|p| if p.z < 2.0 { 0 } else { UNOWNED }).collect();
        let count = mesh.positions.len();
        group.throughput(Throughput::Elements(count as u64));
        group.bench_function(BenchmarkId::new("band_weights", n), |b| {
            b.iter(|| band_weights(&mesh.faces, &mesh.positions, &owners, &[1.0]))
        });
        // Baseline: the per-vertex adjacency the normals build for the same mesh.
        group.bench_function(BenchmarkId::new("normal_adjacency_baseline", n), |b| {
            b.iter(|| NormalAdjacency::new(&mesh.faces, count))
        });
    }
    group.finish();
}

criterion_group!(benches, bind, deform, falloff);
criterion_main!(benches);
