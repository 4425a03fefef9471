//! Fitting one sweep to a mesh part (§3, Fig. 3) with the skeleton as the first guess, against
//! the same fit started from the part's principal axis, measured in the same run: the upper
//! five sixths of a closed tube (attached at z = 1, capped at its tip), at several vertex
//! counts, and the shared meshes' limbs when `../shared/meshes` is beside the clone; and
//! `autorig` (protrusions found and each fitted) on the bunny and the armadillo; and the body
//! autorig searches (seams welded, touching components joined) of a dense tube with small
//! pieces lying on it, whose contacts are searched per vertex among the pieces' triangles; and
//! the mirror map autorig makes twins alike with, against the body search.
//!
//! `cargo bench --features internals --bench fit`.

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::fit::axis::principal_axis;
use sweepffd::fit::body::Body;
use sweepffd::fit::mirror::mirror_map;
use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::mesh::{Faces, Mesh};
use sweepffd::synthetic::Tube;

/// The part's principal axis as a user's axis: the first guess the fit used before the skeleton.
fn principal_axis_options(mesh: &Mesh, vertices: &[u32]) -> FitOptions {
    let positions: Vec<DVec3> = vertices.iter().map(|&v| mesh.positions[v as usize]).collect();
    let (centroid, direction) = principal_axis(&positions);
    FitOptions { axis: Some(vec![centroid - direction, centroid + direction]), ..FitOptions::default() }
}

fn tube_parts(c: &mut Criterion) {
    let mut group = c.benchmark_group("fit_tube_part");
    group.sample_size(10);
    for n in [5_000, 20_000, 50_000] {
        let tube = Tube::with_vertex_count(n, 6.0, 0.5);
        let mesh = tube.mesh();
        let part = largest_connected(&mesh, |p| p.z >= 1.0);
        let options = principal_axis_options(&mesh, &part);
        group.bench_with_input(BenchmarkId::new("skeleton", n), &part, |b, part| {
            b.iter(|| fit(&mesh, part, &FitOptions::default()).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("principal_axis", n), &part, |b, part| {
            b.iter(|| fit(&mesh, part, &options).unwrap())
        });
    }
    group.finish();
}

fn shared_limbs(c: &mut Criterion) {
    let Some(path) = common::shared_mesh("armadillo_50k.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let leg = largest_connected(&mesh, |p| p.x < -5.0 && p.y < -8.0 && p.z < 35.0);
    let options = principal_axis_options(&mesh, &leg);
    let mut group = c.benchmark_group("fit_armadillo_leg_with_foot");
    group.sample_size(10);
    group.bench_function(BenchmarkId::from_parameter(format!("skeleton/{}", leg.len())), |b| {
        b.iter(|| fit(&mesh, &leg, &FitOptions::default()).unwrap())
    });
    group.bench_function(BenchmarkId::from_parameter(format!("principal_axis/{}", leg.len())), |b| {
        b.iter(|| fit(&mesh, &leg, &options).unwrap())
    });
    group.finish();
}

fn autorig_meshes(c: &mut Criterion) {
    let mut group = c.benchmark_group("autorig");
    group.sample_size(10);
    for name in ["bunny_stanford_zipper.obj", "armadillo_50k.obj"] {
        let Some(path) = common::shared_mesh(name) else { continue };
        let mesh = Mesh::load(&path).unwrap();
        group.bench_function(BenchmarkId::from_parameter(format!("{name}/{}", mesh.positions.len())), |b| {
            b.iter(|| autorig(&mesh, &AutorigOptions::default()).unwrap())
        });
    }
    group.finish();
}

/// A 50,000-vertex tube (length 6, radius 0.5) with `pieces` small tubes (length 0.6, radius
/// 0.05, 130 vertices) lying along its wall, 0.01 off it: every piece touches the tube, and
/// each of the tube's vertices near a piece looks for the piece's nearest triangle.
fn tube_with_pieces(pieces: usize) -> Mesh {
    let body = Tube::with_vertex_count(50_000, 6.0, 0.5).mesh();
    let piece = Tube { rings: 8, around: 16, length: 0.6, radius: 0.05 }.mesh();
    let mut positions = body.positions.clone();
    let mut faces = Faces::new();
    for t in body.faces.triangles() {
        faces.push(&t);
    }
    for k in 0..pieces {
        let (angle, z) = (std::f64::consts::TAU * k as f64 / pieces as f64, 0.5 + 4.5 * k as f64 / pieces as f64);
        let offset = positions.len() as u32;
        let (out, up) = (DVec3::new(angle.cos(), angle.sin(), 0.0), DVec3::Z);
        positions.extend(piece.positions.iter().map(|p| out * (0.56 + p.x) + up * (z + p.z) + out.cross(up) * p.y));
        for t in piece.faces.triangles() {
            faces.push(&t.map(|v| v + offset));
        }
    }
    Mesh::from_parts(positions, faces, Vec::new()).unwrap()
}

fn body_contacts(c: &mut Criterion) {
    let mut group = c.benchmark_group("autorig_body");
    group.sample_size(10);
    for pieces in [10, 40] {
        let mesh = tube_with_pieces(pieces);
        group.bench_function(BenchmarkId::new("tube_with_pieces", pieces), |b| b.iter(|| Body::new(&mesh)));
    }
    group.finish();
}

/// The mirror map autorig makes twins alike with, on the 50,000-vertex tube (a mirror image of
/// itself end to end: a whole pass over its vertices) and on the tube with 40 pieces along its
/// wall (no plane: each tried fails at its first vertex with no twin), against the body search
/// of the same mesh in the same run.
fn mirror_maps(c: &mut Criterion) {
    let mut group = c.benchmark_group("autorig_mirror");
    group.sample_size(10);
    for (name, mesh) in
        [("tube", Tube::with_vertex_count(50_000, 6.0, 0.5).mesh()), ("tube_with_pieces", tube_with_pieces(40))]
    {
        let vertices: Vec<u32> = (0..mesh.positions.len() as u32).collect();
        group.bench_function(BenchmarkId::new("mirror_map", name), |b| {
            b.iter(|| mirror_map(&mesh.positions, &vertices))
        });
        group.bench_function(BenchmarkId::new("body", name), |b| b.iter(|| Body::new(&mesh)));
    }
    group.finish();
}

criterion_group!(benches, tube_parts, shared_limbs, autorig_meshes, body_contacts, mirror_maps);
criterion_main!(benches);
