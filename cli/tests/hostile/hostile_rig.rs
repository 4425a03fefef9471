//! Hostile rig, pose and edits files through `sweepffd pose` and `sweepffd volume`: each one
//! ends within a bounded time with one `error: …` line naming the file (and the sweep, key or
//! value at fault), or succeeds with finite values, and an error writes nothing.
//!
//! Each test runs in its own temporary folder with relative paths, so the messages are exact.

use crate::common;

use std::f64::consts::FRAC_1_SQRT_2;
use std::fs;
use std::path::Path;
use std::process::Output;
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use tempfile::TempDir;

/// The bound each command is held to. The contract is 1 s for 100 edits on 10 sweeps; the
/// bound is generous so that a loaded CI machine does not fail the test.
const TIME_BOUND: Duration = Duration::from_secs(5);

/// A key of `m` radii `r` (each ρ_j varied a little so the area is not constant).
fn key(center: [f64; 3], r: f64, rotation: [f64; 4], m: usize) -> Value {
    let radii: Vec<f64> = (0..m).map(|j| r * (1.0 + 0.1 * (j as f64).sin())).collect();
    json!({"center": center, "rotation": rotation, "radii": radii})
}

/// Rotation taking z onto x.
const TO_X: [f64; 4] = [0.0, FRAC_1_SQRT_2, 0.0, FRAC_1_SQRT_2];
const IDENTITY: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// A rig of five sweeps: `body` along z, `arm` a branch leaving it along x, `hand` a branch of
/// the arm, `handle` a loop on the body, and `joint` a virtual branch (it owns no vertices).
fn family() -> Value {
    let body: Vec<Value> = (0..5).map(|i| key([0.0, 0.0, i as f64], 1.0, IDENTITY, 8)).collect();
    let arm: Vec<Value> = (0..3).map(|i| key([0.5 + 0.6 * i as f64, 0.0, 2.0], 0.2, TO_X, 8)).collect();
    let hand: Vec<Value> = (0..3).map(|i| key([1.2 + 0.4 * i as f64, 0.0, 2.0], 0.1, TO_X, 8)).collect();
    let (s, c) = (FRAC_1_SQRT_2, FRAC_1_SQRT_2);
    let handle = vec![
        key([-0.5, 0.0, 1.0], 0.15, [0.0, -s, 0.0, c], 8),
        key([-1.5, 0.0, 2.0], 0.15, IDENTITY, 8),
        key([-0.5, 0.0, 3.0], 0.15, [0.0, s, 0.0, c], 8),
    ];
    let joint = vec![key([0.0, 0.5, 1.5], 0.05, [s, 0.0, 0.0, c], 8), key([0.0, 1.5, 1.5], 0.05, [s, 0.0, 0.0, c], 8)];
    json!({"format": "sweepffd-rig", "version": 1, "sweeps": [
        {"name": "body", "vertices": {"indices": [0]}, "keys": body},
        {"name": "arm", "vertices": {"indices": [1]}, "keys": arm, "parent": {"sweep": "body", "kind": "branch"}},
        {"name": "hand", "vertices": {"indices": [2]}, "keys": hand, "parent": {"sweep": "arm", "kind": "branch"}},
        {"name": "handle", "vertices": {"indices": [3]}, "keys": handle, "parent": {"sweep": "body", "kind": "loop"}},
        {"name": "joint", "keys": joint, "parent": {"sweep": "body", "kind": "branch"}},
    ]})
}

/// Ten sweeps of `keys` keys and `radii` radii: a root along z and nine branches along x.
fn ten_sweeps(keys: usize, radii: usize) -> Value {
    let along = |i: usize| i as f64 / (keys - 1) as f64;
    let mut sweeps = vec![json!({"name": "s0", "vertices": {"indices": [0]},
        "keys": (0..keys).map(|i| key([0.0, 0.0, 4.0 * along(i)], 1.0, IDENTITY, radii)).collect::<Vec<_>>()})];
    for n in 1..10 {
        let z = 0.3 + 0.37 * n as f64;
        sweeps.push(json!({"name": format!("s{n}"), "vertices": {"indices": [n]},
            "keys": (0..keys).map(|i| key([0.5 + along(i), 0.0, z], 0.1, TO_X, radii)).collect::<Vec<_>>(),
            "parent": {"sweep": "s0", "kind": "branch"}}));
    }
    json!({"format": "sweepffd-rig", "version": 1, "sweeps": sweeps})
}

/// A temporary folder in which the command line runs.
struct Scene {
    dir: TempDir,
}

impl Scene {
    fn new() -> Scene {
        let scene = Scene { dir: tempfile::tempdir().unwrap() };
        scene.write("rig.json", family().to_string());
        scene
    }

    fn path(&self) -> &Path {
        self.dir.path()
    }

    fn write(&self, name: &str, contents: impl AsRef<[u8]>) {
        fs::write(self.path().join(name), contents).unwrap();
    }

    /// Runs the command line and checks it ended within [`TIME_BOUND`].
    fn run(&self, args: &[&str]) -> Output {
        let start = Instant::now();
        let output = common::sweepffd(self.path()).args(args).output().unwrap();
        let elapsed = start.elapsed();
        assert!(elapsed < TIME_BOUND, "{args:?} took {elapsed:?}");
        output
    }

    /// `pose --rig rig --edits edits.json --out pose.json --volume volume`.
    fn pose(&self, rig: &str, edits: &str, volume: &str) -> Output {
        self.write("edits.json", edits);
        let _ = fs::remove_file(self.path().join("pose.json"));
        self.run(&["pose", "--rig", rig, "--edits", "edits.json", "--out", "pose.json", "--volume", volume])
    }

    /// The one line of stderr of a failed run, after checking that nothing was written.
    fn error(&self, output: &Output) -> String {
        let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
        assert_eq!(output.status.code(), Some(1), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(!self.path().join("pose.json").exists(), "nothing is written");
        let leftovers: Vec<_> = fs::read_dir(self.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|name| name.ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
        stderr
    }

    fn pose_fails(&self, rig: &str, edits: &str, volume: &str) -> String {
        let output = self.pose(rig, edits, volume);
        self.error(&output)
    }

    /// `volume --rig rig`, expected to fail.
    fn volume_fails(&self, rig: &str) -> String {
        let output = self.run(&["volume", "--rig", rig]);
        self.error(&output)
    }

    /// `volume --rig rig [--pose pose]`: every volume, after checking they are finite.
    fn volumes(&self, rig: &str, pose: Option<&str>) -> Vec<f64> {
        let mut args = vec!["volume", "--rig", rig];
        args.extend(pose.map(|p| ["--pose", p]).into_iter().flatten());
        let output = self.run(&args);
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let report: Value = serde_json::from_slice(&output.stdout).unwrap();
        let volumes: Vec<f64> =
            report["sweeps"].as_array().unwrap().iter().map(|s| s["volume"].as_f64().unwrap()).collect();
        assert!(volumes.iter().all(|v| v.is_finite()), "{volumes:?}");
        volumes
    }
}

/// A bad rig: its name, the change to the family rig, and the error it gives.
type RigCase = (&'static str, fn(&mut Value), &'static str);

/// The family rig with `edit` applied to its JSON.
fn family_with(edit: impl FnOnce(&mut Value)) -> String {
    let mut rig = family();
    edit(&mut rig);
    rig.to_string()
}

// Case 1: a child carried beyond the representable by its parent.

#[test]
fn a_child_carried_out_of_range_by_its_parent_is_named() {
    let scene = Scene::new();
    let edits = r#"[{"op": "move_key", "sweep": "body", "key": 0, "translate": [999999999999999.75, 0, 0]}]"#;
    for volume in ["none", "total", "ratio"] {
        assert_eq!(
            scene.pose_fails("rig.json", edits, volume),
            "error: edits.json: edit 0 (move_key on \"body\"): while keeping sweep \"arm\" attached in the \
             hierarchy: the keys no longer make a sweep: key 0: center coordinate 1.0000000000000003e15 lies beyond \
             ±1e15 mesh units, the largest a rig may have; nothing was written\n"
        );
    }
}

#[test]
fn an_edited_key_beyond_the_coordinate_limit_is_named() {
    let scene = Scene::new();
    let edits = r#"[{"op": "move_key", "sweep": "arm", "key": 1, "translate": [1e300, 0, 0]}]"#;
    assert_eq!(
        scene.pose_fails("rig.json", edits, "none"),
        "error: edits.json: edit 0 (move_key on \"arm\"): the keys no longer make a sweep: key 1: center coordinate \
         1e300 lies beyond ±1e15 mesh units, the largest a rig may have; nothing was written\n"
    );
    let edits = r#"[{"op": "scale_radii", "sweep": "body", "key": 2, "factor": 1e300}]"#;
    assert_eq!(
        scene.pose_fails("rig.json", edits, "total"),
        "error: edits.json: edit 0 (scale_radii on \"body\"): the keys no longer make a sweep: key 2: radius 0 \
         (1e300) is larger than 1e15 mesh units, the largest a rig may have; nothing was written\n"
    );
}

#[test]
fn every_pose_written_reads_back_with_finite_volumes() {
    let scene = Scene::new();
    let edits = r#"[{"op": "scale_radii", "sweep": "arm", "key": 1, "factor": 1e-300},
                    {"op": "move_key", "sweep": "body", "key": 1, "rotate": [1, 0, 0, 1e-9]},
                    {"op": "move_key", "sweep": "body", "key": 3, "translate": [1e14, 0, 0], "mode": "independent"}]"#;
    let output = scene.pose("rig.json", edits, "none");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let text = fs::read_to_string(scene.path().join("pose.json")).unwrap();
    assert!(!text.contains("null"), "{text}");
    scene.volumes("rig.json", Some("pose.json"));
}

// Case 7: edits that ran for minutes.

/// Edits files an attacker would try, with the result each gives under every volume rule:
/// all end within [`TIME_BOUND`], and a failing one names its index, op and sweep.
fn adversarial_edits() -> Vec<(&'static str, String)> {
    let s = FRAC_1_SQRT_2;
    // Keys turned a quarter about x on their own: the body's normals lie across its travel, so
    // its volume cancels to near zero (this took over 200 s before the quadrature was bounded).
    let mut across: Vec<Value> = (0..5)
        .map(|k| json!({"op": "move_key", "sweep": "body", "key": k, "rotate": [s, 0.001 * k as f64, 0, s], "mode": "independent"}))
        .collect();
    across.push(json!({"op": "scale_radii", "sweep": "arm", "key": 1, "factor": 1.3, "theta_range": [0, 2]}));
    let many_on_one_key = vec![
        json!({"op": "move_key", "sweep": "body", "key": 2, "translate": [0.01, 0, 0], "rotate": [0.01, 0, 0, 1]});
        100
    ];
    let many_drags: Vec<Value> = (0..100)
        .map(|i| json!({"op": "drag_point", "sweep": "arm", "theta": 0, "t": 0.7, "to": [1.0 + 0.01 * i as f64, 0.5, 2.5]}))
        .collect();
    vec![
        ("quarter turns", Value::from(across).to_string()),
        ("many on one key", Value::from(many_on_one_key).to_string()),
        ("many drags", Value::from(many_drags).to_string()),
        ("tiny scale", r#"[{"op": "scale_radii", "sweep": "body", "key": 2, "factor": 1e-300}]"#.into()),
        ("huge angle", r#"[{"op": "move_key", "sweep": "body", "key": 1, "rotate": [1, 0, 0, 1e-300]}]"#.into()),
        ("far drag", r#"[{"op": "drag_point", "sweep": "body", "theta": 0, "t": 0.5, "to": [1e300, 1e300, 0]}]"#.into()),
        (
            "far drag on many keys",
            r#"[{"op": "drag_point", "sweep": "arm", "theta": 1e300, "t": 0.9, "to": [1e12, -1e12, 3], "keys": 1000000}]"#.into(),
        ),
        (
            "far section",
            r#"[{"op": "move_section", "sweep": "arm", "t": 0.3, "translate": [1e200, 0, 0], "rotate": [0, 1, 0, 0]}]"#.into(),
        ),
        (
            "loop section",
            r#"[{"op": "move_section", "sweep": "handle", "t": 0.5, "translate": [0, 30, 0], "rotate": [1, 1, 0, 0]}]"#.into(),
        ),
    ]
}

#[test]
fn adversarial_edits_end_in_bounded_time_with_a_named_edit_or_a_finite_pose() {
    let scene = Scene::new();
    for (name, edits) in adversarial_edits() {
        for volume in ["none", "total", "ratio"] {
            let output = scene.pose("rig.json", &edits, volume);
            if output.status.success() {
                let text = fs::read_to_string(scene.path().join("pose.json")).unwrap();
                assert!(!text.contains("null"), "{name}, --volume {volume}: {text}");
                scene.volumes("rig.json", Some("pose.json"));
            } else {
                let error = scene.error(&output);
                assert!(error.starts_with("error: edits.json: edit "), "{name}, --volume {volume}: {error}");
                assert!(error.contains(" on \""), "{name}, --volume {volume}: {error}");
            }
        }
    }
}

#[test]
fn quarter_turned_keys_fail_the_volume_rules_naming_the_volume() {
    let scene = Scene::new();
    let (_, edits) = adversarial_edits().remove(0);
    assert_eq!(
        scene.pose_fails("rig.json", &edits, "total"),
        "error: edits.json: edit 5 (scale_radii on \"arm\"): the volume rule cannot give sweep \"body\" the volume \
         -1.104719e-1; nothing was written\n"
    );
}

#[test]
fn a_drag_that_cannot_converge_names_the_distance_left() {
    let scene = Scene::new();
    let edits =
        r#"[{"op": "drag_point", "sweep": "arm", "theta": 1, "t": 0.9, "to": [1e12, -1e12, 3], "keys": 1000000}]"#;
    assert_eq!(
        scene.pose_fails("rig.json", edits, "none"),
        "error: edits.json: edit 0 (drag_point on \"arm\"): did not converge in 50 iterations: still 1.200e-2 from \
         the target and 0.000e0 rad off; nothing was written\n"
    );
}

#[test]
fn a_hundred_edits_on_ten_sweeps_end_in_bounded_time() {
    let scene = Scene::new();
    scene.write("ten.json", ten_sweeps(16, 32).to_string());
    let drags: Vec<Value> = (0..100)
        .map(|i| {
            json!({"op": "drag_point", "sweep": format!("s{}", i % 10), "theta": 1.0, "t": 0.95,
                        "to": [0.3, 0.2 * (i % 3) as f64, 1.0 + 0.01 * i as f64], "keys": 16})
        })
        .collect();
    let sections: Vec<Value> = (0..100)
        .map(|i| json!({"op": "move_section", "sweep": format!("s{}", i % 10), "t": 0.5, "translate": [0.01, 0, 0], "rotate": [0.05, 0, 0, 1]}))
        .collect();
    let scales: Vec<Value> = (0..100)
        .map(|i| json!({"op": "scale_radii", "sweep": format!("s{}", i % 10), "key": i % 16, "factor": 1.05}))
        .collect();
    for edits in [drags, sections, scales] {
        for volume in ["none", "total", "ratio"] {
            let output = scene.pose("ten.json", &Value::from(edits.clone()).to_string(), volume);
            if !output.status.success() {
                let error = scene.error(&output);
                assert!(error.starts_with("error: edits.json: edit "), "{error}");
            }
        }
    }
}

#[test]
fn an_edits_file_over_the_limit_is_refused_while_read() {
    let scene = Scene::new();
    let edit = r#"{"op": "scale_radii", "sweep": "body", "key": 0, "factor": 1}"#;
    let edits = format!("[{}]", vec![edit; sweepffd::limits::MAX_EDITS + 1].join(","));
    let error = scene.pose_fails("rig.json", &edits, "none");
    assert!(
        error.starts_with(
            "error: edits.json: not a valid edits file: edits: more than 10000 values (the most an edits file may have) \
             at line 1 column "
        ),
        "{error}"
    );
}

#[test]
fn deep_nesting_in_an_edit_hits_the_recursion_limit() {
    let scene = Scene::new();
    let edits =
        format!(r#"[{{"sweep": "body", "deep": {}{}, "op": "move_key"}}]"#, "[".repeat(100_000), "]".repeat(100_000));
    assert_eq!(
        scene.pose_fails("rig.json", &edits, "none"),
        "error: edits.json: not a valid edits file: recursion limit exceeded at line 1 column 153\n"
    );
}

// Case 9: lists too long for their limits, refused while read.

#[test]
fn ten_million_radii_are_refused_at_the_first_radius_over_the_limit() {
    let scene = Scene::new();
    let radii = vec!["1"; 10_000_000].join(",");
    let rig = family().to_string().replacen("\"radii\":[", &format!("\"radii\":[{radii},"), 1);
    scene.write("big.json", rig);
    let error = scene.volume_fails("big.json");
    assert!(
        error.starts_with(
            "error: big.json: not a valid rig file: sweeps[0].keys[0].radii: more than 4096 values (the most a key may \
             have) at line 1 column "
        ),
        "{error}"
    );
}

#[test]
fn too_many_keys_sweeps_or_radii_in_all_are_refused() {
    let scene = Scene::new();
    let keys = family_with(|rig| {
        let key = rig["sweeps"][2]["keys"][0].clone();
        rig["sweeps"][2]["keys"] = Value::from(vec![key; 1025]);
    });
    scene.write("keys.json", keys);
    let error = scene.volume_fails("keys.json");
    assert!(
        error.starts_with(
            "error: keys.json: not a valid rig file: sweeps[2].keys: more than 1024 values (the most a sweep may have)"
        ),
        "{error}"
    );
    let sweeps = family_with(|rig| {
        let sweep = rig["sweeps"][0].clone();
        rig["sweeps"] = Value::from(vec![sweep; 257]);
    });
    scene.write("sweeps.json", sweeps);
    let error = scene.volume_fails("sweeps.json");
    assert!(
        error.starts_with(
            "error: sweeps.json: not a valid rig file: sweeps: more than 256 values (the most a rig may have)"
        ),
        "{error}"
    );
    // 300 keys of 4000 radii: each list within its limit, 1.2 million radii in all.
    let total = family_with(|rig| {
        let key = key([0.0, 0.0, 0.0], 1.0, IDENTITY, 4000);
        rig["sweeps"][0]["keys"] = Value::from(vec![key; 300]);
    });
    scene.write("total.json", total);
    let error = scene.volume_fails("total.json");
    assert!(
        error.starts_with(
            "error: total.json: not a valid rig file: sweeps[0].keys[262].radii: the rig holds more than 1048576 radii \
             in all (the most a rig may have)"
        ),
        "{error}"
    );
}

// Case 11: knots and other fields that made evaluation blow up.

#[test]
fn knots_closer_than_the_minimum_spacing_are_refused() {
    let scene = Scene::new();
    scene.write("knots.json", family_with(|rig| rig["sweeps"][0]["knots"] = json!([0, 1e-300, 0.5, 0.7, 1])));
    assert_eq!(
        scene.volume_fails("knots.json"),
        "error: knots.json: sweep \"body\": knot 1 (1e-300) is less than 1e-6 above the knot before it (0e0); knots \
         must be at least that far apart\n"
    );
    scene.write("near.json", family_with(|rig| rig["sweeps"][0]["keys"][1]["center"] = json!([0, 0, 1e-9])));
    assert_eq!(
        scene.volume_fails("near.json"),
        "error: near.json: sweep \"body\": key 1: center lies 2.5e-10 of the sweep's chord length from the center of \
         key 0; the chord-length knots need at least 1e-6\n"
    );
}

#[test]
fn fields_that_would_overflow_evaluation_are_refused() {
    let scene = Scene::new();
    let cases: [RigCase; 5] = [
        (
            "center",
            |rig| rig["sweeps"][0]["keys"][4]["center"] = json!([0, 0, 1e300]),
            "sweep \"body\": key 4: center coordinate 1e300 lies beyond ±1e15 mesh units, the largest a rig may have",
        ),
        (
            "radius",
            |rig| rig["sweeps"][1]["keys"][1]["radii"][3] = json!(1e160),
            "sweep \"arm\": key 1: radius 3 (1e160) is larger than 1e15 mesh units, the largest a rig may have",
        ),
        (
            "huge rotation",
            |rig| rig["sweeps"][0]["keys"][2]["rotation"] = json!([1e200, 0, 0, 1]),
            "sweep \"body\": key 2: rotation cannot be normalized: its squared length inf under- or overflows",
        ),
        (
            "tiny rotation",
            |rig| rig["sweeps"][0]["keys"][2]["rotation"] = json!([1e-160, 0, 0, 0]),
            "sweep \"body\": key 2: rotation cannot be normalized: its squared length 1e-320 under- or overflows",
        ),
        ("empty keys", |rig| rig["sweeps"][3]["keys"] = json!([]), "sweep \"handle\": needs at least 2 keys, found 0"),
    ];
    for (name, edit, message) in cases {
        scene.write("bad.json", family_with(edit));
        assert_eq!(scene.volume_fails("bad.json"), format!("error: bad.json: {message}\n"), "{name}");
    }
}

#[test]
fn infinity_spelled_as_a_big_number_is_a_parse_error() {
    let scene = Scene::new();
    scene.write("inf.json", family().to_string().replacen("1.0", "1e999", 1));
    let error = scene.volume_fails("inf.json");
    assert!(
        error.starts_with("error: inf.json: not a valid rig file: number out of range at line 1 column "),
        "{error}"
    );
}

#[test]
fn a_volume_whose_normals_lie_across_its_travel_is_quick_and_near_zero() {
    let scene = Scene::new();
    let s = FRAC_1_SQRT_2;
    scene.write(
        "across.json",
        family_with(|rig| {
            rig["sweeps"] = json!([rig["sweeps"][0]]);
            for k in 0..5 {
                rig["sweeps"][0]["keys"][k]["rotation"] = json!([s, 0.001 * k as f64, 0, s]);
            }
        }),
    );
    let volumes = scene.volumes("across.json", None);
    assert!(volumes[0].abs() < 1e-4, "{volumes:?}");
}

// The hierarchy and names.

#[test]
fn hierarchy_mistakes_are_named() {
    let scene = Scene::new();
    let cases: [RigCase; 5] = [
        (
            "self-parent",
            |rig| rig["sweeps"][0]["parent"] = json!({"sweep": "body", "kind": "branch"}),
            "the hierarchy has a cycle: body → body",
        ),
        (
            "cycle",
            |rig| rig["sweeps"][0]["parent"] = json!({"sweep": "hand", "kind": "branch"}),
            "the hierarchy has a cycle: body → hand → arm → body",
        ),
        (
            "missing parent",
            |rig| rig["sweeps"][1]["parent"] = json!({"sweep": "torso", "kind": "branch"}),
            "sweep \"arm\": its parent \"torso\" is not a sweep of the rig",
        ),
        ("duplicate name", |rig| rig["sweeps"][2]["name"] = json!("arm"), "two sweeps are named \"arm\""),
        ("no sweeps", |rig| rig["sweeps"] = json!([]), "the rig has no sweeps"),
    ];
    for (name, edit, message) in cases {
        scene.write("bad.json", family_with(edit));
        assert_eq!(scene.volume_fails("bad.json"), format!("error: bad.json: {message}\n"), "{name}");
    }
}

#[test]
fn unicode_names_pass_through() {
    let scene = Scene::new();
    let rig = family().to_string().replace("\"arm\"", "\"腕 🦾\"");
    scene.write("unicode.json", rig);
    let edits = r#"[{"op": "scale_radii", "sweep": "腕 🦾", "key": 1, "factor": 1.2}]"#;
    let output = scene.pose("unicode.json", edits, "ratio");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(fs::read_to_string(scene.path().join("pose.json")).unwrap().contains("腕 🦾"));
}
