//! `sweepffd pose`: edits applied through the command line, the pose it writes, and every error
//! of the edits contract (the pose is then not written).

use crate::common;

use std::fs;
use std::path::Path;

use glam::{DQuat, DVec3};
use sweepffd::formats::LoadedMesh;
use sweepffd::rig::{LinkKind, ParentLink, Rig, RigDocument, RigSweep};
use sweepffd::sweep::Key;
use sweepffd::synthetic::{Tube, tube_rig};

/// A tube with its rig (`rig.json`, one sweep `tube`) and a second rig (`family.json`) where a
/// short `arm` hangs from the tube as a branch.
fn scene(dir: &Path) {
    let tube = Tube { rings: 30, around: 16, length: 3.0, radius: 0.4 };
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.join("tube.obj"), &mesh.mesh.positions).unwrap();
    let rig = tube_rig(&tube, 5, 8);
    fs::write(dir.join("rig.json"), rig.to_document().to_json()).unwrap();
    let mut sweeps = rig.sweeps().to_vec();
    sweeps.push(arm(Some(("tube", LinkKind::Branch))));
    fs::write(dir.join("family.json"), Rig::new(sweeps).unwrap().to_document().to_json()).unwrap();
}

/// A virtual arm leaving the tube sideways at height 1.5.
fn arm(parent: Option<(&str, LinkKind)>) -> RigSweep {
    let rotation = DQuat::from_rotation_arc(DVec3::Z, DVec3::X);
    RigSweep {
        name: "arm".into(),
        vertices: None,
        keys: (0..3).map(|i| Key::circle(DVec3::new(0.2 + 0.5 * i as f64, 0.0, 1.5), rotation, 0.1, 8)).collect(),
        knots: None,
        parent: parent.map(|(sweep, kind)| ParentLink { sweep: sweep.into(), kind }),
        falloff: 0.0,
        rotation: Default::default(),
    }
}

fn pose(dir: &Path, rig: &str, edits: &str, extra: &[&str]) -> std::process::Output {
    fs::write(dir.join("edits.json"), edits).unwrap();
    common::sweepffd(dir)
        .args(["pose", "--rig", rig, "--edits", "edits.json", "--out", "pose.json"])
        .args(extra)
        .output()
        .unwrap()
}

fn fails(dir: &Path, rig: &str, edits: &str, expected: &str) {
    let output = pose(dir, rig, edits, &[]);
    assert_eq!(output.status.code(), Some(1), "{}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.starts_with(expected), "expected «{expected}…», got «{stderr}»");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(!dir.join("pose.json").exists(), "nothing is written");
}

const EDITS: &str = r#"[
    {"op": "move_key", "sweep": "tube", "key": 2, "rotate": [0, 0.2588, 0, 0.9659], "mode": "local"},
    {"op": "scale_radii", "sweep": "tube", "key": 4, "factor": 0.5},
    {"op": "drag_point", "sweep": "tube", "theta": 0, "t": 0.5, "to": [0.9, 0.2, 1.6]},
    {"op": "move_section", "sweep": "arm", "t": 1.0, "translate": [0, 0.3, 0]}
]"#;

/// The pose `sweepffd pose` wrote in `dir`, as sweeps of the rig `family.json`.
fn posed_family(dir: &Path) -> (Rig, Vec<sweepffd::sweep::Sweep>) {
    let document = RigDocument::parse(&fs::read_to_string(dir.join("pose.json")).unwrap()).unwrap();
    let rig = Rig::load(&dir.join("family.json")).unwrap();
    let posed = rig.pose_from_document(&document, None).unwrap();
    (rig, posed)
}

#[test]
fn pose_writes_a_pose_that_deform_takes() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let output = pose(dir.path(), "family.json", EDITS, &[]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let (_, posed) = posed_family(dir.path());
    // Only the virtual arm was edited after the drag, so the dragged point stays on target.
    let reached = posed[0].surface_point(0.0, 0.5);
    assert!(reached.distance(DVec3::new(0.9, 0.2, 1.6)) < 1e-4 * 3.0, "{reached}");
    let arm_end = posed[1].center(1.0);
    assert!(arm_end.distance(DVec3::new(1.2, 0.3, 1.5)) > 0.1, "the arm moved with the tube and its own edit");
    let deformed = common::sweepffd(dir.path())
        .args(["deform", "--mesh", "tube.obj", "--rig", "family.json", "--pose", "pose.json", "--out", "out.obj"])
        .args(["--backend", "cpu"])
        .output()
        .unwrap();
    assert!(deformed.status.success(), "{}", String::from_utf8_lossy(&deformed.stderr));
    assert!(dir.path().join("out.obj").exists());
}

/// A `bend` in an edits file: the tube (5 keys, along z) turned 90° about its cross-section's x
/// axis at its middle over half its length: its last key has turned by exactly 90° about x
/// (the rest frames are the identity), its first has not moved, and the keys between share the
/// turn.
#[test]
fn pose_applies_a_bend() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let edits = r#"[{"op": "bend", "sweep": "tube", "t": 0.5, "span": 0.5, "axis": [1, 0, 0], "angle_deg": 90}]"#;
    let output = pose(dir.path(), "rig.json", edits, &[]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let rig = Rig::load(&dir.path().join("rig.json")).unwrap();
    let document = RigDocument::parse(&fs::read_to_string(dir.path().join("pose.json")).unwrap()).unwrap();
    let posed = rig.pose_from_document(&document, None).unwrap();
    let (rest, posed) = (&rig.rest()[0], &posed[0]);
    let knots = rest.knots();
    assert_eq!(posed.center(0.0), rest.center(0.0));
    assert!(posed.orientation(0.0).angle_between(rest.orientation(0.0)) < 1e-12);
    let turned = posed.orientation(1.0) * rest.orientation(1.0).inverse();
    assert!(turned.angle_between(DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2)) < 1e-9, "{turned}");
    let steps: Vec<f64> = (1..5)
        .map(|i| posed.orientation(knots[i]).angle_between(posed.orientation(knots[i - 1])).to_degrees())
        .collect();
    assert!(steps.iter().all(|&s| s < 60.0), "no key takes most of the turn: {steps:?}");
}

/// A pose that folds its sweep is written, with a warning naming the sweep and where it folds;
/// `deform` warns of the same pose and writes the mesh; a gentle pose warns of nothing.
#[test]
fn a_folding_pose_is_written_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let tight = r#"[{"op": "move_key", "sweep": "tube", "key": 2, "rotate": [0.9063, 0, 0, 0.4226], "mode": "local"}]"#;
    let output = pose(dir.path(), "rig.json", tight, &[]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("warning: pose.json: sweep \"tube\" folds: its cross-sections cross for t in [0."),
        "{stderr}"
    );
    assert!(dir.path().join("pose.json").exists());
    let deformed = common::sweepffd(dir.path())
        .args(["deform", "--mesh", "tube.obj", "--rig", "rig.json", "--pose", "pose.json", "--out", "out.obj"])
        .args(["--backend", "cpu", "--quiet"])
        .output()
        .unwrap();
    assert!(deformed.status.success(), "{}", String::from_utf8_lossy(&deformed.stderr));
    assert!(String::from_utf8_lossy(&deformed.stderr).contains("warning: pose.json: sweep \"tube\" folds"));
    assert!(dir.path().join("out.obj").exists());
    let gentle = r#"[{"op": "bend", "sweep": "tube", "t": 0.5, "span": 0.5, "axis": [1, 0, 0], "angle_deg": 45}]"#;
    let output = pose(dir.path(), "rig.json", gentle, &[]);
    assert!(output.status.success());
    assert_eq!(String::from_utf8_lossy(&output.stderr), "");
}

#[test]
fn pose_with_the_total_rule_keeps_the_volume() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let edits = EDITS.replace("\"factor\": 0.5", "\"factor\": 2.5");
    let output = pose(dir.path(), "family.json", &edits, &["--volume", "total"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let (rig, posed) = posed_family(dir.path());
    // The tube is the only sweep that owns vertices, so it absorbs its own change.
    let (rest, after) = (rig.rest()[0].volume(), posed[0].volume());
    assert!(((after - rest) / rest).abs() < 1e-6, "rest {rest}, posed {after}");
    let without = pose(dir.path(), "family.json", &edits, &[]);
    assert!(without.status.success());
    let (_, free) = posed_family(dir.path());
    let change = (free[0].volume() - rest) / rest;
    assert!(change.abs() > 0.05, "{change}: the edits change the volume without the rule");
}

#[test]
fn unknown_sweep_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    fails(
        dir.path(),
        "rig.json",
        r#"[{"op": "scale_radii", "sweep": "neck", "key": 0, "factor": 2}]"#,
        "error: edits.json: edit 0 (scale_radii on \"neck\"): the rig has no sweep \"neck\"; nothing was written",
    );
}

#[test]
fn key_out_of_range_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    fails(
        dir.path(),
        "rig.json",
        r#"[{"op": "move_key", "sweep": "tube", "key": 1, "translate": [0, 0.1, 0]},
            {"op": "move_key", "sweep": "tube", "key": 5, "translate": [1, 0, 0]}]"#,
        "error: edits.json: edit 1 (move_key on \"tube\"): sweep \"tube\" has 5 keys, so there is no key 5",
    );
}

#[test]
fn edit_that_does_not_converge_names_the_remaining_distance() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    fails(
        dir.path(),
        "rig.json",
        r#"[{"op": "drag_point", "sweep": "tube", "theta": 0, "t": 0.5, "to": [40, 0, 1.5], "mode": "rotate", "keys": 1}]"#,
        "error: edits.json: edit 0 (drag_point on \"tube\"): did not converge in 50 iterations: still",
    );
}

#[test]
fn malformed_edits_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    fails(
        dir.path(),
        "rig.json",
        r#"[{"op": "twist", "sweep": "tube"}]"#,
        "error: edits.json: not a valid edits file: unknown variant `twist`",
    );
    fails(
        dir.path(),
        "rig.json",
        r#"[{"op": "scale_radii", "sweep": "tube", "key": 0, "factor": -1}]"#,
        "error: edits.json: edit 0 (scale_radii on \"tube\"): \"factor\" must be a positive number, found -1",
    );
    fails(
        dir.path(),
        "rig.json",
        r#"[{"op": "move_section", "sweep": "tube", "t": 1.5}]"#,
        "error: edits.json: edit 0 (move_section on \"tube\"): \"t\" must lie in [0, 1], found 1.5",
    );
    let bend = |fields: &str| format!(r#"[{{"op": "bend", "sweep": "tube", {fields}}}]"#);
    for (fields, expected) in [
        (
            r#""t": 0.5, "span": 0, "axis": [1, 0, 0], "angle_deg": 60"#,
            "\"span\" must be a positive width in t, found 0",
        ),
        (r#""t": 1.2, "span": 0.2, "axis": [1, 0, 0], "angle_deg": 60"#, "\"t\" must lie in [0, 1], found 1.2"),
        (r#""t": 0.5, "span": 0.2, "axis": [0, 0, 0], "angle_deg": 60"#, "\"axis\" must be a non-zero direction"),
        (r#""t": 0.5, "span": 0.2, "axis": [1, 0, 0], "angle_deg": 1e400"#, "not a valid edits file"),
    ] {
        let on = if expected.starts_with("not") { String::new() } else { " edit 0 (bend on \"tube\"):".into() };
        fails(dir.path(), "rig.json", &bend(fields), &format!("error: edits.json:{on} {expected}"));
    }
    fails(
        dir.path(),
        "rig.json",
        r#"[{"op": "bend", "sweep": "leg", "t": 0.5, "span": 0.2, "axis": [1, 0, 0], "angle_deg": 60}]"#,
        "error: edits.json: edit 0 (bend on \"leg\"): the rig has no sweep \"leg\"",
    );
}

/// Writes a rig of the tube sweep and `others` and runs a harmless edit on it.
fn rig_fails(others: Vec<RigSweep>, expected: &str) {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let mut document = RigDocument::parse(&fs::read_to_string(dir.path().join("rig.json")).unwrap()).unwrap();
    let mut sweeps: Vec<RigSweep> = Rig::from_document(&document, None).unwrap().sweeps().to_vec();
    sweeps.extend(others);
    // Written as a document directly: Rig::new would refuse these rigs.
    document.sweeps = sweeps
        .iter()
        .map(|s| sweepffd::rig::SweepDocument {
            name: s.name.clone(),
            vertices: s.vertices.clone(),
            keys: s.keys.iter().map(Into::into).collect(),
            knots: s.knots.clone(),
            parent: s.parent.clone(),
            falloff: (s.falloff > 0.0).then_some(s.falloff),
            rotation_interpolation: None,
        })
        .collect();
    fs::write(dir.path().join("bad.json"), document.to_json()).unwrap();
    fails(dir.path(), "bad.json", r#"[{"op": "scale_radii", "sweep": "tube", "key": 0, "factor": 1.1}]"#, expected);
}

#[test]
fn cycle_in_the_hierarchy_is_an_error() {
    let mut a = arm(Some(("b", LinkKind::Branch)));
    a.name = "a".into();
    let mut b = arm(Some(("a", LinkKind::Branch)));
    b.name = "b".into();
    rig_fails(vec![a, b], "error: bad.json: the hierarchy has a cycle: a → b → a");
}

#[test]
fn unknown_parent_is_an_error() {
    rig_fails(
        vec![arm(Some(("trunk", LinkKind::Branch)))],
        "error: bad.json: sweep \"arm\": its parent \"trunk\" is not a sweep of the rig",
    );
}

#[test]
fn loop_child_whose_keys_cannot_be_bound_is_an_error() {
    let mut handle = arm(Some(("tube", LinkKind::Loop)));
    // Its last key lies above the tube's top end: no cross-section plane of the tube reaches it.
    handle.keys[2].center = DVec3::new(0.5, 0.0, 4.5);
    rig_fails(
        vec![handle],
        "error: bad.json: sweep \"arm\": key 2 cannot be bound to its parent \"tube\": its center lies beyond the parent's ends",
    );
}

#[test]
fn loop_of_two_keys_is_an_error() {
    let mut handle = arm(Some(("tube", LinkKind::Loop)));
    handle.keys.truncate(2);
    rig_fails(vec![handle], "error: bad.json: sweep \"arm\": a loop child needs at least 3 keys");
}

#[test]
fn mesh_rule_without_a_mesh_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let output = pose(dir.path(), "rig.json", "[]", &["--volume", "mesh"]);
    assert_eq!(output.status.code(), Some(1));
    assert_eq!(String::from_utf8_lossy(&output.stderr), "error: --volume mesh needs --mesh\n");
}

/// The mesh rule keeps an enclosed volume, which an open mesh does not have: refused naming an
/// edge of its rim (it was accepted silently).
#[test]
fn mesh_rule_with_an_open_mesh_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    fs::write(dir.path().join("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n").unwrap();
    let output = pose(dir.path(), "rig.json", "[]", &["--volume", "mesh", "--mesh", "open.obj"]);
    assert_eq!(output.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&output.stderr),
        "error: open.obj: --volume mesh needs a closed mesh, but the edge between vertices 0 and 2 borders 1 face(s), \
         not 2\n"
    );
    assert!(!dir.path().join("pose.json").exists());
}
