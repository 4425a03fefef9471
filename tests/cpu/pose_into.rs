//! [`Rig::pose_into`] against [`Rig::pose`]: bit-identical sweeps on flat rigs and on a
//! hierarchy (a branch, a loop and a virtual parent, moved through their links by edits of the
//! root), and the same error for every kind of bad pose.

use glam::{DQuat, DVec3};
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::rig::{LinkKind, ParentLink, PoseBuffer, Rig, RigSweep, VertexSelection};
use sweepffd::sweep::{Key, Sweep};
use sweepffd::synthetic::{BendTwistTaper, Tube, split_tube_rig, tube_rig};

fn sweep(name: &str, keys: Vec<Key>, parent: Option<(&str, LinkKind)>, owns: bool) -> RigSweep {
    RigSweep {
        name: name.to_string(),
        vertices: owns.then(|| VertexSelection::Indices(vec![])),
        keys,
        knots: None,
        parent: parent.map(|(sweep, kind)| ParentLink { sweep: sweep.to_string(), kind }),
        falloff: 0.0,
        rotation: Default::default(),
    }
}

fn circle(center: [f64; 3], rotation: DQuat, radius: f64, samples: usize) -> Key {
    Key::circle(DVec3::from_array(center), rotation, radius, samples)
}

/// A trunk along z (root); a branch leaving it sideways; a loop (a handle) from one of its
/// cross-sections to another; a virtual sweep (owning no vertices) parented to the trunk, and a
/// leaf branching off the virtual sweep.
fn hierarchy() -> Rig {
    let up = DQuat::IDENTITY;
    let side = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
    let trunk = (0..5).map(|i| circle([0.0, 0.0, i as f64], up, 0.5, 8)).collect();
    let branch = (0..3).map(|i| circle([0.2 + 0.6 * i as f64, 0.0, 1.5], side, 0.2, 6)).collect();
    let handle = vec![
        circle([0.0, 0.2, 1.0], up, 0.1, 5),
        circle([0.0, 1.2, 1.6], up, 0.1, 5),
        circle([0.0, 1.2, 2.4], up, 0.1, 5),
        circle([0.0, 0.2, 3.0], up, 0.1, 5),
    ];
    let hidden = (0..3).map(|i| circle([-0.2 - 0.5 * i as f64, 0.0, 3.5], side, 0.3, 4)).collect();
    let leaf = (0..2).map(|i| circle([-0.8 - 0.4 * i as f64, 0.0, 3.5], side, 0.1, 7)).collect();
    Rig::new(vec![
        sweep("trunk", trunk, None, true),
        sweep("branch", branch, Some(("trunk", LinkKind::Branch)), true),
        sweep("handle", handle, Some(("trunk", LinkKind::Loop)), true),
        sweep("hidden", hidden, Some(("trunk", LinkKind::Branch)), false),
        sweep("leaf", leaf, Some(("hidden", LinkKind::Branch)), true),
    ])
    .unwrap()
}

/// The same sweeps, every bit (`Debug` of f64 tells -0 from 0; `==` would not).
fn assert_bit_identical(actual: &[Sweep], expected: &[Sweep], what: &str) {
    assert_eq!(actual.len(), expected.len(), "{what}: sweep count");
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        assert_eq!(format!("{a:?}"), format!("{e:?}"), "{what}: sweep {i}");
    }
}

fn pose_both(rig: &Rig, keys: &[Vec<Key>], buffer: &mut PoseBuffer, what: &str) {
    rig.pose_into(keys, buffer).unwrap();
    assert_bit_identical(buffer, &rig.pose(keys).unwrap(), what);
}

#[test]
fn a_fresh_buffer_holds_the_rest_sweeps() {
    let rig = hierarchy();
    assert_bit_identical(&rig.pose_buffer(), rig.rest(), "fresh buffer");
}

#[test]
fn pose_into_matches_pose_on_flat_rigs_frame_after_frame() {
    let tube = Tube { rings: 9, around: 12, length: 4.0, radius: 0.5 };
    for rig in [tube_rig(&tube, 8, 16), split_tube_rig(&tube, 4, 16, 0.3)] {
        let mut buffer = rig.pose_buffer();
        for frame in 0..4 {
            let f = frame as f64;
            let pose = BendTwistTaper { bend: 0.4 * f, twist: -0.3 * f, taper: 1.0 - 0.1 * f };
            pose_both(&rig, &pose.keys(&rig), &mut buffer, &format!("frame {frame}"));
        }
    }
}

#[test]
fn pose_into_matches_pose_on_a_hierarchy_moved_through_its_links() {
    let rig = hierarchy();
    let mut posing = Posing::new(&rig);
    let mut buffer = rig.pose_buffer();
    let edits = [
        Edit::MoveKey {
            sweep: "trunk".into(),
            key: 2,
            translate: [0.3, -0.1, 0.2],
            rotate: DQuat::from_rotation_x(0.4).to_array(),
            mode: KeyMode::Local,
        },
        Edit::ScaleRadii { sweep: "trunk".into(), key: 3, factor: 1.3, theta_range: None },
        Edit::MoveKey {
            sweep: "hidden".into(),
            key: 2,
            translate: [-0.2, 0.3, 0.0],
            rotate: DQuat::from_rotation_z(0.5).to_array(),
            mode: KeyMode::Local,
        },
    ];
    for edit in &edits {
        posing.apply(edit).unwrap();
        pose_both(&rig, posing.keys(), &mut buffer, edit.op());
    }
    assert_ne!(posing.keys()[1][0], rig.sweeps()[1].keys[0], "the branch followed the trunk");
    assert_ne!(posing.keys()[4][0], rig.sweeps()[4].keys[0], "the leaf followed the virtual sweep");
}

#[test]
fn a_buffer_of_another_rig_is_resized_to_this_one() {
    let rig = hierarchy();
    let other = tube_rig(&Tube { rings: 3, around: 8, length: 2.0, radius: 0.5 }, 3, 9);
    let mut buffer = other.pose_buffer();
    let keys: Vec<Vec<Key>> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
    pose_both(&rig, &keys, &mut buffer, "resized");
}

#[test]
fn pose_into_takes_key_slices() {
    let rig = hierarchy();
    let keys: Vec<Vec<Key>> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
    let slices: Vec<&[Key]> = keys.iter().map(Vec::as_slice).collect();
    let mut buffer = rig.pose_buffer();
    rig.pose_into(&slices, &mut buffer).unwrap();
    assert_bit_identical(&buffer, &rig.pose(&keys).unwrap(), "slices");
}

#[test]
fn bad_poses_fail_with_the_errors_of_pose_and_leave_the_buffer_alone() {
    let rig = hierarchy();
    let rest: Vec<Vec<Key>> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
    let spoil = |sweep: usize, change: &dyn Fn(&mut Vec<Key>)| {
        let mut keys = rest.clone();
        change(&mut keys[sweep]);
        keys
    };
    let cases: Vec<(&str, Vec<Vec<Key>>)> = vec![
        ("missing sweep", rest[..3].to_vec()),
        ("no sweeps", Vec::new()),
        ("key count", spoil(1, &|k| k.truncate(2))),
        ("radius count", spoil(2, &|k| k[1].radii.push(0.1))),
        ("negative radius", spoil(4, &|k| k[1].radii[0] = -1.0)),
        ("non-finite center", spoil(0, &|k| k[3].center.y = f64::NAN)),
        ("zero rotation", spoil(3, &|k| k[0].rotation = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0))),
        ("far center", spoil(0, &|k| k[0].center.x = 1e16)),
        ("two errors: the first sweep's is named", {
            let mut keys = spoil(4, &|k| k[0].radii[0] = -1.0);
            keys[1][0].center.z = f64::INFINITY;
            keys
        }),
    ];
    let posed = BendTwistTaper { bend: 0.3, twist: 0.2, taper: 0.9 }.keys(&rig);
    let mut buffer = rig.pose_buffer();
    rig.pose_into(&posed, &mut buffer).unwrap();
    let before = format!("{:?}", buffer.sweeps());
    for (what, keys) in cases {
        let expected = rig.pose(&keys).expect_err(what).to_string();
        let found = rig.pose_into(&keys, &mut buffer).expect_err(what).to_string();
        assert_eq!(found, expected, "{what}");
        assert_eq!(format!("{:?}", buffer.sweeps()), before, "{what}: the buffer changed");
    }
}
