//! Files with very many groups: an OBJ with a `g` statement before each of its 200,000 faces.
//! Binding a rig to it costs time linear in the groups (it was quadratic: 37–65 s on two
//! cores), and an error that lists the groups names a few and counts the rest (it was one line
//! of every name, a megabyte at 100,000 groups).

use std::fmt::Write as _;
use std::time::{Duration, Instant};

use crate::common;

/// Faces (each in a group of its own) of the file below.
const GROUPS: usize = 200_000;

/// Far more than linear work needs (under half a second on two cores), far less than the
/// quadratic cost was.
const DEADLINE: Duration = Duration::from_secs(10);

/// The longest error line accepted.
const MAX_LINE: usize = 1024;

/// A folder with `groups.obj` (four vertices, [`GROUPS`] triangles, `g gI` before each) and
/// the rigs `named.json` (one sweep owning the groups `g199999` and `g5`) and `missing.json`
/// (one sweep owning the group `nosuch`).
fn scene() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
    for g in 0..GROUPS {
        writeln!(obj, "g g{g}\nf 1 2 3").unwrap();
    }
    std::fs::write(dir.path().join("groups.obj"), obj).unwrap();
    let key = |z| format!(r#"{{"center": [0, 0, {z}], "rotation": [0, 0, 0, 1], "radii": [1, 1, 1]}}"#);
    let keys = format!("[{}, {}]", key(0), key(1));
    for (name, groups) in [("named", r#"["g199999", "g5"]"#), ("missing", r#"["nosuch"]"#)] {
        let rig = format!(
            r#"{{"format": "sweepffd-rig", "version": 1, "sweeps": [{{"name": "s", "vertices": {{"groups": {groups}}}, "keys": {keys}}}]}}"#
        );
        std::fs::write(dir.path().join(format!("{name}.json")), rig).unwrap();
    }
    dir
}

#[test]
fn a_rig_binds_to_two_hundred_thousand_groups_in_linear_time() {
    let dir = scene();
    let start = Instant::now();
    let out = common::sweepffd(dir.path())
        .args(["deform", "--mesh", "groups.obj", "--rig", "named.json", "--pose", "named.json", "--out", "out.obj"])
        .args(["--backend", "cpu"])
        .output()
        .unwrap();
    let took = start.elapsed();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    eprintln!("deform of {GROUPS} groups: {took:?}");
    assert!(took < DEADLINE, "deform of {GROUPS} groups took {took:?}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("deformed 3 of 4 vertices"), "{stdout}");
}

#[test]
fn a_missing_group_is_named_with_a_few_of_the_others() {
    let dir = scene();
    let out = common::sweepffd(dir.path())
        .args(["deform", "--mesh", "groups.obj", "--rig", "missing.json", "--pose", "missing.json", "--out", "out.obj"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        stderr,
        "error: missing.json: sweep \"s\": the mesh groups.obj has no group \"nosuch\" (its groups: g0, g1, g2, g3, g4, \
         g5, g6, g7, … and 199,992 more)\n"
    );
    let out = common::sweepffd(dir.path())
        .args(["fit", "--mesh", "groups.obj", "--group", "nosuch", "--out", "fit.json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no group \"nosuch\" (groups: g0, g1,"), "{stderr}");
    for line in stderr.lines() {
        assert!(line.len() <= MAX_LINE, "an error line of {} bytes", line.len());
    }
}
