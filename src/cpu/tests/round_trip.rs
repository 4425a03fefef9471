//! Bind then deform with the unchanged rest rig reproduces every vertex, on real meshes: within
//! 1e-9 × the bounding-box diagonal on the f64 reference path and 1e-5 × diagonal on the f32
//! CPU twin of the GPU kernels. Each rig's sweep spans the mesh's principal axis, with vertices
//! beyond both ends.

use crate::common;

use glam::DVec3;
use sweepffd::bind::{Binding, UNOWNED, bind_vertices};
use sweepffd::coeffs::SweepCoefficients;
use sweepffd::cpu;
use sweepffd::deform::deform_hard;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;

const F64_TOLERANCE: f64 = 1e-9;
const F32_TOLERANCE: f64 = 1e-5;

struct Case {
    mesh: Mesh,
    rig: Rig,
    owners: Vec<u32>,
    diagonal: f64,
}

fn case(name: &str) -> Option<Case> {
    let path = common::shared_mesh(name)?;
    let mesh = Mesh::load(&path).expect("shared mesh loads");
    let rig = common::axis_rig(&mesh, 9, 16);
    let owners = rig.owners(&mesh, name).unwrap();
    let diagonal = mesh.diagonal();
    Some(Case { mesh, rig, owners, diagonal })
}

/// The largest distance between corresponding points and the index where it occurs.
fn worst(a: &[DVec3], b: &[DVec3]) -> (f64, usize) {
    a.iter()
        .zip(b)
        .map(|(p, q)| p.distance(*q))
        .enumerate()
        .fold((0.0, 0), |(max, at), (i, d)| if d > max { (d, i) } else { (max, at) })
}

fn f64_round_trip(case: &Case) -> Vec<Binding> {
    let bindings = bind_vertices(case.rig.rest(), &case.owners, &case.mesh.positions, &|_| {});
    assert!(bindings.iter().all(|b| b.sweep != UNOWNED));
    let mut back = vec![DVec3::ZERO; case.mesh.positions.len()];
    deform_hard(case.rig.rest(), &bindings, &case.mesh.positions, &mut back);
    let (error, at) = worst(&back, &case.mesh.positions);
    println!("f64 round trip: worst {:.3e} × diagonal at vertex {at}", error / case.diagonal);
    assert!(error <= F64_TOLERANCE * case.diagonal, "vertex {at} moved by {error:e} (diagonal {})", case.diagonal);
    bindings
}

fn f32_twin_round_trip(case: &Case) {
    let rest = case.rig.rest();
    let coefficients = SweepCoefficients::new(rest);
    let positions = cpu::packed(&case.mesh.positions);
    let bindings = cpu::bind::bind_to(rest, &case.owners, &positions);
    let mut out = positions.clone();
    cpu::deform::deform(&coefficients.cells, &bindings, &mut out);
    let back: Vec<DVec3> = out.chunks_exact(3).map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)).collect();
    let (error, at) = worst(&back, &case.mesh.positions);
    println!("f32 twin round trip: worst {:.3e} × diagonal at vertex {at}", error / case.diagonal);
    assert!(error <= F32_TOLERANCE * case.diagonal, "vertex {at} moved by {error:e} (diagonal {})", case.diagonal);
}

fn check(name: &str) {
    let Some(case) = case(name) else { return };
    let bindings = f64_round_trip(&case);
    let beyond = bindings.iter().filter(|b| b.params.t == 0.0 || b.params.t == 1.0).count();
    assert!(beyond > 0, "the rig must leave vertices beyond its ends");
    f32_twin_round_trip(&case);
}

#[test]
fn bunny_round_trips() {
    check("bunny_stanford_zipper.obj");
}

#[test]
fn newell_teapot_round_trips() {
    check("teapot_newell.obj");
}

#[test]
fn armadillo_round_trips() {
    check("armadillo_50k.obj");
}
