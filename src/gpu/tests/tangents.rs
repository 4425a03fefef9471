//! Deformed tangents on the GPU: against their CPU twin on the GPU's own normals (within
//! 1e-5 rad, worst vertex reported), orthogonal to the GPU normals (|t · n| ≤ 1e-4) and unit,
//! the twin against the f64 reference, a rotation of a tube about its axis rotating the wall's
//! tangents with it, and opposite normals giving finite tangents.
//!
//! Without a GPU adapter the GPU tests print a notice and pass; `SWEEPFFD_REQUIRE_GPU=1` makes a
//! missing adapter fail them.

use crate::common;

use glam::{DQuat, DVec3, DVec4, Vec3, Vec4};
use sweepffd::coeffs::UNOWNED;
use sweepffd::cpu;
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuDeformer, rest_positions};
use sweepffd::mesh::Mesh;
use sweepffd::normals::tangents::deformed_tangents;
use sweepffd::normals::{NormalAdjacency, vertex_normals};
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;
use sweepffd::synthetic::{BendTwistTaper, Tube, attached_tube_rig, tube_rig};

/// GPU tangents against the twin's, radians.
const GPU_TOLERANCE: f64 = 1e-5;
/// The twin against the f64 reference on the same normals, radians.
const REFERENCE_TOLERANCE: f64 = 1e-5;
/// |t · n| of a GPU tangent and the GPU normal of its vertex.
const ORTHOGONALITY: f32 = 1e-4;

const POSE: BendTwistTaper = BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 };

fn tube() -> Tube {
    Tube { rings: 48, around: 40, length: 4.0, radius: 0.5 }
}

/// Rest tangents as a host might supply them: around the tube's axis, leaning a little off
/// the rest normals (Gram-Schmidt has work to do), w alternating ±1.
fn rest_tangents(mesh: &Mesh) -> Vec<[f32; 4]> {
    let normals = vertex_normals(&mesh.positions, &NormalAdjacency::new(&mesh.faces, mesh.positions.len()));
    normals
        .iter()
        .zip(&mesh.positions)
        .enumerate()
        .map(|(v, (n, p))| {
            let around = DVec3::Z.cross(*p + DVec3::new(0.1, 0.05, 0.0));
            let t = (around - *n * n.dot(around)).normalize() + 0.02 * *n;
            let w = if v % 2 == 0 { 1.0 } else { -1.0 };
            t.as_vec3().extend(w).to_array()
        })
        .collect()
}

/// The angle between the xyz of two tangents (atan2 of |a × b| and a · b in f64; zero when both
/// are zero, π when one is), and whether their w agree.
fn angle(a: [f32; 4], b: [f32; 4]) -> f64 {
    let (x, y) = (Vec4::from_array(a).truncate().as_dvec3(), Vec4::from_array(b).truncate().as_dvec3());
    let angle = match (x == DVec3::ZERO, y == DVec3::ZERO) {
        (true, true) => 0.0,
        (false, false) => x.cross(y).length().atan2(x.dot(y)),
        _ => std::f64::consts::PI,
    };
    if a[3] == b[3] { angle } else { std::f64::consts::PI }
}

/// The worst angle between corresponding tangents and its vertex.
fn worst_angle(a: &[[f32; 4]], b: &[[f32; 4]]) -> (f64, usize) {
    a.iter().zip(b).map(|(x, y)| angle(*x, *y)).enumerate().fold((0.0, 0), |w, (i, e)| if e > w.0 { (e, i) } else { w })
}

/// What the GPU returns: rest normals, deformed normals (xyz) and deformed tangents (xyzw).
struct GpuRun {
    rest_normals: Vec<f32>,
    normals: Vec<f32>,
    tangents: Vec<[f32; 4]>,
}

/// The GPU's rest normals, deformed normals and deformed tangents of `mesh` posed by `keys`.
fn gpu_run(rig: &Rig, mesh: &Mesh, tangents: &[[f32; 4]], keys: &[Vec<Key>]) -> Option<GpuRun> {
    let context = common::gpu()?;
    let owners = rig.owners(mesh, "tube").unwrap();
    let bindings = BindingSource::Bind { owners: &owners, bands: &[] };
    let (positions, triangles) = (rest_positions(&mesh.positions), triangle_list(mesh));
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, bindings).with_triangles(&triangles).with_tangents(tangents);
    let mut deformer = GpuDeformer::new(context, &descriptor).unwrap();
    let rest_normals = deformer.read_normals().unwrap().unwrap();
    deformer.deform(&rig.pose(keys).unwrap()).unwrap();
    let normals = deformer.read_normals().unwrap().unwrap();
    Some(GpuRun { rest_normals, normals, tangents: deformer.read_tangents().unwrap().unwrap() })
}

/// The mesh's triangles as an engine holds them: three u32 indices each.
fn triangle_list(mesh: &Mesh) -> Vec<u32> {
    mesh.faces.triangles().flatten().collect()
}

fn to_dvec3(flat: &[f32]) -> Vec<DVec3> {
    flat.chunks_exact(3).map(|n| Vec3::from_slice(n).as_dvec3()).collect()
}

fn check_against_twin(name: &str, rig: &Rig, mesh: &Mesh) {
    let tangents = rest_tangents(mesh);
    let Some(GpuRun { rest_normals, normals, tangents: gpu }) = gpu_run(rig, mesh, &tangents, &POSE.keys(rig)) else {
        return;
    };
    let mut twin = vec![[0.0; 4]; gpu.len()];
    cpu::tangents::tangents(&rest_normals, &normals, &tangents, &mut twin);
    let (worst, at) = worst_angle(&gpu, &twin);
    println!("{name}: tangents, GPU vs twin worst angle {worst:.2e} rad at vertex {at}");
    assert!(worst <= GPU_TOLERANCE, "{name}: GPU tangent {:?} vs twin {:?} at vertex {at}", gpu[at], twin[at]);

    let (mut worst_dot, mut worst_length, mut at_dot) = (0.0f32, 0.0f32, 0);
    for (v, t) in gpu.iter().enumerate() {
        let (t, n) = (Vec4::from_array(*t).truncate(), Vec3::from_slice(&normals[3 * v..3 * v + 3]));
        assert!(t.is_finite(), "{name}: tangent {t} at vertex {v}");
        worst_length = worst_length.max((t.length() - 1.0).abs());
        if t.dot(n).abs() > worst_dot {
            (worst_dot, at_dot) = (t.dot(n).abs(), v);
        }
    }
    println!("{name}: tangents, worst |t · n| {worst_dot:.2e} at vertex {at_dot}, worst |‖t‖ − 1| {worst_length:.2e}");
    assert!(worst_dot <= ORTHOGONALITY, "{name}: |t · n| = {worst_dot} at vertex {at_dot}");
    assert!(worst_length <= ORTHOGONALITY, "{name}: a tangent is {worst_length} off unit length");

    let rest64: Vec<DVec4> = tangents.iter().map(|t| Vec4::from_array(*t).as_dvec4()).collect();
    let reference: Vec<[f32; 4]> = deformed_tangents(&to_dvec3(&rest_normals), &to_dvec3(&normals), &rest64)
        .iter()
        .map(|t| t.as_vec4().to_array())
        .collect();
    let (worst, at) = worst_angle(&twin, &reference);
    println!("{name}: tangents, twin vs f64 worst angle {worst:.2e} rad at vertex {at}");
    assert!(worst <= REFERENCE_TOLERANCE, "{name}: twin {:?} vs f64 {:?} at vertex {at}", twin[at], reference[at]);
}

#[test]
fn gpu_tangents_match_the_twin_on_a_bent_tube() {
    let tube = tube();
    check_against_twin("owned tube", &tube_rig(&tube, 5, 8), &tube.mesh());
}

#[test]
fn gpu_tangents_match_the_twin_on_a_partly_owned_tube() {
    // The first ring and bottom cap stay at rest: their tangents are the rest pass's.
    let tube = tube();
    let rig = attached_tube_rig(&tube, 5, 8, 0.0);
    let mesh = tube.mesh();
    assert!(rig.owners(&mesh, "tube").unwrap().contains(&UNOWNED));
    check_against_twin("attached tube", &rig, &mesh);
}

#[test]
fn turning_the_tube_about_its_axis_turns_the_wall_tangents_with_it() {
    let tube = tube();
    let (rig, mesh) = (tube_rig(&tube, 5, 8), tube.mesh());
    let tangents = rest_tangents(&mesh);
    let turn = DQuat::from_rotation_z(0.9);
    let keys: Vec<Vec<Key>> = rig
        .sweeps()
        .iter()
        .map(|s| {
            s.keys.iter().map(|k| Key { center: turn * k.center, rotation: turn * k.rotation, ..k.clone() }).collect()
        })
        .collect();
    let Some(GpuRun { normals, tangents: gpu, .. }) = gpu_run(&rig, &mesh, &tangents, &keys) else { return };
    // Wall vertices between the end rings have radial rest normals: the minimal rotation taking
    // them to the turned normals is the turn itself.
    let (mut worst, mut at) = (0.0, 0);
    for v in tube.around as usize..((tube.rings - 1) * tube.around) as usize {
        let n = Vec3::from_slice(&normals[3 * v..3 * v + 3]).as_dvec3();
        let t0 = Vec4::from_array(tangents[v]).as_dvec4().truncate();
        let expected = turn * (t0 - turn.inverse() * n * (turn.inverse() * n).dot(t0)).normalize();
        let error = angle(gpu[v], expected.as_vec3().extend(tangents[v][3]).to_array());
        if error > worst {
            (worst, at) = (error, v);
        }
    }
    println!("turned tube: wall tangents vs the turned rest tangents, worst angle {worst:.2e} rad at vertex {at}");
    assert!(worst <= 1e-4, "wall tangent {:?} at vertex {at}", gpu[at]);
    // The cap centers' normals lie on the axis and do not change: minimal rotation does not see
    // a turn about the normal, so their tangents stay (the documented limitation).
    let top = mesh.positions.len() - 1;
    let stayed =
        angle(gpu[top], cpu::tangents::deformed_tangent(Vec3::Z, Vec3::Z, Vec4::from_array(tangents[top])).to_array());
    assert!(stayed <= 1e-5, "top cap center: {:?}", gpu[top]);
}

#[test]
fn twin_tangent_at_opposite_normals_is_finite_unit_and_orthogonal() {
    let n0 = Vec3::new(0.0, 0.6, 0.8);
    for n in [-n0, (-n0 + Vec3::new(3e-3, 0.0, 0.0)).normalize(), (-n0 + Vec3::new(2e-2, 0.0, 0.0)).normalize()] {
        let t = cpu::tangents::deformed_tangent(n0, n, Vec4::new(1.0, 0.0, 0.0, -1.0));
        assert!(t.is_finite(), "{n}: {t}");
        assert!((t.truncate().length() - 1.0).abs() < 1e-6 && t.truncate().dot(n).abs() < 1e-6, "{n}: {t}");
        assert_eq!(t.w, -1.0);
        let reference =
            sweepffd::normals::tangents::deformed_tangent(n0.as_dvec3(), n.as_dvec3(), DVec4::new(1.0, 0.0, 0.0, -1.0));
        let error = angle(t.to_array(), reference.as_vec4().to_array());
        assert!(error <= 1e-3, "{n}: twin {t} vs f64 {reference}: {error} rad");
    }
    let zero = cpu::tangents::deformed_tangent(Vec3::ZERO, Vec3::ZERO, Vec4::new(0.0, 0.0, 0.0, 1.0));
    assert_eq!(zero, Vec4::W);
}
