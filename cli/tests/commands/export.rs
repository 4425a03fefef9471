//! `sweepffd export`: a mesh, its rig and poses as one glTF animation. The demo tube with 5 poses
//! and the bunny's autorig with 3: each morph target, read back with the `gltf` crate (sparse
//! accessors expanded), puts every vertex where `sweepffd deform` of that pose puts it, within
//! 1e-6 of the diagonal; the animation's keyframes turn the targets on one by one; the Khronos
//! glTF validator reports no error and no warning (`cli/tests/gltf-validator`: `npm ci` there;
//! without it the check prints why and is skipped, and fails under `CI=true`).

use crate::common;

use std::fs;
use std::path::Path;

use glam::DVec3;
use sweepffd::formats::LoadedMesh;

use common::sweepffd;

/// Runs the Khronos validator on `file`: `None` (with a notice) where it is not installed.
fn validator_report(file: &Path) -> Option<serde_json::Value> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gltf-validator");
    let missing = if !folder.join("node_modules/gltf-validator").exists() {
        Some("the npm package gltf-validator is not installed (npm ci in cli/tests/gltf-validator)".to_string())
    } else {
        None
    };
    let run = || std::process::Command::new("node").arg(folder.join("validate.mjs")).arg(file).output();
    let output = match (missing, run()) {
        (None, Ok(output)) if output.status.success() => output,
        (None, Ok(output)) => panic!("the validator failed: {}", String::from_utf8_lossy(&output.stderr)),
        (None, Err(error)) => return skip(&format!("node cannot run ({error})")),
        (Some(why), _) => return skip(&why),
    };
    Some(serde_json::from_slice(&output.stdout).expect("the validator prints JSON"))
}

fn skip(why: &str) -> Option<serde_json::Value> {
    assert!(!std::env::var("CI").is_ok_and(|v| v == "true" || v == "1"), "CI=true but {why}");
    eprintln!("skipping the glTF validator check: {why}");
    None
}

/// The rest positions and each morph target's positions (rest + displacement) of the first
/// primitive, the keyframe times and the weights, from `file`.
fn read_animation(file: &Path) -> (Vec<DVec3>, Vec<Vec<DVec3>>, Vec<f32>, Vec<f32>) {
    let gltf = gltf::Gltf::from_slice(&fs::read(file).unwrap()).unwrap();
    let blob = gltf.blob.clone().expect("a GLB's binary chunk");
    let buffers = [blob];
    let document = gltf.document;
    let mesh = document.meshes().next().unwrap();
    let primitive = mesh.primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let rest: Vec<DVec3> = reader.read_positions().unwrap().map(|p| DVec3::from_array(p.map(f64::from))).collect();
    let targets: Vec<Vec<DVec3>> = reader
        .read_morph_targets()
        .map(|(positions, _, _)| {
            positions.unwrap().zip(&rest).map(|(d, r)| *r + DVec3::from_array(d.map(f64::from))).collect()
        })
        .collect();
    let animation = document.animations().next().unwrap();
    let channel = animation.channels().next().unwrap();
    let reader = channel.reader(|b| Some(&buffers[b.index()]));
    let times: Vec<f32> = reader.read_inputs().unwrap().collect();
    let weights: Vec<f32> = match reader.read_outputs().unwrap() {
        gltf::animation::util::ReadOutputs::MorphTargetWeights(w) => w.into_f32().collect(),
        _ => panic!("the channel animates weights"),
    };
    (rest, targets, times, weights)
}

/// Exports `poses` of `mesh` and `rig` (in `dir`), checks each target against `deform`'s output
/// and the keyframes, and runs the validator; returns the worst distance over the diagonal.
fn export_and_check(dir: &Path, mesh: &str, rig: &str, poses: &[String]) -> f64 {
    let output = sweepffd(dir)
        .args(["--quiet", "export", "--mesh", mesh, "--rig", rig, "--out", "anim.glb", "--backend", "cpu"])
        .arg("--poses")
        .args(poses)
        .args(["--seconds-per-pose", "0.5"])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let (rest, targets, times, weights) = read_animation(&dir.join("anim.glb"));
    let loaded = LoadedMesh::load(&dir.join(mesh)).unwrap();
    let diagonal = loaded.mesh.diagonal();
    assert_eq!(rest.len(), loaded.mesh.positions.len());
    assert_eq!(targets.len(), poses.len());
    let mut worst: f64 = 0.0;
    for (k, (pose, target)) in poses.iter().zip(&targets).enumerate() {
        let out = format!("deformed-{k}.obj");
        let status = sweepffd(dir)
            .args(["--quiet", "deform", "--mesh", mesh, "--rig", rig, "--pose", pose, "--out", &out])
            .args(["--backend", "cpu"])
            .status()
            .unwrap();
        assert!(status.success());
        let deformed = LoadedMesh::load(&dir.join(&out)).unwrap().mesh.positions;
        for (p, q) in target.iter().zip(&deformed) {
            worst = worst.max(p.distance(*q) / diagonal);
        }
    }
    assert!(worst <= 1e-6, "a morph target is {worst:e} × the diagonal off deform's output");
    // Keyframe k at 0.5·k s, where target k alone has weight 1.
    let n = poses.len();
    assert_eq!(times, (0..n).map(|k| 0.5 * k as f32).collect::<Vec<_>>());
    assert_eq!(weights, (0..n * n).map(|i| if i / n == i % n { 1.0 } else { 0.0 }).collect::<Vec<f32>>());
    if let Some(report) = validator_report(&dir.join("anim.glb")) {
        assert_eq!((report["numErrors"].as_u64(), report["numWarnings"].as_u64()), (Some(0), Some(0)), "{report}");
    }
    worst
}

#[test]
fn the_demo_tube_exports_five_poses_that_deform_makes() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    assert!(sweepffd(dir).args(["--quiet", "demo", "--out", "demo"]).status().unwrap().success());
    let poses: Vec<String> = (0..5)
        .map(|k| {
            let angle = 20 * k;
            let edits = format!(
                r#"[{{"op": "bend", "sweep": "tube", "t": 0.5, "span": 0.5, "axis": [1, 0, 0], "angle_deg": {angle}}}]"#
            );
            fs::write(dir.join(format!("edits-{k}.json")), edits).unwrap();
            let pose = format!("pose-{k}.json");
            let status = sweepffd(dir)
                .args([
                    "--quiet",
                    "pose",
                    "--rig",
                    "demo/rig.json",
                    "--edits",
                    &format!("edits-{k}.json"),
                    "--out",
                    &pose,
                ])
                .status()
                .unwrap();
            assert!(status.success());
            pose
        })
        .collect();
    let worst = export_and_check(dir, "demo/rest.obj", "demo/rig.json", &poses);
    eprintln!("demo tube, 5 poses: morph targets within {worst:.2e} × diagonal of deform's output");
}

#[test]
fn the_bunnys_autorig_exports_three_poses_that_deform_makes() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fs::copy(&path, dir.join("bunny.obj")).unwrap();
    let status =
        sweepffd(dir).args(["--quiet", "autorig", "--mesh", "bunny.obj", "--out", "rig.json"]).status().unwrap();
    assert!(status.success());
    let poses: Vec<String> = [(0.0, 0.0), (40.0, -30.0), (-25.0, 60.0)]
        .iter()
        .enumerate()
        .map(|(k, (a, b))| {
            let edits = format!(
                r#"[{{"op": "bend", "sweep": "limb0", "t": 0.5, "span": 0.3, "axis": [1, 0, 0], "angle_deg": {a}}},
                    {{"op": "bend", "sweep": "limb1", "t": 0.4, "span": 0.3, "axis": [0, 1, 0], "angle_deg": {b}}}]"#
            );
            fs::write(dir.join(format!("edits-{k}.json")), edits).unwrap();
            let pose = format!("pose-{k}.json");
            let status = sweepffd(dir)
                .args(["--quiet", "pose", "--rig", "rig.json", "--edits", &format!("edits-{k}.json"), "--out", &pose])
                .status()
                .unwrap();
            assert!(status.success());
            pose
        })
        .collect();
    let worst = export_and_check(dir, "bunny.obj", "rig.json", &poses);
    eprintln!("bunny's ears, 3 poses: morph targets within {worst:.2e} × diagonal of deform's output");
}

#[test]
fn bad_exports_are_errors_that_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    assert!(sweepffd(dir).args(["--quiet", "demo", "--out", "demo"]).status().unwrap().success());
    for (args, expected) in [
        (&["--out", "anim.obj"][..], "an animation is written as .glb or .gltf"),
        (&["--out", "anim.glb", "--seconds-per-pose", "0"][..], "--seconds-per-pose must be positive"),
        (&["--out", "anim.glb", "--poses", "missing.json"][..], "missing.json"),
    ] {
        let poses: &[&str] = if args.contains(&"--poses") { &[] } else { &["--poses", "demo/pose.json"] };
        let output = sweepffd(dir)
            .args(["export", "--mesh", "demo/rest.obj", "--rig", "demo/rig.json"])
            .args(poses)
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(!dir.join("anim.glb").exists() && !dir.join("anim.obj").exists());
    }
}
