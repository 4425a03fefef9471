//! Reading and writing large OBJ and binary PLY files: `Mesh::load` and the faithful
//! `Mesh::save` of a generated tube of 200k vertices (a 15 MB OBJ of shortest round-trip
//! digits), beside the floor of each in the same run: reading the file's bytes, and writing as
//! many bytes atomically.
//!
//! `cargo bench --bench io`. Needs no file: the meshes are written into a temporary folder.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use sweepffd::atomic_file::write_atomically;
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::synthetic::Tube;

const VERTICES: usize = 200_000;

fn io(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let tube = LoadedMesh::from(Tube::with_vertex_count(VERTICES, 2.0, 0.1).mesh());
    // Irrational-looking coordinates, as a deformed or subdivided mesh has: about 17 digits each.
    let positions: Vec<DVec3> = tube.mesh.positions.iter().map(|&p| p * (1.0 + 1e-7 * std::f64::consts::PI)).collect();
    let moved: Vec<DVec3> = positions.iter().map(|&p| p * 1.001 + DVec3::splat(1e-4)).collect();
    for name in ["tube.obj", "tube.ply"] {
        let mut group = c.benchmark_group(format!("io {name}"));
        group.sample_size(10);
        let path = dir.path().join(name);
        tube.save(&path, &positions).unwrap();
        let bytes = std::fs::read(&path).unwrap().len();
        let id = VERTICES;
        group.bench_with_input(BenchmarkId::new("read the bytes (floor)", id), &path, |b, path| {
            b.iter(|| std::fs::read(path).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("Mesh::load", id), &path, |b, path| {
            b.iter(|| Mesh::load(path).unwrap())
        });
        let mesh = LoadedMesh::load(&path).unwrap();
        let out = dir.path().join(format!("out_{name}"));
        let zeros = vec![0u8; bytes];
        group.bench_with_input(BenchmarkId::new("write as many bytes (floor)", id), &out, |b, out| {
            b.iter(|| write_atomically(out, |w| std::io::Write::write_all(w, &zeros)).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("Mesh::save, every vertex moved", id), &out, |b, out| {
            b.iter(|| mesh.save(out, &moved).unwrap())
        });
        group.finish();
    }
}

criterion_group!(benches, io);
criterion_main!(benches);
