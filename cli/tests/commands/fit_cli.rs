//! `sweepffd fit` through the command line: the rig it writes, appending to a rig, the fit
//! report, and its errors (after which nothing is written).

use crate::common;

use std::fs;
use std::path::Path;

use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::synthetic::Tube;

/// A tube of radius 0.4 along z from 0 to 3 (groups `wall` and `caps`), and two index files
/// splitting its wall at z = 1.5.
fn scene(dir: &Path) -> Mesh {
    let tube = Tube { rings: 40, around: 24, length: 3.0, radius: 0.4 };
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.join("tube.obj"), &mesh.mesh.positions).unwrap();
    let wall = mesh.mesh.group_vertices("wall").unwrap();
    let (lower, upper): (Vec<u32>, Vec<u32>) = wall.iter().partition(|&&v| mesh.mesh.positions[v as usize].z < 1.5);
    fs::write(dir.join("lower.json"), serde_json::to_string(&lower).unwrap()).unwrap();
    let spaced: Vec<String> = upper.iter().map(u32::to_string).collect();
    fs::write(dir.join("upper.txt"), spaced.join(" \n")).unwrap();
    mesh.mesh
}

fn fit(dir: &Path, args: &[&str]) -> std::process::Output {
    common::sweepffd(dir).args(["fit", "--mesh", "tube.obj"]).args(args).output().unwrap()
}

#[test]
fn fitting_a_group_writes_a_rig_whose_keys_match_the_tube() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let out = fit(dir.path(), &["--group", "wall", "--out", "rig.json"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("fit \"wall\": 960 vertices"), "{stdout}");
    assert!(stdout.contains("every vertex binds with a root"), "{stdout}");
    assert!(stdout.contains("step: rough sweep enclosing the part"), "{stdout}");
    let rig = Rig::load(&dir.path().join("rig.json")).unwrap();
    assert_eq!(rig.sweeps().len(), 1);
    let sweep = &rig.sweeps()[0];
    assert_eq!(sweep.name, "wall");
    for key in &sweep.keys {
        assert_eq!(key.radii.len(), 32);
        if (0.05..2.95).contains(&key.center.z) {
            // A polygon of 24 sides inscribed in the circle: its radius lies between the
            // apothem and the circumradius; the radii fitted to its vertices, which lie on the
            // circle, pass through them, and the periodic spline between them overshoots the
            // circle by at most 0.1%.
            for r in &key.radii {
                assert!((0.4 * (std::f64::consts::PI / 24.0).cos() - 1e-9..=0.4 * 1.001).contains(r), "{r}");
            }
        }
    }
}

#[test]
fn appending_builds_a_rig_of_several_sweeps() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = scene(dir.path());
    let out = fit(dir.path(), &["--indices", "lower.json", "--out", "rig.json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out =
        fit(dir.path(), &["--indices", "upper.txt", "--append-to", "rig.json", "--out", "rig.json", "--keys", "4"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let rig = Rig::load(&dir.path().join("rig.json")).unwrap();
    let names: Vec<&str> = rig.sweeps().iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["lower", "upper"]);
    let owners = rig.owners(&mesh, "tube.obj").unwrap();
    assert_eq!(owners.iter().filter(|&&o| o != sweepffd::bind::UNOWNED).count(), 960);

    // The same name again, or vertices another sweep owns: refused, the rig unchanged.
    let before = fs::read(dir.path().join("rig.json")).unwrap();
    let out = fit(dir.path(), &["--indices", "upper.txt", "--append-to", "rig.json", "--out", "rig.json"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("rig.json: the rig already has a sweep named \"upper\"; choose another with --name"),
        "{stderr}"
    );
    let out =
        fit(dir.path(), &["--indices", "upper.txt", "--name", "again", "--append-to", "rig.json", "--out", "rig.json"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("claimed"), "{stderr}");
    assert_eq!(fs::read(dir.path().join("rig.json")).unwrap(), before);
}

#[test]
fn bad_requests_name_what_is_wrong_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    fs::write(dir.path().join("bad.txt"), "1 2 x3").unwrap();
    fs::write(dir.path().join("far.txt"), "1 2 99999").unwrap();
    let cases: [(&[&str], &str); 10] = [
        (&[], "say which part to fit with --group or --indices"),
        (&["--group", "wall", "--indices", "lower.json"], "give either --group or --indices, not both"),
        (&["--group", "handle"], "tube.obj: no group \"handle\" (groups: wall, caps)"),
        (&["--indices", "bad.txt"], "bad.txt: \"x3\" is not a vertex index"),
        (&["--indices", "far.txt"], "far.txt: vertex 99999 is out of range: tube.obj has 962 vertices"),
        (&["--group", "wall", "--axis", "0,0,0;1,2"], "--axis: point 1 (\"1,2\") is not three finite numbers x,y,z"),
        (
            &["--group", "wall", "--keys", "1"],
            "tube.obj: fitting sweep \"wall\": --keys must be at least 2, found 1; nothing was written",
        ),
        (
            &["--group", "wall", "--falloff", "-1"],
            "tube.obj: fitting sweep \"wall\": --falloff must be a finite width of at least 0 (mesh units), found -1; nothing was written",
        ),
        (
            &["--group", "wall", "--falloff", "nan"],
            "--falloff must be a finite width of at least 0 (mesh units), found NaN",
        ),
        (
            &["--group", "wall", "--falloff", "inf"],
            "--falloff must be a finite width of at least 0 (mesh units), found inf",
        ),
    ];
    for (args, message) in cases {
        let out = fit(dir.path(), &[args, &["--out", "rig.json"]].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!dir.path().join("rig.json").exists(), "{args:?} wrote the rig");
    }
}

/// The chord length Σ |p_i − p_{i−1}| of a sweep's key centers.
fn chord_length(sweep: &sweepffd::rig::RigSweep) -> f64 {
    sweep.keys.windows(2).map(|pair| pair[0].center.distance(pair[1].center)).sum()
}

#[test]
fn the_falloff_is_a_fraction_of_the_parts_length_unless_given() {
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path());
    let out = fit(dir.path(), &["--group", "wall", "--out", "rig.json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let rig = Rig::load(&dir.path().join("rig.json")).unwrap();
    let (sweep, fraction) = (&rig.sweeps()[0], sweepffd::fit::DEFAULT_FALLOFF_FRACTION);
    assert!(
        (sweep.falloff - fraction * chord_length(sweep)).abs() < 1e-9,
        "{} of {}",
        sweep.falloff,
        chord_length(sweep)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let line = format!("  falloff {:.6} (default: {fraction} of the part's length)", sweep.falloff);
    assert!(stdout.contains(&line), "{stdout}");

    let out = fit(dir.path(), &["--group", "wall", "--falloff", "0.25", "--out", "given.json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(Rig::load(&dir.path().join("given.json")).unwrap().sweeps()[0].falloff, 0.25);
    assert!(String::from_utf8_lossy(&out.stdout).contains("  falloff 0.250000 (--falloff)"));

    // 0: a hard boundary, and the rig file leaves the field out.
    let out = fit(dir.path(), &["--group", "wall", "--falloff", "0", "--out", "hard.json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(Rig::load(&dir.path().join("hard.json")).unwrap().sweeps()[0].falloff, 0.0);
    assert!(!fs::read_to_string(dir.path().join("hard.json")).unwrap().contains("falloff"));
    assert!(String::from_utf8_lossy(&out.stdout).contains("  falloff 0: a hard boundary (--falloff)"));
}

#[test]
fn key_0_is_written_at_the_end_where_the_part_is_attached() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = scene(dir.path());
    // Each part takes one cap (the ring's vertices and its center) and is cut from the rest of
    // the wall at the other end: attached there only.
    let ring = |r: u32| r * 24..(r + 1) * 24;
    let lower: Vec<u32> = (0..30).flat_map(ring).chain([960]).collect();
    let upper: Vec<u32> = (10..40).flat_map(ring).chain([961]).collect();
    for (name, part, cut_z) in [("lower", lower, 29.0 * 3.0 / 39.0), ("upper", upper, 10.0 * 3.0 / 39.0)] {
        assert!(part.iter().all(|&v| (v as usize) < mesh.positions.len()));
        fs::write(dir.path().join(format!("{name}.json")), serde_json::to_string(&part).unwrap()).unwrap();
        let out = fit(dir.path(), &["--indices", &format!("{name}.json"), "--out", &format!("{name}-rig.json")]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(stdout.contains("key 0 at the attached end"), "{stdout}");
        let rig = Rig::load(&dir.path().join(format!("{name}-rig.json"))).unwrap();
        let keys = &rig.sweeps()[0].keys;
        let (first, last) = (keys[0].center.z, keys[keys.len() - 1].center.z);
        assert!((first - cut_z).abs() < (last - cut_z).abs(), "{name}: key 0 at z = {first}, the last at z = {last}");
    }
}
