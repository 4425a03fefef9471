//! `sweepffd autorig`: the command's report, rig file and errors; the empty rig it writes for a
//! sphere, which `deform` and `render` take as leaving the mesh as it is. The protrusions that
//! `fit::autorig` finds are the engine's tests (`src/fit/tests/autorig.rs`).

use crate::common;

use std::fs;

use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;

use common::sphere;

#[test]
fn a_bad_option_is_refused_naming_its_flag() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("sphere.obj");
    LoadedMesh::from(sphere(8, 16)).save(&mesh, &sphere(8, 16).positions).unwrap();
    let out = common::sweepffd(dir.path())
        .args(["autorig", "--mesh", "sphere.obj", "--min-length", "0", "--out", "rig.json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("--min-length must be a positive fraction of the mesh's size, found 0"), "{stderr}");
}

/// Runs `sweepffd autorig` on `mesh` in `dir`, writing `rig.json`: the sweeps it wrote (it
/// must succeed) and its stderr, then the report of the same run with `--json`.
fn autorig_command(dir: &std::path::Path, mesh: &str) -> (usize, String, serde_json::Value) {
    let out = common::sweepffd(dir).args(["autorig", "--mesh", mesh, "--out", "rig.json"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{stderr}");
    let written: serde_json::Value = serde_json::from_str(&fs::read_to_string(dir.join("rig.json")).unwrap()).unwrap();
    let sweeps = written["sweeps"].as_array().map_or(usize::MAX, Vec::len);
    let out = common::sweepffd(dir).args(["autorig", "--mesh", mesh, "--out", "rig.json", "--json"]).output().unwrap();
    (sweeps, stderr, serde_json::from_slice(&out.stdout).unwrap())
}

#[test]
fn the_command_writes_the_rig_and_reports_each_part() {
    let dir = tempfile::tempdir().unwrap();
    let ball = LoadedMesh::from(sphere(24, 48));
    ball.save(&dir.path().join("ball.obj"), &ball.mesh.positions).unwrap();
    let (sweeps, stderr, report) = autorig_command(dir.path(), "ball.obj");
    assert!(stderr.contains("ball.obj: found no protrusion"), "{stderr}");
    assert_eq!(sweeps, 0);
    assert_eq!(report["parts"].as_array().map(Vec::len), Some(0));
    assert_eq!(report["left_out"].as_array().map(Vec::len), Some(0));

    // The empty rig is usable: deform writes the mesh as it is, render draws it, both with a
    // notice; pose, which has no sweep to edit, refuses it with a clear error.
    let out = common::sweepffd(dir.path())
        .args(["deform", "--mesh", "ball.obj", "--rig", "rig.json", "--pose", "rig.json", "--out", "same.obj"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("rig.json: the rig has no sweeps; wrote the mesh unchanged to same.obj"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
    let same = Mesh::load(&dir.path().join("same.obj")).unwrap();
    let saved = Mesh::load(&dir.path().join("ball.obj")).unwrap();
    assert_eq!(same.positions, saved.positions);
    // render needs a GPU adapter (it skips with a notice when none exists).
    if common::gpu().is_some() {
        let out = common::sweepffd(dir.path())
            .args(["render", "--mesh", "ball.obj", "--rig", "rig.json", "--out", "ball.png", "--size", "64x48"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        assert!(stderr.contains("rig.json: the rig has no sweeps; drawing the mesh as it is"), "{stderr}");
        assert!(dir.path().join("ball.png").is_file());
    }
    fs::write(dir.path().join("edits.json"), "[]").unwrap();
    let out = common::sweepffd(dir.path())
        .args(["pose", "--rig", "rig.json", "--edits", "edits.json", "--out", "pose.json"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("rig.json: the rig has no sweeps"));

    fs::write(dir.path().join("empty.obj"), "# nothing\n").unwrap();
    let out =
        common::sweepffd(dir.path()).args(["autorig", "--mesh", "empty.obj", "--out", "empty.json"]).output().unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("empty.obj"), "the error names the file: {stderr}");
    assert!(!dir.path().join("empty.json").exists());
}

/// Each part's report says how many of its key sections are not star-shaped, as the fit found
/// them, and so its fit target (15% RMS |d| rather than 10%); the table says so only where some
/// are, and a notice names the sweeps that fit looser than their target: the bunny's ears have
/// crescent sections (its back ear at 11.5% is within its 15%), the chair's legs none, and the
/// faerie's −z forearm and hand, whose sections are not all star-shaped, is over its 15%.
#[test]
fn each_part_reports_its_sections_that_are_not_star_shaped_and_its_target() {
    let mut counts = Vec::new();
    for shared in ["bunny_closed.obj", "chair.off", "characters/faerie.obj"] {
        let Some(path) = common::shared_mesh(shared) else { return };
        let file = shared.rsplit('/').next().unwrap();
        let dir = tempfile::tempdir().unwrap();
        fs::copy(&path, dir.path().join(file)).unwrap();
        let out = common::sweepffd(dir.path()).args(["autorig", "--mesh", file, "--out", "rig.json"]).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{stderr}");
        let table = String::from_utf8_lossy(&out.stdout).into_owned();
        let (_, _, report) = autorig_command(dir.path(), file);
        let rigged = sweepffd::fit::autorig::autorig(&Mesh::load(&path).unwrap(), &Default::default()).unwrap();
        let parts = report["parts"].as_array().unwrap();
        assert_eq!(parts.len(), rigged.parts.len());
        let mut loose = Vec::new();
        for (part, fitted) in parts.iter().zip(&rigged.parts) {
            let count = part["sections_not_star_shaped"].as_u64().unwrap() as usize;
            let expected = fitted.fit.sections.iter().filter(|s| s.several_crossings > 0).count();
            assert_eq!(count, expected, "{file}: {part}");
            let target = if count > 0 { 0.15 } else { 0.10 };
            assert_eq!(part["target"].as_f64(), Some(target), "{file}: {part}");
            let named = |l: &&str| {
                l.strip_prefix(fitted.name.as_str()).is_some_and(|rest| rest.starts_with(':') || rest.starts_with(" ("))
            };
            let line = table.lines().find(named).unwrap();
            let said = format!("({count} of its {} sections not star-shaped)", fitted.fit.keys.len());
            assert_eq!(line.contains(&said), count > 0, "{line}");
            assert_eq!(line.contains("not star-shaped"), count > 0, "{line}");
            counts.push((file, count));
            // RMS |d| at the part's own vertices, and at those its sweep was fitted to (a
            // chain's link: its neighbours' within the overlap too).
            assert_eq!(part["rms_d"].as_f64(), Some(fitted.quality.rms_d), "{file}: {part}");
            assert_eq!(part["fitted_rms_d"].as_f64(), Some(fitted.fit.quality.rms_d), "{file}: {part}");
            assert_eq!(part["fitted_vertices"].as_u64(), Some(fitted.fit.quality.vertices as u64), "{file}: {part}");
            if fitted.quality.rms_d > target {
                loose.push(format!("{} ({:.1}% of {:.0}%)", fitted.name, 100.0 * fitted.quality.rms_d, 100.0 * target));
            }
        }
        let notice = stderr.lines().find(|l| l.contains("fit looser than their target"));
        eprintln!("{file}: {notice:?}");
        match notice {
            Some(notice) => {
                assert!(notice.ends_with(&format!(": {}", loose.join(", "))), "{notice}");
                assert!(notice.contains(&format!("{} of {} sweeps", loose.len(), parts.len())), "{notice}");
            }
            None => assert!(loose.is_empty(), "{file}: {loose:?}"),
        }
        assert_eq!(loose.is_empty(), file != "faerie.obj", "{file}: {loose:?}");
    }
    eprintln!("sections not star-shaped: {counts:?}");
    assert!(
        counts
            .iter()
            .filter(|(file, _)| *file != "faerie.obj")
            .all(|&(file, count)| (count > 0) == (file == "bunny_closed.obj")),
        "{counts:?}"
    );
}

/// A mesh whose protrusions are all left out (spot's coarse control cage: its two ears are a
/// few quads, no tube) gets an empty rig whose notice says so after naming each part left
/// out, not that it found none; `--json` lists them.
#[test]
fn a_mesh_whose_every_protrusion_is_left_out_says_so() {
    let Some(path) = common::shared_mesh("spot_control_mesh.obj") else { return };
    let dir = tempfile::tempdir().unwrap();
    fs::copy(&path, dir.path().join("cage.obj")).unwrap();
    let (sweeps, stderr, report) = autorig_command(dir.path(), "cage.obj");
    let lines: Vec<&str> = stderr.lines().collect();
    let left_out = lines.iter().filter(|l| l.contains("cage.obj: left out a part of")).count();
    assert!(left_out >= 1, "{stderr}");
    assert_eq!(lines.len(), left_out + 1, "{stderr}");
    let last = format!("notice: cage.obj: left out every protrusion found ({left_out}); wrote an empty rig");
    assert_eq!(lines.last().copied(), Some(last.as_str()), "the summary comes last: {stderr}");
    assert!(!stderr.contains("found no protrusion"), "{stderr}");
    assert_eq!(sweeps, 0);
    assert_eq!(report["parts"].as_array().map(Vec::len), Some(0));
    let listed = report["left_out"].as_array().unwrap();
    assert_eq!(listed.len(), left_out);
    // Each is loose, or too small to be fitted (null).
    for part in listed {
        let vertices = part["vertices"].as_u64().unwrap();
        match part["sections_rms_d"].as_f64() {
            Some(rms) => assert!(rms > sweepffd::fit::autorig::MAX_RMS, "{part}"),
            None if part["folded"].is_array() => {}
            None => assert!(vertices < sweepffd::fit::autorig::MIN_VERTICES as u64, "{part}"),
        }
        assert!(vertices >= 4 && part["tip"].is_u64(), "{part}");
    }
}

/// A flat mesh (a strip meshed in a plane, as a drawing's outline may be): the part found is
/// left out, its notice saying its sections have next to no area rather than a meaningless
/// percentage (they missed it by 53,045% of their mean radius), and the rig is empty.
#[test]
fn a_flat_mesh_is_left_out_as_flat() {
    let dir = tempfile::tempdir().unwrap();
    let (columns, rows) = (60, 6);
    let mut obj = String::new();
    for j in 0..=rows {
        for i in 0..=columns {
            obj += &format!("v {} {} 0\n", 0.25 * i as f64, 0.25 * j as f64);
        }
    }
    let at = |i: usize, j: usize| j * (columns + 1) + i + 1;
    for j in 0..rows {
        for i in 0..columns {
            obj += &format!(
                "f {} {} {}\nf {} {} {}\n",
                at(i, j),
                at(i + 1, j),
                at(i + 1, j + 1),
                at(i, j),
                at(i + 1, j + 1),
                at(i, j + 1)
            );
        }
    }
    fs::write(dir.path().join("flat.obj"), obj).unwrap();
    let (sweeps, stderr, report) = autorig_command(dir.path(), "flat.obj");
    assert_eq!(sweeps, 0, "{stderr}");
    assert!(stderr.contains("they have next to no area, a flat part"), "{stderr}");
    assert!(!stderr.contains("RMS |d| 5"), "no meaningless percentage: {stderr}");
    assert!(stderr.contains("left out every protrusion found (1); wrote an empty rig"), "{stderr}");
    assert_eq!(report["parts"].as_array().map(Vec::len), Some(0));
}
