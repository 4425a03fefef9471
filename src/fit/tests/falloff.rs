//! Falloff bands (rig field `falloff`) on the f64 reference, the f32 twins and the GPU: seams
//! that do not tear, a twisted band that does not collapse, two sweeps that blend at their
//! joint, and exactness where the paper's Eq. 2 must hold.

use crate::common;

use common::falloff_tubes::{TUBE, attached_arm, split_tube};

use glam::{DQuat, DVec3, Vec3};
use sweepffd::bind::MeshBindings;
use sweepffd::cpu;
use sweepffd::deform::{deform_hard, deform_vertices};
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::gpu::BindingSource;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;

/// The rig's keys with key 0 of `sweep` turned by `rotate` about its center, local mode (the
/// keys after it follow rigidly).
fn turn_key0(rig: &Rig, sweep: &str, rotate: DQuat) -> Vec<Vec<Key>> {
    let mut posing = Posing::new(rig);
    let edit = Edit::MoveKey {
        sweep: sweep.to_string(),
        key: 0,
        translate: [0.0; 3],
        rotate: rotate.to_array(),
        mode: KeyMode::Local,
    };
    posing.apply(&edit).unwrap();
    posing.keys().to_vec()
}

fn deform(rig: &Rig, bindings: &MeshBindings, mesh: &Mesh, keys: &[Vec<Key>]) -> Vec<DVec3> {
    let posed = rig.pose(keys).unwrap();
    let mut out = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(rig.rest(), &posed, bindings, &mesh.positions, &mut out);
    out
}

/// Every mesh edge once, as (a, b) with a < b.
fn edges(mesh: &Mesh) -> Vec<(u32, u32)> {
    let mut edges: Vec<(u32, u32)> = mesh
        .faces
        .iter()
        .flat_map(|face| (0..face.len()).map(move |i| (face[i], face[(i + 1) % face.len()])))
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// Deformed length over rest length of an edge.
fn stretch(rest: &[DVec3], posed: &[DVec3], (a, b): (u32, u32)) -> f64 {
    let (a, b) = (a as usize, b as usize);
    posed[a].distance(posed[b]) / rest[a].distance(rest[b])
}

fn largest_stretch(mesh: &Mesh, posed: &[DVec3]) -> f64 {
    edges(mesh).into_iter().map(|e| stretch(&mesh.positions, posed, e)).fold(0.0, f64::max)
}

#[test]
fn a_swung_arm_stays_attached_with_falloff_and_tears_without() {
    let turn = DQuat::from_rotation_x(30f64.to_radians());
    let mut worst = Vec::new();
    for falloff in [1.5, 0.0] {
        let (mesh, rig) = attached_arm(falloff);
        let owners = rig.owners(&mesh, "tube").unwrap();
        let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
        assert_eq!(bindings.has_bands(), falloff > 0.0);
        let posed = deform(&rig, &bindings, &mesh, &turn_key0(&rig, "arm", turn));
        worst.push(largest_stretch(&mesh, &posed));
    }
    eprintln!("swung arm: largest edge stretch {:.3} with falloff, {:.3} without", worst[0], worst[1]);
    assert!(worst[0] <= 2.0, "with falloff: {:.3}", worst[0]);
    assert!(worst[1] > 3.0, "without falloff the seam should tear: {:.3}", worst[1]);
}

#[test]
fn a_half_twisted_band_turns_instead_of_collapsing() {
    let (mesh, rig) = attached_arm(1.5);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let keys = turn_key0(&rig, "arm", DQuat::from_rotation_z(std::f64::consts::PI));
    let blended = deform(&rig, &bindings, &mesh, &keys);
    // The same weights applied as a linear blend of the rest and fully posed positions.
    let mut full = vec![DVec3::ZERO; mesh.positions.len()];
    deform_hard(&rig.pose(&keys).unwrap(), &bindings.vertices, &mesh.positions, &mut full);
    let weights = bindings.weights();
    let linear: Vec<DVec3> = (0..mesh.positions.len()).map(|v| mesh.positions[v].lerp(full[v], weights[v])).collect();
    let in_band = |(a, b): (u32, u32)| [a, b].iter().any(|&v| weights[v as usize] > 0.0 && weights[v as usize] < 1.0);
    let band_edges: Vec<(u32, u32)> = edges(&mesh).into_iter().filter(|&e| in_band(e)).collect();
    assert!(band_edges.len() > 100, "{} band edges", band_edges.len());
    let shortest = |positions: &[DVec3]| {
        band_edges.iter().map(|&e| stretch(&mesh.positions, positions, e)).fold(f64::INFINITY, f64::min)
    };
    let (ours, lbs) = (shortest(&blended), shortest(&linear));
    eprintln!("180° twist: shortest band edge {ours:.3} of its rest length (frame blend), {lbs:.3} (linear blend)");
    assert!(ours >= 0.4, "frame blend: {ours:.3}");
    assert!(lbs < 0.4, "the linear blend should collapse: {lbs:.3}");
}

#[test]
fn two_sweeps_blend_smoothly_at_their_joint() {
    let (mesh, rig) = split_tube(1.0);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let upper = rig.sweep_index("upper").unwrap() as u32;
    assert!(bindings.bands.iter().any(|b| b.second.sweep == upper));
    let keys = turn_key0(&rig, "upper", DQuat::from_rotation_x(60f64.to_radians()));
    let posed = deform(&rig, &bindings, &mesh, &keys);
    let largest = largest_stretch(&mesh, &posed);
    // Axial edges of one generatrix at the outside of the bend, across and beside the joint
    // (rings 30 | 31; ring 30 is z = 3, owned by the lower sweep).
    let around = TUBE.around;
    let worst_axial = |ring: u32| {
        (0..around)
            .map(|k| stretch(&mesh.positions, &posed, (ring * around + k, (ring + 1) * around + k)))
            .fold(0.0, f64::max)
    };
    let (before, across, after) = (worst_axial(29), worst_axial(30), worst_axial(31));
    eprintln!(
        "joint bent 60°: largest stretch {largest:.3}; axial edges beside {before:.3} / across {across:.3} / beside {after:.3}"
    );
    assert!(largest <= 1.5, "{largest:.3}");
    assert!(across <= 1.1 * before.max(after), "across {across:.3}, beside {before:.3} and {after:.3}");
    // Without falloff the joint opens.
    let (mesh, rig) = split_tube(0.0);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let hard = rig.bind_mesh(&mesh, &owners, &|_| {});
    let posed = deform(&rig, &hard, &mesh, &keys);
    assert!(largest_stretch(&mesh, &posed) > 1.5);
}

#[test]
fn falloff_is_exact_where_it_must_be() {
    let (mesh, rig) = attached_arm(1.5);
    let diagonal = mesh.diagonal();
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let keys = turn_key0(&rig, "arm", DQuat::from_rotation_x(0.5));
    let posed = deform(&rig, &bindings, &mesh, &keys);
    let weights = bindings.weights();
    let keeps = bindings.keeps_rest();
    assert!(keeps.iter().zip(&owners).any(|(&k, &o)| k && o != u32::MAX), "a weight-0 vertex exists");
    for v in 0..mesh.positions.len() {
        if keeps[v] {
            assert_eq!(posed[v], mesh.positions[v], "vertex {v} keeps its rest position to the bit");
        }
    }
    // Deep inside (w = 1): exactly Eq. 2.
    let mut hard = vec![DVec3::ZERO; mesh.positions.len()];
    deform_hard(&rig.pose(&keys).unwrap(), &bindings.vertices, &mesh.positions, &mut hard);
    let deep = (0..mesh.positions.len()).filter(|&v| weights[v] == 1.0);
    let worst = deep.map(|v| posed[v].distance(hard[v])).fold(0.0, f64::max);
    assert!(worst <= 1e-12 * diagonal, "{worst:e}");
    // Round trip at rest.
    let rest_keys: Vec<Vec<Key>> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
    let back = deform(&rig, &bindings, &mesh, &rest_keys);
    let worst = (0..mesh.positions.len()).map(|v| back[v].distance(mesh.positions[v])).fold(0.0, f64::max);
    assert!(worst <= 1e-9 * diagonal, "round trip {worst:e}");
}

#[test]
fn a_rigid_motion_of_every_key_moves_two_blended_sweeps_rigidly() {
    let (mesh, rig) = split_tube(1.0);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let motion = glam::DAffine3::from_rotation_translation(
        DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 1.3),
        DVec3::new(0.4, -2.0, 7.0),
    );
    let keys: Vec<Vec<Key>> = rig
        .sweeps()
        .iter()
        .map(|s| {
            s.keys
                .iter()
                .map(|k| Key {
                    center: motion.transform_point3(k.center),
                    rotation: DQuat::from_mat3(&motion.matrix3) * k.rotation,
                    radii: k.radii.clone(),
                })
                .collect()
        })
        .collect();
    let posed = deform(&rig, &bindings, &mesh, &keys);
    let worst = (0..mesh.positions.len())
        .map(|v| posed[v].distance(motion.transform_point3(mesh.positions[v])))
        .fold(0.0, f64::max);
    assert!(worst <= 1e-9 * mesh.diagonal(), "{worst:e}");
}

#[test]
fn twin_and_gpu_match_the_f64_reference_with_falloff() {
    let cases = [("attached arm", attached_arm(1.5), "arm"), ("split tube", split_tube(1.0), "upper")];
    for (name, (mesh, rig), sweep) in cases {
        let diagonal = mesh.diagonal() as f32;
        let owners = rig.owners(&mesh, "tube").unwrap();
        let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
        let keys = turn_key0(&rig, sweep, DQuat::from_rotation_x(0.8) * DQuat::from_rotation_z(0.6));
        let reference = cpu::packed(&deform(&rig, &bindings, &mesh, &keys));
        let twin = super::twin::twin_positions(&rig, &mesh, &bindings, &keys);
        let (error, ulps, at) = common::worst_f32(&reference, &twin);
        eprintln!("{name}: twin vs f64 {:.2e} × diagonal, {ulps} ULP, at vertex {}", error / diagonal, at / 3);
        assert!(error <= 1e-5 * diagonal, "{name}: twin vs f64 {error:e} at vertex {}", at / 3);
        // Round trip at rest, falloff on.
        let rest = cpu::packed(&mesh.positions);
        let rest_keys: Vec<Vec<Key>> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
        let back = super::twin::twin_positions(&rig, &mesh, &bindings, &rest_keys);
        let (error, _, at) = common::worst_f32(&rest, &back);
        assert!(error <= 1e-5 * diagonal, "{name}: twin round trip {error:e} at vertex {}", at / 3);
        let Some(context) = common::gpu() else { continue };
        let weights = rig.band_weights(&mesh, &owners);
        let source = BindingSource::Bind { owners: &owners, bands: &weights };
        let mut deformer = common::deformer(context, rig.rest(), &mesh.positions, source, None).unwrap();
        assert_eq!(deformer.band_vertex_count(), bindings.bands.len());
        deformer.deform(&rig.pose(&keys).unwrap()).unwrap();
        let gpu = deformer.read_positions().unwrap();
        let (error, ulps, at) = common::worst_f32(&twin, &gpu);
        eprintln!("{name}: GPU vs twin {:.2e} × diagonal, {ulps} ULP, at vertex {}", error / diagonal, at / 3);
        assert!(error <= 1e-5 * diagonal, "{name}: GPU vs twin {error:e} at vertex {}", at / 3);
        let (error, _, at) = common::worst_f32(&reference, &gpu);
        assert!(error <= 1e-5 * diagonal, "{name}: GPU vs f64 {error:e} at vertex {}", at / 3);
        deformer.deform(rig.rest()).unwrap();
        let (error, _, at) = common::worst_f32(&rest, &deformer.read_positions().unwrap());
        eprintln!("{name}: GPU round trip at rest {:.2e} × diagonal, at vertex {}", error / diagonal, at / 3);
        assert!(error <= 1e-5 * diagonal, "{name}: GPU round trip {error:e} at vertex {}", at / 3);
        deformer.deform(&rig.pose(&keys).unwrap()).unwrap();
        let gpu = deformer.read_positions().unwrap();
        // Weight-0 vertices against the rest position keep the f32 rest position to the bit.
        for (v, keeps) in bindings.keeps_rest().iter().enumerate() {
            if *keeps {
                assert_eq!(Vec3::from_slice(&gpu[3 * v..]), Vec3::from_slice(&rest[3 * v..]), "{name}: vertex {v}");
            }
        }
    }
}
