//! Replacing the falloff bands of a GPU deformer (`GpuDeformer::set_bands`) after a pose: the
//! result is the deformer built fresh with the new bands (positions, bindings and band records),
//! whether the deformer had bands before or not, was bound on the GPU or given precomputed
//! bindings; no bands at all is the hard deformation; bad bands are refused.
//!
//! Without an adapter the tests print why and skip (`SWEEPFFD_REQUIRE_GPU=1` fails them).

use crate::common;

use common::falloff_tubes::{attached_arm, split_tube};

use glam::{DQuat, Vec3};
use sweepffd::coeffs::BAND_FLAG;
use sweepffd::cpu;
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::gpu::{BindingSource, GpuContext, GpuDeformer};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;

/// Positions of a deformer rebound with `set_bands` must match the fresh one within this share of
/// the bounding box diagonal (the same kernels on the same inputs: in practice bit for bit).
const TOLERANCE: f32 = 1e-6;

/// The rig's keys with key 0 of `sweep` turned and moved (local mode: the keys after it follow).
fn swing(rig: &Rig, sweep: &str) -> Vec<Vec<Key>> {
    let mut posing = Posing::new(rig);
    let rotate = DQuat::from_rotation_x(0.7) * DQuat::from_rotation_z(0.5);
    let edit = Edit::MoveKey {
        sweep: sweep.to_string(),
        key: 0,
        translate: [0.2, -0.1, 0.3],
        rotate: rotate.to_array(),
        mode: KeyMode::Local,
    };
    posing.apply(&edit).unwrap();
    posing.keys().to_vec()
}

/// A deformer of `rig`'s bands on `mesh`, bound on the GPU, with normals.
fn bound(context: &GpuContext, mesh: &Mesh, rig: &Rig) -> GpuDeformer {
    let owners = rig.owners(mesh, "tube").unwrap();
    let bands = rig.band_weights(mesh, &owners);
    let source = BindingSource::Bind { owners: &owners, bands: &bands };
    common::deformer(context, rig.rest(), &mesh.positions, source, Some(&mesh.faces)).unwrap()
}

/// Asserts that `rebound` deforms, binds and records bands as `fresh` does under `keys`.
fn assert_same(
    name: &str,
    mesh: &Mesh,
    rig: &Rig,
    keys: &[Vec<Key>],
    rebound: &mut GpuDeformer,
    fresh: &mut GpuDeformer,
) {
    let posed = rig.pose(keys).unwrap();
    rebound.deform(&posed).unwrap();
    fresh.deform(&posed).unwrap();
    let diagonal = mesh.diagonal() as f32;
    let (ours, theirs) = (rebound.read_positions().unwrap(), fresh.read_positions().unwrap());
    let (error, ulps, at) = common::worst_f32(&theirs, &ours);
    eprintln!("{name}: positions {:.2e} × diagonal, {ulps} ULP, worst at vertex {}", error / diagonal, at / 3);
    assert!(error <= TOLERANCE * diagonal, "{name}: {error:e} at vertex {}", at / 3);
    let (ours, theirs) = (rebound.read_normals().unwrap().unwrap(), fresh.read_normals().unwrap().unwrap());
    let (error, _, at) = common::worst_f32(&theirs, &ours);
    assert!(error <= 1e-5, "{name}: normals {error:e} at vertex {}", at / 3);
    assert_eq!(rebound.read_bindings().unwrap(), fresh.read_bindings().unwrap(), "{name}: bindings and band flags");
    assert_eq!(rebound.read_band_records().unwrap(), fresh.read_band_records().unwrap(), "{name}: band records");
    assert_eq!(rebound.band_vertex_count(), fresh.band_vertex_count());
}

#[test]
fn new_falloff_widths_after_a_pose_match_a_deformer_built_with_them() {
    let Some(context) = common::gpu() else { return };
    type Fixture = fn(f64) -> (Mesh, Rig);
    let cases: [(&str, Fixture, &str, f64, f64); 4] = [
        ("arm 0.8 → 1.6", attached_arm, "arm", 0.8, 1.6),
        ("arm 1.6 → 0.5", attached_arm, "arm", 1.6, 0.5),
        ("arm 0 → 1.2 (no bands before)", attached_arm, "arm", 0.0, 1.2),
        ("split tube 0.5 → 1.0", split_tube, "upper", 0.5, 1.0),
    ];
    for (name, fixture, sweep, before, after) in cases {
        let (mesh, old_rig) = fixture(before);
        let (_, rig) = fixture(after);
        let keys = swing(&rig, sweep);
        let mut rebound = bound(context, &mesh, &old_rig);
        // Posed first, so that vertices that now keep their rest position have been moved.
        rebound.deform(&old_rig.pose(&keys).unwrap()).unwrap();
        let owners = rig.owners(&mesh, "tube").unwrap();
        let weights = rig.band_weights(&mesh, &owners);
        assert!(!weights.is_empty());
        rebound.set_bands(&sweepffd::gpu::rest_positions(&mesh.positions), &weights).unwrap();
        let mut fresh = bound(context, &mesh, &rig);
        assert_same(name, &mesh, &rig, &keys, &mut rebound, &mut fresh);
        // The weight-0 vertices against the rest position hold the f32 rest position to the bit.
        let positions = rebound.read_positions().unwrap();
        let rest = cpu::packed(&mesh.positions);
        let keeps = weights.iter().filter(|w| w.fades_to_rest() && w.weight == 0.0).map(|w| w.vertex as usize);
        let mut kept = 0;
        for v in keeps {
            assert_eq!(Vec3::from_slice(&positions[3 * v..]), Vec3::from_slice(&rest[3 * v..]), "{name}: vertex {v}");
            kept += 1;
        }
        eprintln!("{name}: {} band vertices, {kept} keep their rest position", weights.len());
    }
}

#[test]
fn no_bands_is_the_hard_deformation() {
    let Some(context) = common::gpu() else { return };
    for (name, (mesh, rig), (_, hard), sweep) in [
        ("arm", attached_arm(1.5), attached_arm(0.0), "arm"),
        ("split tube", split_tube(1.0), split_tube(0.0), "upper"),
    ] {
        let keys = swing(&rig, sweep);
        let mut rebound = bound(context, &mesh, &rig);
        rebound.deform(&rig.pose(&keys).unwrap()).unwrap();
        assert!(rebound.band_vertex_count() > 0);
        rebound.set_bands(&sweepffd::gpu::rest_positions(&mesh.positions), &[]).unwrap();
        assert_eq!(rebound.band_vertex_count(), 0);
        assert!(rebound.read_bindings().unwrap().iter().all(|b| b.cell == u32::MAX || b.cell & BAND_FLAG == 0));
        let mut fresh = bound(context, &mesh, &hard);
        assert_same(&format!("{name} without bands"), &mesh, &hard, &keys, &mut rebound, &mut fresh);
    }
}

#[test]
fn precomputed_bindings_take_new_bands_too() {
    let Some(context) = common::gpu() else { return };
    let (mesh, old_rig) = split_tube(0.4);
    let (_, rig) = split_tube(1.1);
    // Bindings read back from a deformer bound on the GPU, so that only the bands differ.
    let source = bound(context, &mesh, &old_rig);
    let (bindings, records) = (source.read_bindings().unwrap(), source.read_band_records().unwrap());
    let precomputed = BindingSource::Precomputed { bindings: &bindings, bands: &records };
    let mut rebound =
        common::deformer(context, old_rig.rest(), &mesh.positions, precomputed, Some(&mesh.faces)).unwrap();
    let keys = swing(&rig, "upper");
    rebound.deform(&rig.pose(&keys).unwrap()).unwrap();
    let owners = rig.owners(&mesh, "tube").unwrap();
    rebound.set_bands(&sweepffd::gpu::rest_positions(&mesh.positions), &rig.band_weights(&mesh, &owners)).unwrap();
    let mut fresh = bound(context, &mesh, &rig);
    assert_same("precomputed split tube 0.4 → 1.1", &mesh, &rig, &keys, &mut rebound, &mut fresh);
}

#[test]
fn bad_bands_are_refused_and_change_nothing() {
    let Some(context) = common::gpu() else { return };
    let (mesh, rig) = attached_arm(1.0);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let weights = rig.band_weights(&mesh, &owners);
    let mut deformer = bound(context, &mesh, &rig);
    let unowned = owners.iter().position(|&o| o == u32::MAX).unwrap() as u32;
    let mut unsorted = weights.clone();
    unsorted.swap(0, 1);
    let mut on_unowned = weights.clone();
    on_unowned[0].vertex = unowned;
    let mut heavy = weights.clone();
    heavy[0].weight = 1.0;
    let mut stranger = weights.clone();
    stranger[0].neighbour = 1;
    for (what, bad) in [("unsorted", unsorted), ("unowned", on_unowned), ("w = 1", heavy), ("no sweep 1", stranger)] {
        let error = deformer.set_bands(&sweepffd::gpu::rest_positions(&mesh.positions), &bad).unwrap_err();
        assert!(error.to_string().contains("not sorted, owned and in range"), "{what}: {error}");
    }
    let error = deformer.set_bands(&sweepffd::gpu::rest_positions(&mesh.positions[1..]), &weights).unwrap_err();
    assert!(error.to_string().contains("rest positions"), "{error}");
    // The deformer still deforms as one built with the rig's bands.
    let keys = swing(&rig, "arm");
    let mut fresh = bound(context, &mesh, &rig);
    assert_same("after refused bands", &mesh, &rig, &keys, &mut deformer, &mut fresh);
}
