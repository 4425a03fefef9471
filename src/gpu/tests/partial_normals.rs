//! Normals recomputed only where the one-ring moves equal a full recomputation, to the bit: on a
//! tube whose top rings (a few % of its vertices) a sweep owns, bent, twisted and tapered, the
//! GPU deformer's normals equal those of a second deformer that computes every normal of the
//! deformed positions, and the CPU twin over the dirty vertices equals the twin over all.
//!
//! Without a GPU adapter the GPU test prints a notice and passes; `SWEEPFFD_REQUIRE_GPU=1`
//! makes a missing adapter fail it.

use crate::common;

use glam::{DVec3, Vec3};
use sweepffd::coeffs::{GpuBinding, UNOWNED};
use sweepffd::cpu;
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuDeformer, rest_positions};
use sweepffd::mesh::Mesh;
use sweepffd::normals::{NormalAdjacency, dirty_vertices};
use sweepffd::rig::{Rig, RigSweep};
use sweepffd::synthetic::{BendTwistTaper, Tube, straight_sweep};

const POSE: BendTwistTaper = BendTwistTaper { bend: 1.0, twist: 1.3, taper: 0.7 };

/// A tube of 40 rings of 48 and a rig whose one sweep owns its top `owned_rings` rings and top
/// cap, keys from just below them to the top.
fn top_owned_tube(owned_rings: u32) -> (Mesh, Rig) {
    let tube = Tube { rings: 40, around: 48, length: 4.0, radius: 0.5 };
    let first = tube.rings - owned_rings;
    let owned: Vec<u32> =
        (first * tube.around..tube.rings * tube.around).chain([tube.rings * tube.around + 1]).collect();
    let step = tube.length / (tube.rings - 1) as f64;
    let z = ((first as f64 - 0.5) * step, tube.length + 0.5 * step);
    let sweep = RigSweep { name: "top".to_string(), ..straight_sweep(&tube, owned, z, 4, 8, 0.0) };
    (tube.mesh(), Rig::new(vec![sweep]).unwrap())
}

/// The first vertex whose normals differ in any bit, with both normals.
fn first_difference(a: &[f32], b: &[f32]) -> Option<(usize, [f32; 3], [f32; 3])> {
    let bits = |x: &[f32]| x.iter().map(|c| c.to_bits()).collect::<Vec<_>>();
    (0..a.len() / 3).find(|&v| bits(&a[3 * v..3 * v + 3]) != bits(&b[3 * v..3 * v + 3])).map(|v| {
        let n = |x: &[f32]| [x[3 * v], x[3 * v + 1], x[3 * v + 2]];
        (v, n(a), n(b))
    })
}

/// The dirty vertices of the tube: a few % of it, the owned ones and the ring below them.
fn dirty(mesh: &Mesh, owners: &[u32]) -> Vec<u32> {
    let adjacency = NormalAdjacency::new(&mesh.faces, mesh.positions.len());
    dirty_vertices(&adjacency, |v| owners[v] != UNOWNED)
}

#[test]
fn dirty_vertices_are_the_owned_ones_and_their_one_ring() {
    let (mesh, rig) = top_owned_tube(2);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let dirty = dirty(&mesh, &owners);
    let owned = owners.iter().filter(|&&o| o != UNOWNED).count();
    // Two owned rings and the top cap, plus the ring below them.
    assert_eq!(owned, 2 * 48 + 1);
    assert_eq!(dirty.len(), owned + 48, "{dirty:?}");
    assert!(dirty.len() * 100 < mesh.positions.len() * 10, "{} of {}", dirty.len(), mesh.positions.len());
}

#[test]
fn twin_over_the_dirty_vertices_equals_the_twin_over_all_to_the_bit() {
    let (mesh, rig) = top_owned_tube(2);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let adjacency = NormalAdjacency::new(&mesh.faces, mesh.positions.len());
    let rest = cpu::packed(&mesh.positions);
    let bindings = cpu::bind::bind_to(rig.rest(), &owners, &rest);
    let mut coefficients = sweepffd::coeffs::SweepCoefficients::new(rig.rest());
    coefficients.update(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let mut posed = rest.clone();
    cpu::deform::deform(&coefficients.cells, &bindings, &mut posed);

    let mut partial = vec![0.0; rest.len()];
    cpu::normals::normals(&rest, &adjacency, &mut partial);
    let rest_normals = partial.clone();
    cpu::normals::normals_of(&posed, &adjacency, &dirty(&mesh, &owners), &mut partial);
    let mut full = vec![0.0; rest.len()];
    cpu::normals::normals(&posed, &adjacency, &mut full);
    assert_eq!(first_difference(&partial, &full), None, "twin: partial vs full");
    let changed = first_difference(&rest_normals, &full);
    assert!(changed.is_some(), "the pose changed no normal: the test would prove nothing");
}

#[test]
fn gpu_normals_over_the_dirty_vertices_equal_a_full_recomputation_to_the_bit() {
    let Some(context) = common::gpu() else { return };
    let (mesh, rig) = top_owned_tube(2);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = BindingSource::Bind { owners: &owners, bands: &[] };
    let (positions, triangles) =
        (rest_positions(&mesh.positions), mesh.faces.triangles().flatten().collect::<Vec<u32>>());
    let descriptor = DeformerDescriptor::new(rig.rest(), &positions, bindings).with_triangles(&triangles);
    let mut deformer = GpuDeformer::new(context, &descriptor).unwrap();
    let rest_normals = deformer.read_normals().unwrap().unwrap();
    deformer.deform(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let positions = deformer.read_positions().unwrap();
    let normals = deformer.read_normals().unwrap().unwrap();

    // A deformer at rest on the deformed positions computes every normal at creation.
    let deformed: Vec<DVec3> = positions.chunks_exact(3).map(|p| Vec3::from_slice(p).as_dvec3()).collect();
    let unbound = vec![GpuBinding { cell: UNOWNED, ..Default::default() }; deformed.len()];
    let bindings = BindingSource::Precomputed { bindings: &unbound, bands: &[] };
    let deformed = rest_positions(&deformed);
    let full =
        GpuDeformer::new(context, &DeformerDescriptor::new(rig.rest(), &deformed, bindings).with_triangles(&triangles))
            .unwrap();
    let full = full.read_normals().unwrap().unwrap();
    let difference = first_difference(&normals, &full);
    println!("GPU partial vs full normals: first difference {difference:?}");
    assert_eq!(difference, None, "GPU: partial vs full (vertex, partial, full)");

    // The pose changed normals, also of unowned vertices next to owned ones.
    let dirty = dirty(&mesh, &owners);
    let changed: Vec<usize> = (0..mesh.positions.len())
        .filter(|&v| first_difference(&rest_normals[3 * v..3 * v + 3], &normals[3 * v..3 * v + 3]).is_some())
        .collect();
    println!("{} normals changed, {} dirty of {} vertices", changed.len(), dirty.len(), mesh.positions.len());
    assert!(changed.iter().all(|&v| dirty.binary_search(&(v as u32)).is_ok()), "a clean vertex changed");
    assert!(changed.iter().any(|&v| owners[v] == UNOWNED), "no unowned vertex's normal changed");
}
