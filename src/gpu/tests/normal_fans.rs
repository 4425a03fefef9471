//! The normals kernel on every kind of fan its rows hold: closed fans (which close back to
//! their first neighbour without repeating it), boundary fans, several fans around a
//! non-manifold vertex, and a vertex in no triangle (never listed: its normal stays zero). A
//! tube carrying an open strip, a fin of three triangles on one edge and an isolated vertex is
//! bent, twisted and tapered; the GPU normals equal the twin's on the same positions, within
//! 1e-5 rad (zero exactly where the twin's is zero), and the twin's equal the f64 reference's
//! within 1e-5 rad.
//!
//! Without a GPU adapter the test prints a notice and passes; `SWEEPFFD_REQUIRE_GPU=1` makes a
//! missing adapter fail it.

use crate::common;

use common::normal_angles::worst_angle;
use glam::{DVec3, Vec3};
use sweepffd::cpu;
use sweepffd::gpu::BindingSource;
use sweepffd::mesh::Mesh;
use sweepffd::normals::{FAN_CLOSE, FAN_START, NormalAdjacency, vertex_normals};
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

const POSE: BendTwistTaper = BendTwistTaper { bend: 1.1, twist: 1.4, taper: 0.7 };
const GPU_TOLERANCE: f64 = 1e-5;
const REFERENCE_TOLERANCE: f64 = 1e-5;

/// The tube with, inside it, an open strip of 8 triangles, a fin (three triangles on the edge
/// (a, b)) and, last, an isolated vertex.
fn tube_with_open_and_non_manifold_parts(tube: &Tube) -> Mesh {
    let mesh = tube.mesh();
    let (mut positions, mut faces) = (mesh.positions, mesh.faces);
    let first = positions.len() as u32;
    for i in 0..10 {
        let z = 0.5 + 0.25 * (i / 2) as f64;
        positions.push(DVec3::new(0.2 * (i % 2) as f64, 0.1, z));
    }
    for i in 0..8 {
        faces.push(&[first + i, first + i + 1, first + i + 2]);
    }
    let fin = positions.len() as u32;
    for p in [[0.0, -0.2, 2.5], [0.0, -0.2, 3.0], [0.2, -0.1, 2.7], [-0.2, -0.1, 2.7], [0.0, 0.1, 2.8]] {
        positions.push(DVec3::from_array(p));
    }
    for [a, b, c] in [[0, 1, 2], [1, 0, 3], [0, 1, 4]] {
        faces.push(&[fin + a, fin + b, fin + c]);
    }
    positions.push(DVec3::new(0.1, 0.0, 2.0));
    Mesh::from_parts(positions, faces, Vec::new()).unwrap()
}

#[test]
fn closed_boundary_and_non_manifold_fans_and_an_isolated_vertex_match_the_twin() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube { rings: 16, around: 24, length: 4.0, radius: 0.5 };
    let mesh = tube_with_open_and_non_manifold_parts(&tube);
    let adjacency = NormalAdjacency::new(&mesh.faces, mesh.positions.len());
    let fin = mesh.positions.len() - 6;
    let closing = (0..tube.vertex_count()).filter(|&v| adjacency.fans_of(v).iter().any(|&e| e & FAN_CLOSE != 0));
    assert_eq!(closing.count(), tube.vertex_count(), "every tube vertex closes its fan");
    let several = |v: usize| adjacency.fans_of(v).iter().filter(|&&e| e & FAN_START != 0).count() > 1;
    assert!(several(fin) && several(fin + 1), "the fin's edge has several fans at each end");
    let isolated = mesh.positions.len() - 1;
    assert!(adjacency.fans_of(isolated).is_empty());

    let rig = tube_rig(&tube, 6, 12);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = BindingSource::Bind { owners: &owners, bands: &[] };
    let mut deformer = common::deformer(context, rig.rest(), &mesh.positions, bindings, Some(&mesh.faces)).unwrap();
    deformer.deform(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let positions = deformer.read_positions().unwrap();
    let normals = deformer.read_normals().unwrap().unwrap();
    let mut twin = vec![f32::NAN; positions.len()];
    cpu::normals::normals(&positions, &adjacency, &mut twin);
    let (angle, at) = worst_angle(&normals, &twin);
    println!("GPU vs twin: worst angle {angle:.2e} rad at vertex {at}");
    assert!(angle <= GPU_TOLERANCE, "GPU normal off the twin's by {angle} rad at vertex {at}");
    assert_eq!(normals[3 * isolated..3 * isolated + 3], [0.0; 3], "the isolated vertex");
    let moved = (fin..isolated).any(|v| positions[3 * v..3 * v + 3] != mesh.positions[v].as_vec3().to_array());
    assert!(moved, "the pose did not move the fin: the test would not reach the per-frame pass");

    let positions64: Vec<DVec3> = positions.chunks_exact(3).map(|p| Vec3::from_slice(p).as_dvec3()).collect();
    let reference: Vec<f32> =
        vertex_normals(&positions64, &adjacency).iter().flat_map(|n| n.as_vec3().to_array()).collect();
    let (angle, at) = worst_angle(&twin, &reference);
    println!("twin vs f64: worst angle {angle:.2e} rad at vertex {at}");
    assert!(angle <= REFERENCE_TOLERANCE, "twin normal off the f64 one by {angle} rad at vertex {at}");
}
