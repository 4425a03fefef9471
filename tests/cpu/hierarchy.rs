//! Hierarchies of sweeps (§5) on the Newell teapot (body the root, the spout a branch, the
//! handle a loop) and on a four-leg chair joined by virtual sweeps.

use crate::common;

use glam::{DQuat, DVec3};
use sweepffd::edit::{Edit, KeyMode, Posing, VolumeRule};
use sweepffd::mesh::Mesh;
use sweepffd::rig::{LinkKind, ParentLink, Rig, RigSweep, VertexSelection};
use sweepffd::sweep::{Key, Sweep};

fn teapot() -> Option<(Mesh, Rig)> {
    let mesh = Mesh::load(&common::shared_mesh("teapot_newell_parts.obj")?).unwrap();
    let rig = common::teapot_rig(&mesh);
    Some((mesh, rig))
}

/// For every bound key of every child, how far its center is from its bound point on the posed
/// parent; the largest.
fn worst_detachment(rig: &Rig, keys: &[Vec<Key>]) -> f64 {
    let posed: Vec<Sweep> =
        keys.iter().zip(rig.rest()).map(|(k, rest)| Sweep::try_new(k, Some(rest.knots())).unwrap()).collect();
    let mut worst = 0.0f64;
    for (child, link) in rig.links().iter().enumerate() {
        let Some(link) = link else { continue };
        let chain = &keys[child];
        let mut bound = vec![(link.first, &chain[0])];
        if let Some(last) = link.last {
            bound.push((last, &chain[chain.len() - 1]));
        }
        for (binding, key) in bound {
            let on_parent = binding.key_on(&posed[link.parent], &key.radii);
            worst = worst.max(on_parent.center.distance(key.center));
        }
    }
    worst
}

fn scale_and_bend_body() -> [Edit; 2] {
    [
        Edit::ScaleRadii { sweep: "body".into(), key: 3, factor: 1.25, theta_range: None },
        Edit::MoveKey {
            sweep: "body".into(),
            key: 4,
            translate: [0.1, 0.0, 0.0],
            rotate: DQuat::from_rotation_z(-0.25).to_array(),
            mode: KeyMode::Local,
        },
    ]
}

fn bend_handle() -> Edit {
    Edit::MoveKey {
        sweep: "handle".into(),
        key: 3,
        translate: [-0.2, 0.1, 0.0],
        rotate: DQuat::from_rotation_z(0.3).to_array(),
        mode: KeyMode::Local,
    }
}

#[test]
fn editing_the_body_keeps_the_handle_and_spout_on_it() {
    let Some((mesh, rig)) = teapot() else { return };
    let diagonal = mesh.diagonal();
    let mut posing = Posing::new(&rig);
    for edit in scale_and_bend_body() {
        posing.apply(&edit).unwrap();
        let detached = worst_detachment(&rig, posing.keys());
        println!("after {}: worst detachment {:.2e} × diagonal", edit.op(), detached / diagonal);
        assert!(detached <= 1e-4 * diagonal, "{} detached a child by {detached}", edit.op());
    }
    // The children did follow: the spout and handle moved.
    assert_ne!(posing.keys()[1][0], rig.sweeps()[1].keys[0]);
    assert_ne!(posing.keys()[2][0], rig.sweeps()[2].keys[0]);
}

#[test]
fn bending_the_handle_keeps_both_ends_attached_by_moving_the_body() {
    let Some((mesh, rig)) = teapot() else { return };
    let diagonal = mesh.diagonal();
    let mut posing = Posing::new(&rig);
    posing.apply(&bend_handle()).unwrap();
    let detached = worst_detachment(&rig, posing.keys());
    println!("bent handle: worst detachment {:.2e} × diagonal", detached / diagonal);
    assert!(detached <= 1e-4 * diagonal, "the handle came off by {detached}");
    let body_moved = posing.keys()[0]
        .iter()
        .zip(&rig.sweeps()[0].keys)
        .map(|(a, b)| a.center.distance(b.center))
        .fold(0.0, f64::max);
    assert!(body_moved > 1e-3 * diagonal, "the body must have moved to hold the handle ({body_moved})");
}

#[test]
fn without_the_hierarchy_the_loop_breaks() {
    let Some((mesh, rig)) = teapot() else { return };
    let diagonal = mesh.diagonal();
    for edits in [vec![bend_handle()], scale_and_bend_body().to_vec()] {
        let mut posing = Posing::new(&rig);
        posing.hierarchy = false;
        for edit in &edits {
            posing.apply(edit).unwrap();
        }
        let detached = worst_detachment(&rig, posing.keys());
        println!("no hierarchy: worst detachment {:.2e} × diagonal", detached / diagonal);
        assert!(detached > 1e-2 * diagonal, "the break of Fig. 12 must show ({detached})");
    }
}

#[test]
fn total_rule_keeps_the_sum_of_the_sweep_volumes() {
    let Some((_, rig)) = teapot() else { return };
    // Fig. 13a: the body shrinks and the spout and handle take up what it loses.
    let shrink = Edit::ScaleRadii { sweep: "body".into(), key: 3, factor: 0.96, theta_range: None };
    let volumes = |posing: &Posing| -> Vec<f64> { posing.sweeps().unwrap().iter().map(Sweep::volume).collect() };
    let mut plain = Posing::new(&rig);
    let before = volumes(&plain);
    plain.apply(&shrink).unwrap();
    let unruled = volumes(&plain);
    let mut posing = Posing::new(&rig);
    posing.volume = VolumeRule::Total;
    posing.apply(&shrink).unwrap();
    let after = volumes(&posing);
    let sum = |v: &[f64]| v.iter().sum::<f64>();
    println!("total rule: {before:?} → {after:?} (without the rule {unruled:?})");
    assert!(((sum(&unruled) - sum(&before)) / sum(&before)).abs() > 0.01, "the edit must change the total volume");
    assert!(((sum(&after) - sum(&before)) / sum(&before)).abs() <= 1e-6, "{} → {}", sum(&before), sum(&after));
    assert!(after[1] > before[1] && after[2] > before[2], "the spout and handle grow");
}

#[test]
fn total_rule_refuses_a_change_the_other_parts_cannot_absorb() {
    let Some((_, rig)) = teapot() else { return };
    let mut posing = Posing::new(&rig);
    posing.volume = VolumeRule::Total;
    let grow = Edit::ScaleRadii { sweep: "body".into(), key: 3, factor: 1.25, theta_range: None };
    let error = posing.apply(&grow).unwrap_err();
    assert!(error.to_string().starts_with("the volume rule cannot give sweep"), "{error}");
    let rest: Vec<_> = rig.sweeps().iter().map(|sweep| sweep.keys.clone()).collect();
    assert_eq!(posing.keys(), rest, "a failed edit changes nothing, in any sweep");
    // After edits that moved and rescaled every sweep, a failing one puts back every key,
    // radii included, to the bit (the edit ran in place, journaled).
    let shrink = Edit::ScaleRadii { sweep: "body".into(), key: 3, factor: 0.97, theta_range: None };
    posing.apply(&shrink).unwrap();
    let edited = posing.keys().to_vec();
    assert_ne!(edited, rest, "the shrink moved and rescaled sweeps");
    posing.apply(&grow).unwrap_err();
    assert_eq!(posing.keys(), edited, "a failed edit after others changes nothing");
    posing.apply(&shrink).unwrap();
    assert_ne!(posing.keys(), edited, "edits go on after a failure");
}

#[test]
fn ratio_rule_keeps_each_child_to_parent_ratio() {
    let Some((mesh, rig)) = teapot() else { return };
    let mut posing = Posing::new(&rig);
    posing.volume = VolumeRule::Ratio;
    let ratios = |posing: &Posing| -> Vec<f64> {
        let v: Vec<f64> = posing.sweeps().unwrap().iter().map(Sweep::volume).collect();
        vec![v[1] / v[0], v[2] / v[0]]
    };
    let before = ratios(&posing);
    for edit in scale_and_bend_body() {
        posing.apply(&edit).unwrap();
    }
    let after = ratios(&posing);
    println!("ratio rule: {before:?} → {after:?}");
    for (a, b) in after.iter().zip(&before) {
        assert!(((a - b) / b).abs() <= 1e-6, "{before:?} → {after:?}");
    }
    assert!(worst_detachment(&rig, posing.keys()) <= 1e-4 * mesh.diagonal(), "the rescaled children stay attached");
}

/// Four legs at the corners of a unit square: A and B joined by a virtual sweep hung from A, C
/// joined to B by another, D on its own.
fn chair() -> Rig {
    let leg = |x: f64, z: f64, top_first: bool| -> Vec<Key> {
        let mut keys: Vec<Key> = [0.0, 0.5, 0.95]
            .iter()
            .map(|&y| Key::circle(DVec3::new(x, y, z), DQuat::from_rotation_arc(DVec3::Z, DVec3::Y), 0.05, 8))
            .collect();
        if top_first {
            keys.reverse();
            for key in &mut keys {
                key.rotation = DQuat::from_rotation_arc(DVec3::Z, DVec3::NEG_Y);
            }
        }
        keys
    };
    let bar = |from: DVec3, direction: DVec3| -> Vec<Key> {
        let rotation = DQuat::from_rotation_arc(DVec3::Z, direction);
        (0..3).map(|i| Key::circle(from + direction * (0.6 * i as f64), rotation, 0.02, 8)).collect()
    };
    let sweep = |name: &str, owns: bool, keys: Vec<Key>, parent: Option<&str>| RigSweep {
        name: name.into(),
        vertices: owns.then(|| VertexSelection::Indices(vec![])),
        keys,
        knots: None,
        parent: parent.map(|p| ParentLink { sweep: p.into(), kind: LinkKind::Branch }),
        falloff: 0.0,
        rotation: Default::default(),
    };
    Rig::new(vec![
        sweep("leg_a", true, leg(0.0, 0.0, false), None),
        sweep("front", false, bar(DVec3::new(0.0, 0.9, 0.0), DVec3::X), Some("leg_a")),
        sweep("leg_b", true, leg(1.0, 0.0, true), Some("front")),
        sweep("side", false, bar(DVec3::new(1.0, 0.9, 0.0), DVec3::Z), Some("leg_b")),
        sweep("leg_c", true, leg(1.0, 1.0, true), Some("side")),
        sweep("leg_d", true, leg(0.0, 1.0, false), None),
    ])
    .unwrap()
}

#[test]
fn virtual_sweeps_carry_a_leg_move_to_the_legs_they_join() {
    let rig = chair();
    let mut posing = Posing::new(&rig);
    let shift = DVec3::new(0.2, 0.0, -0.1);
    posing
        .apply(&Edit::MoveKey {
            sweep: "leg_a".into(),
            key: 0,
            translate: shift.to_array(),
            rotate: [0.0, 0.0, 0.0, 1.0],
            mode: KeyMode::Local,
        })
        .unwrap();
    let moved = |sweep: usize| posing.keys()[sweep][0].center - rig.sweeps()[sweep].keys[0].center;
    for joined in [2, 4] {
        assert!((moved(joined) - shift).length() < 1e-9, "{} moved by {}", rig.sweeps()[joined].name, moved(joined));
    }
    assert_eq!(posing.keys()[5], rig.sweeps()[5].keys, "leg_d is joined to nothing and stays");
}

#[test]
fn mesh_rule_keeps_the_enclosed_volume_of_the_closed_bunny() {
    let Some(path) = common::shared_mesh("bunny_closed.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let rig = common::axis_rig(&mesh, 7, 16);
    let owners = rig.owners(&mesh, "bunny").unwrap();
    let bindings = sweepffd::bind::MeshBindings::hard(sweepffd::bind::bind_vertices(
        rig.rest(),
        &owners,
        &mesh.positions,
        &|_| {},
    ));
    let bound = sweepffd::edit::BoundMesh { mesh: &mesh, bindings: &bindings };
    let rest_volume = mesh.enclosed_volume(&mesh.positions);
    let edits: Vec<Edit> =
        (2..5).map(|key| Edit::ScaleRadii { sweep: "body".into(), key, factor: 1.25, theta_range: None }).collect();
    let run = |rule: VolumeRule| -> f64 {
        let mut posing = Posing::new(&rig).with_mesh(bound.clone());
        posing.volume = rule;
        for edit in &edits {
            posing.apply(edit).unwrap();
        }
        bound.volume(&rig, posing.keys()).unwrap()
    };
    let (without, with) = (run(VolumeRule::None), run(VolumeRule::Mesh));
    println!("closed bunny: rest {rest_volume}, posed {without} without the rule, {with} with it");
    assert!(((without - rest_volume) / rest_volume).abs() > 0.10, "the pose must change the volume by over 10%");
    assert!(((with - rest_volume) / rest_volume).abs() <= 1e-3, "{with} vs {rest_volume}");
}

/// The ratio rule on a branch of zero radii says why it cannot keep the ratio (it printed the
/// target volume as NaN).
#[test]
fn ratio_rule_names_a_sweep_without_volume() {
    let straight = |x: f64, radius: f64| -> Vec<Key> {
        [0.0, 0.5, 1.0].iter().map(|&z| Key::circle(DVec3::new(x, 0.0, z), DQuat::IDENTITY, radius, 8)).collect()
    };
    let trunk = RigSweep::new("trunk", straight(0.0, 0.3)).owning(VertexSelection::Indices(vec![]));
    let branch = RigSweep::new("branch", straight(0.1, 0.0))
        .owning(VertexSelection::Indices(vec![]))
        .with_parent(ParentLink { sweep: "trunk".into(), kind: LinkKind::Branch });
    let rig = Rig::new(vec![trunk, branch]).unwrap();
    let mut posing = Posing::new(&rig);
    posing.volume = VolumeRule::Ratio;
    let grow = Edit::ScaleRadii { sweep: "trunk".into(), key: 1, factor: 1.2, theta_range: None };
    let error = posing.apply(&grow).unwrap_err();
    assert_eq!(
        error.to_string(),
        "the volume rule `ratio` cannot keep sweep \"branch\"'s volume in ratio: it had no volume before the edit"
    );
}
