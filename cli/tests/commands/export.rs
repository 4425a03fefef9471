//! `sweepffd export`: a mesh, its rig and poses as one glTF animation. The demo tube with 5 poses
//! and the bunny's autorig with 3: each morph target, read back with the `gltf` crate (sparse
//! accessors expanded), puts every vertex where `sweepffd deform` of that pose puts it, within
//! 1e-6 of the diagonal; the animation's keyframes turn the targets on one by one; the Khronos
//! glTF validator reports no error and no warning; three.js in headless Chromium plays the
//! tube's animation where `sweepffd render` draws each pose (`cli/tests/js`: `npm ci` there,
//! and Debian's `chromium`; without them those checks print why and are skipped, and fail under
//! `CI=true`).

use crate::common;

use std::fs;
use std::path::Path;

use glam::DVec3;
use sweepffd::formats::LoadedMesh;

use common::sweepffd;

/// Runs the Khronos validator on `file`: `None` (with a notice) where it is not installed.
fn validator_report(file: &Path) -> Option<serde_json::Value> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/js");
    let missing = if !folder.join("node_modules/gltf-validator").exists() {
        Some("the npm package gltf-validator is not installed (npm ci in cli/tests/js)".to_string())
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

/// Poses `rig` (in `dir`) by each edits file of `edits` in turn, from its rest keys; returns the
/// pose files written, `pose-K.json`.
fn write_poses(dir: &Path, rig: &str, edits: &[String]) -> Vec<String> {
    edits
        .iter()
        .enumerate()
        .map(|(k, edits)| {
            fs::write(dir.join(format!("edits-{k}.json")), edits).unwrap();
            let pose = format!("pose-{k}.json");
            let args = ["--quiet", "pose", "--rig", rig, "--edits", &format!("edits-{k}.json"), "--out", &pose];
            assert!(sweepffd(dir).args(args).status().unwrap().success());
            pose
        })
        .collect()
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
    assert_eq!(targets.len(), poses.len());
    // Each glTF vertex is a mesh vertex, or one of its copies across a texture seam: found by
    // its rest position (vertices at one rest position move together).
    let key = |p: DVec3| p.as_vec3().to_array().map(f32::to_bits);
    let at: std::collections::HashMap<[u32; 3], usize> =
        loaded.mesh.positions.iter().enumerate().map(|(v, p)| (key(*p), v)).collect();
    let source: Vec<usize> = rest.iter().map(|p| at[&key(*p)]).collect();
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
        for (p, &v) in target.iter().zip(&source) {
            worst = worst.max(p.distance(deformed[v]) / diagonal);
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

/// The texture coordinates, positions and indices of the first primitive of GLB `file`.
fn textured_primitive(file: &Path) -> (Vec<[f32; 2]>, Vec<[f32; 3]>, Vec<u32>) {
    let gltf = gltf::Gltf::from_slice(&fs::read(file).unwrap()).unwrap();
    let buffers = [gltf.blob.clone().unwrap()];
    let primitive = gltf.document.meshes().next().unwrap().primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let uv = reader.read_tex_coords(0).expect("TEXCOORD_0").into_f32().collect();
    let positions = reader.read_positions().unwrap().collect();
    let indices = reader.read_indices().unwrap().into_u32().collect();
    (uv, positions, indices)
}

#[test]
fn the_demo_tube_exports_five_poses_that_deform_makes() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let poses = tube_poses(dir, &[0, 20, 40, 60, 80]);
    let worst = export_and_check(dir, "demo/rest.obj", "demo/rig.json", &poses);
    eprintln!("demo tube, 5 poses: morph targets within {worst:.2e} × diagonal of deform's output");
}

/// The bunny's autorig (`bunny.obj` in `dir`, rig `rig.json`) and three poses of its ears,
/// bent two ways each; returns the pose files.
fn bunny_poses(dir: &Path) -> Vec<String> {
    let status =
        sweepffd(dir).args(["--quiet", "autorig", "--mesh", "bunny.obj", "--out", "rig.json"]).output().unwrap();
    assert!(status.status.success());
    let edits: Vec<String> = [(0.0, 0.0), (40.0, -30.0), (-25.0, 60.0)]
        .iter()
        .map(|(a, b)| {
            format!(
                r#"[{{"op": "bend", "sweep": "limb0", "t": 0.5, "span": 0.3, "axis": [1, 0, 0], "angle_deg": {a}}},
                    {{"op": "bend", "sweep": "limb1", "t": 0.4, "span": 0.3, "axis": [0, 1, 0], "angle_deg": {b}}}]"#
            )
        })
        .collect();
    write_poses(dir, "rig.json", &edits)
}

#[test]
fn the_bunnys_autorig_exports_three_poses_that_deform_makes() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fs::copy(&path, dir.join("bunny.obj")).unwrap();
    let poses = bunny_poses(dir);
    let worst = export_and_check(dir, "bunny.obj", "rig.json", &poses);
    eprintln!("bunny's ears, 3 poses: morph targets within {worst:.2e} × diagonal of deform's output");
}

/// Spot (an OBJ with texture coordinates, 3,225 `vt` for 2,930 vertices): its autorig's legs
/// bent three ways. The animation's vertices carry the texture coordinates of the face corners
/// they come from (v flipped to glTF's), a vertex on a texture seam split into one vertex per
/// coordinate, each moving as `deform` moves the mesh vertex; the validator is clean.
#[test]
fn spot_exports_its_texture_coordinates_with_its_poses() {
    let Some(path) = common::shared_mesh("spot_triangulated.obj") else { return };
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fs::copy(&path, dir.join("spot.obj")).unwrap();
    let status =
        sweepffd(dir).args(["--quiet", "autorig", "--mesh", "spot.obj", "--out", "rig.json"]).output().unwrap();
    assert!(status.status.success());
    let edits: Vec<String> = [0, 30, -30]
        .iter()
        .map(|angle| {
            format!(
                r#"[{{"op": "bend", "sweep": "limb0", "t": 0.5, "span": 0.4, "axis": [1, 0, 0], "angle_deg": {angle}}},
                    {{"op": "bend", "sweep": "limb1", "t": 0.5, "span": 0.4, "axis": [0, 1, 0], "angle_deg": {angle}}}]"#
            )
        })
        .collect();
    let poses = write_poses(dir, "rig.json", &edits);
    let worst = export_and_check(dir, "spot.obj", "rig.json", &poses);
    eprintln!("spot, 3 poses: morph targets within {worst:.2e} × diagonal of deform's output");
    // The texture coordinates: every corner of the OBJ's faces has its (u, 1 − v) at its glTF
    // vertex.
    let (uv, positions, indices) = textured_primitive(&dir.join("anim.glb"));
    let text = fs::read_to_string(dir.join("spot.obj")).unwrap();
    let vt: Vec<[f32; 2]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("vt "))
        .map(|l| {
            let mut w = l.split_whitespace().map(|x| x.parse::<f32>().unwrap());
            [w.next().unwrap(), w.next().unwrap()]
        })
        .collect();
    let mesh = LoadedMesh::load(&dir.join("spot.obj")).unwrap().mesh;
    assert!(uv.len() > mesh.positions.len(), "seam vertices are split: {} of {}", uv.len(), mesh.positions.len());
    let corners: Vec<(usize, usize)> = text
        .lines()
        .filter_map(|l| l.strip_prefix("f "))
        .flat_map(|l| l.split_whitespace().map(|c| c.split('/').map(|i| i.parse::<usize>().unwrap() - 1)))
        .map(|mut c| (c.next().unwrap(), c.next().unwrap()))
        .collect();
    assert_eq!(corners.len(), indices.len(), "spot's faces are triangles, each corner once");
    for (&(v, t), &g) in corners.iter().zip(&indices) {
        assert_eq!(uv[g as usize], [vt[t][0], 1.0 - vt[t][1]], "corner of vertex {v}");
        assert_eq!(positions[g as usize], mesh.positions[v].as_vec3().to_array(), "corner of vertex {v}");
    }
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

/// Chromium (Debian's `chromium`), for the three.js check: `None` with a notice where it is
/// missing (a failure under `CI=true`).
fn chromium() -> Option<&'static str> {
    let found = ["chromium", "chromium-browser"]
        .into_iter()
        .find(|name| std::process::Command::new(name).arg("--version").output().is_ok_and(|o| o.status.success()));
    if found.is_none() {
        skip("no chromium to run three.js in (apt-get install chromium)");
    }
    found
}

/// Pixels of `picture` that are not its background (`background`, within 24 per channel).
fn mask(picture: &image::RgbaImage, background: [u8; 3]) -> Vec<bool> {
    picture.pixels().map(|p| (0..3).any(|c| p[c].abs_diff(background[c]) > 24)).collect()
}

/// Intersection over union of two masks.
fn overlap(a: &[bool], b: &[bool]) -> f64 {
    let both = a.iter().zip(b).filter(|(x, y)| **x && **y).count();
    let either = a.iter().zip(b).filter(|(x, y)| **x || **y).count();
    both as f64 / either.max(1) as f64
}

/// The silhouettes three.js draws of `anim.glb` in `dir` at each keyframe and those
/// `sweepffd render` draws of each pose of `mesh` and `rig`, with the same camera (`view`, the
/// framing `render` gives each pose); `None` where three.js or Chromium is missing.
fn three_js_and_render(
    dir: &Path,
    mesh: &str,
    rig: &str,
    poses: &[String],
    view: [f32; 2],
) -> Option<Vec<(Vec<bool>, Vec<bool>)>> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/js");
    if !folder.join("node_modules/three").exists() {
        skip("the npm package three is not installed (npm ci in cli/tests/js)");
        return None;
    }
    let chromium = chromium()?;
    common::gpu()?;
    let (width, height) = (400u32, 300u32);
    let angles = sweepffd_cli::render::ViewAngles::try_new(view[0], view[1]).unwrap();
    let rest = LoadedMesh::load(&dir.join(mesh)).unwrap().mesh;
    let frame = sweepffd::frame::Frame::of_points(&rest.positions);
    let rig_file = sweepffd::rig::Rig::load(&dir.join(rig)).unwrap();
    let owners = rig_file.owners(&rest, mesh).unwrap();
    let bindings = rig_file.bind_mesh(&rest, &owners, &|_| {});
    let mut masks = Vec::new();
    for (k, pose) in poses.iter().enumerate() {
        let out = format!("render-{k}.png");
        let view = format!("{},{}", view[0], view[1]);
        let args = ["--quiet", "render", "--mesh", mesh, "--rig", rig, "--pose", pose, "--view", &view];
        assert!(sweepffd(dir).args(args).args(["--size", "400x300", "--out", &out]).status().unwrap().success());
        let rendered = mask(&image::open(dir.join(&out)).unwrap().to_rgba8(), [245, 245, 247]);
        // The camera `render` frames this pose with, from the frame's local space to the world.
        let posed = rig_file.load_pose(&dir.join(pose)).unwrap();
        let mut deformed = vec![DVec3::ZERO; rest.positions.len()];
        sweepffd::deform::deform_vertices(rig_file.rest(), &posed, &bindings, &rest.positions, &mut deformed);
        let local: Vec<glam::Vec3> = frame.local_positions(&deformed).iter().map(|p| p.as_vec3()).collect();
        let (lo, hi) =
            local.iter().fold((glam::Vec3::INFINITY, glam::Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let camera = sweepffd_cli::render::Camera::framing(lo, hi, angles, width as f32 / height as f32);
        let world = |p: glam::Vec3| frame.to_world(p.as_dvec3());
        let xyz = |p: DVec3| format!("{},{},{}", p.x, p.y, p.z);
        let url = format!(
            "file://{}?glb=file://{}&time={}&eye={}&target={}&up={}&fov={}&near={}&far={}&width={width}&height={height}",
            folder.join("play.html").display(),
            dir.join("anim.glb").display(),
            k as f64,
            xyz(world(camera.eye)),
            xyz(world(camera.target)),
            xyz(camera.up.as_dvec3()),
            camera.fov_y_degrees,
            f64::from(camera.near) * frame.scale,
            f64::from(camera.far) * frame.scale,
        );
        let shot = dir.join(format!("three-{k}.png"));
        let output = std::process::Command::new(chromium)
            .args(["--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"])
            .args(["--allow-file-access-from-files", "--force-device-scale-factor=1", "--hide-scrollbars"])
            .arg(format!("--window-size={width},{height}"))
            .args(["--virtual-time-budget=20000", &format!("--screenshot={}", shot.display()), &url])
            .output()
            .unwrap();
        assert!(shot.exists(), "chromium drew nothing: {}", String::from_utf8_lossy(&output.stderr));
        masks.push((mask(&image::open(&shot).unwrap().to_rgba8(), [255, 255, 255]), rendered));
    }
    Some(masks)
}

/// Writes `angles.len()` poses of the demo tube in `dir/demo`, each bent by one angle (degrees)
/// over half its length, and returns their files.
fn tube_poses(dir: &Path, angles: &[i32]) -> Vec<String> {
    assert!(sweepffd(dir).args(["--quiet", "demo", "--out", "demo"]).status().unwrap().success());
    write_poses(dir, "demo/rig.json", &angles.iter().map(|&angle| tube_bend(angle)).collect::<Vec<_>>())
}

/// The edits file bending the demo tube by `angle` degrees over half its length.
fn tube_bend(angle: i32) -> String {
    format!(r#"[{{"op": "bend", "sweep": "tube", "t": 0.5, "span": 0.5, "axis": [1, 0, 0], "angle_deg": {angle}}}]"#)
}

/// three.js loads the demo tube's export (5 poses) in headless Chromium and plays its
/// animation: at each keyframe its silhouette, seen by the camera `sweepffd render` frames that
/// pose with, covers what `sweepffd render` draws of the pose (intersection over union at least
/// 0.95), and covers each other keyframe's pose markedly less, so a wrong target or wrong
/// weights fail the check.
#[test]
fn three_js_plays_each_pose_of_the_tube_where_render_draws_it() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let poses = tube_poses(dir, &[0, 20, 40, 60, 80]);
    let export = ["--quiet", "export", "--mesh", "demo/rest.obj", "--rig", "demo/rig.json", "--out", "anim.glb"];
    let exported = sweepffd(dir).args(export).arg("--poses").args(&poses).args(["--backend", "cpu"]).status();
    assert!(exported.unwrap().success());
    let Some(masks) = three_js_and_render(dir, "demo/rest.obj", "demo/rig.json", &poses, [90.0, 20.0]) else { return };
    for (k, (played, _)) in masks.iter().enumerate() {
        let same = overlap(played, &masks[k].1);
        let others: Vec<f64> = (0..masks.len()).filter(|&j| j != k).map(|j| overlap(played, &masks[j].1)).collect();
        eprintln!(
            "tube keyframe {k}: three.js against render of pose {k}: IoU {same:.4}; of the other poses {others:.3?}"
        );
        assert!(same >= 0.95, "keyframe {k}: three.js covers render's pose by IoU {same}");
        assert!(others.iter().all(|&o| o < same - 0.05), "keyframe {k} also matches another pose: {others:?}");
    }
}

/// The same for the bunny's autorig with its ears bent three ways (sparse targets).
#[test]
fn three_js_plays_each_pose_of_the_bunny_where_render_draws_it() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fs::copy(&path, dir.join("bunny.obj")).unwrap();
    let poses = bunny_poses(dir);
    let export = ["--quiet", "export", "--mesh", "bunny.obj", "--rig", "rig.json", "--out", "anim.glb"];
    assert!(
        sweepffd(dir).args(export).arg("--poses").args(&poses).args(["--backend", "cpu"]).status().unwrap().success()
    );
    let Some(masks) = three_js_and_render(dir, "bunny.obj", "rig.json", &poses, [30.0, 20.0]) else { return };
    for (k, (played, rendered)) in masks.iter().enumerate() {
        let same = overlap(played, rendered);
        eprintln!("bunny keyframe {k}: three.js against render of pose {k}: IoU {same:.4}");
        assert!(same >= 0.95, "keyframe {k}: three.js covers render's pose by IoU {same}");
    }
}

/// The tube as a glTF file with TEXCOORD_0 (u around, v along), written to `path`; returns the
/// texture coordinates per vertex.
fn tube_gltf_with_texcoords(path: &Path, tube: &sweepffd::synthetic::Tube) -> Vec<[f32; 2]> {
    use base64::Engine;
    let mesh = tube.mesh();
    let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.as_vec3().to_array()).collect();
    let texcoords: Vec<[f32; 2]> = mesh
        .positions
        .iter()
        .map(|p| [(p.y.atan2(p.x) / std::f64::consts::TAU + 0.5) as f32, (p.z / tube.length) as f32])
        .collect();
    let indices: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let mut data: Vec<u8> = Vec::new();
    for p in &positions {
        p.iter().for_each(|c| data.extend_from_slice(&c.to_le_bytes()));
    }
    let uv_offset = data.len();
    for t in &texcoords {
        t.iter().for_each(|c| data.extend_from_slice(&c.to_le_bytes()));
    }
    let index_offset = data.len();
    indices.iter().for_each(|i| data.extend_from_slice(&i.to_le_bytes()));
    let (lo, hi) = positions.iter().fold(([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]), |(lo, hi), p| {
        (std::array::from_fn(|i| lo[i].min(p[i])), std::array::from_fn(|i| hi[i].max(p[i])))
    });
    let n = positions.len();
    let document = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5125, "count": indices.len(), "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": uv_offset},
            {"buffer": 0, "byteOffset": uv_offset, "byteLength": index_offset - uv_offset},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": data.len() - index_offset},
        ],
        "buffers": [{"byteLength": data.len(),
            "uri": format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&data))}],
    });
    fs::write(path, document.to_string()).unwrap();
    texcoords
}

/// A glTF source's TEXCOORD_0 goes into the animation: every exported vertex has its source
/// vertex's coordinates, the targets are `deform`'s, and the validator is clean.
#[test]
fn a_gltf_source_exports_its_texture_coordinates_with_its_poses() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let tube = sweepffd::synthetic::Tube { rings: 20, around: 12, length: 2.0, radius: 0.3 };
    let texcoords = tube_gltf_with_texcoords(&dir.join("tube.gltf"), &tube);
    let rig = sweepffd::synthetic::tube_rig(&tube, 5, 8);
    fs::write(dir.join("rig.json"), rig.to_document().to_json()).unwrap();
    let poses = write_poses(dir, "rig.json", &[0, 40, 80].map(tube_bend));
    let worst = export_and_check(dir, "tube.gltf", "rig.json", &poses);
    eprintln!("glTF tube, 3 poses: morph targets within {worst:.2e} × diagonal of deform's output");
    let (uv, positions, _) = textured_primitive(&dir.join("anim.glb"));
    let mesh = tube.mesh();
    let at: std::collections::HashMap<[u32; 3], usize> =
        mesh.positions.iter().enumerate().map(|(v, p)| (p.as_vec3().to_array().map(f32::to_bits), v)).collect();
    assert_eq!(uv.len(), mesh.positions.len(), "one texture coordinate per vertex: nothing to split");
    for (p, t) in positions.iter().zip(&uv) {
        let source = at[&p.map(f32::to_bits)];
        let expected = texcoords[source];
        assert!((t[0] - expected[0]).abs() < 1e-6 && (t[1] - expected[1]).abs() < 1e-6, "vertex {source}: {t:?}");
    }
}
