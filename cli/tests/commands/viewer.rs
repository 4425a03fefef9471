//! The viewer, driven by scripts in a virtual X display (Xvfb) on the GPU adapter (lavapipe in
//! CI): a scripted drag of the mesh changes the picture where the mesh moved, its saved pose is
//! exactly what `sweepffd pose` makes of the same drag_point edit, undo and redo walk back and
//! forth, a mesh without a rig gets a sweep fitted to a clicked part or a whole rig from the
//! auto-rig key, and the weight paint shows
//! a falloff band that a scripted falloff change widens, moving the posed mesh to what a rig
//! with that falloff draws.
//!
//! Without Xvfb (and no DISPLAY) or without an adapter the tests print why and skip; under
//! `CI=true` a missing Xvfb fails them, and under `SWEEPFFD_REQUIRE_GPU=1` a missing adapter.
#![cfg(feature = "viewer")]

use crate::common;
use crate::common::star;
use sweepffd::formats::LoadedMesh;

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};

use common::{REQUIRE_GPU, sweepffd};
use image::RgbaImage;
use serde_json::Value;

/// Window size of the scripted sessions, and the scene's part of it (left of the 290-point
/// panel; Xvfb has one pixel per point).
const WINDOW: (u32, u32) = (1000, 800);
const SCENE_WIDTH: u32 = 1000 - 290;

/// An X display for the viewer's window: a private Xvfb, killed on drop, or the session's own.
struct Display {
    name: String,
    server: Option<Child>,
}

impl Drop for Display {
    fn drop(&mut self) {
        if let Some(server) = &mut self.server {
            let _ = server.kill();
            let _ = server.wait();
        }
    }
}

fn flag(name: &str) -> bool {
    std::env::var(name).is_ok_and(|v| v == "1" || v == "true")
}

/// Starts Xvfb on a free display (it reports which through `-displayfd`), or falls back on
/// `DISPLAY`; `None` with a notice when neither exists (a failure under `CI=true`).
fn display() -> Option<Display> {
    let started = Command::new("Xvfb")
        .args(["-displayfd", "1", "-screen", "0", "1280x1024x24", "-nolisten", "tcp"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn();
    match started {
        Ok(mut server) => {
            let mut line = String::new();
            BufReader::new(server.stdout.take().expect("piped"))
                .read_line(&mut line)
                .expect("Xvfb reports its display");
            assert!(!line.trim().is_empty(), "Xvfb did not start");
            Some(Display { name: format!(":{}", line.trim()), server: Some(server) })
        }
        Err(error) => {
            if let Ok(name) = std::env::var("DISPLAY") {
                return Some(Display { name, server: None });
            }
            assert!(!flag("CI"), "CI=true but Xvfb cannot be started ({error}); install Debian's xvfb");
            eprintln!("skipping viewer test: no Xvfb ({error}) and no DISPLAY");
            None
        }
    }
}

/// Runs `sweepffd view` with `args` in `dir` on `display`; the parsed report, or `None` with a
/// notice when no adapter can draw into a window (a failure under `SWEEPFFD_REQUIRE_GPU=1`).
fn view(display: &Display, dir: &Path, args: &[&str]) -> Option<Value> {
    let size = format!("{}x{}", WINDOW.0, WINDOW.1);
    let output = sweepffd(dir)
        .arg("view")
        .args(args)
        .args(["--size", &size])
        .env("DISPLAY", &display.name)
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("sweepffd runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() && stderr.contains("no GPU adapter") && !flag(REQUIRE_GPU) {
        eprintln!("skipping viewer test: {stderr}");
        return None;
    }
    assert!(output.status.success(), "sweepffd view failed: {stderr}");
    Some(serde_json::from_slice(&output.stdout).expect("the report is JSON"))
}

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

fn picture(path: &Path) -> RgbaImage {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgba8()
}

/// Whether any pixel within 3 of (x, y) differs from the background.
fn covered(picture: &RgbaImage, x: u32, y: u32) -> bool {
    let background = image::Rgba(sweepffd_cli::render::BACKGROUND);
    (x - 3..=x + 3).any(|x| (y - 3..=y + 3).any(|y| *picture.get_pixel(x, y) != background))
}

/// The demo's tube (along z, one sweep) in `dir/demo`.
fn demo_tube(dir: &Path) {
    let status = sweepffd(dir).args(["--quiet", "demo", "--out", "demo"]).status().unwrap();
    assert!(status.success());
}

#[test]
fn scripted_drag_moves_the_mesh_and_saves_the_pose_that_sweepffd_pose_makes() {
    let Some(display) = display() else { return };
    let dir = tempfile::tempdir().unwrap();
    demo_tube(dir.path());
    // The camera frames the tube with its middle at the scene's center; the drag takes the
    // point there up and left, into what was background.
    let (from, to) = ([SCENE_WIDTH / 2, WINDOW.1 / 2], [SCENE_WIDTH / 2 - 60, 140]);
    write(
        &dir.path().join("drag.json"),
        &format!(
            r#"[{{"wait": 0.2}}, {{"screenshot": "before"}},
                {{"drag": {{"from": {from:?}, "to": {to:?}, "seconds": 0.5}}}},
                {{"screenshot": "after"}}, {{"save_pose": "pose.json"}}, {{"save_edits": "edits.json"}},
                {{"key": "ctrl+z"}}, {{"save_pose": "undone.json"}},
                {{"key": "ctrl+shift+z"}}, {{"save_pose": "redone.json"}}]"#
        ),
    );
    let Some(report) =
        view(&display, dir.path(), &["--mesh", "demo/rest.obj", "--rig", "demo/rig.json", "--script", "drag.json"])
    else {
        return;
    };
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");
    assert_eq!(report["screenshots"].as_array().unwrap().len(), 2, "{report}");
    assert!(report["drag_frames"].as_u64().unwrap() >= 1, "{report}");

    // The picture changed where the mesh moved: the drag's end was background before, and the
    // dragged point is drawn there after.
    let before = picture(&dir.path().join("before.png"));
    let after = picture(&dir.path().join("after.png"));
    assert_eq!(before.dimensions(), WINDOW);
    assert!(covered(&before, from[0], from[1]), "the drag starts on the tube");
    assert!(!covered(&before, to[0], to[1]), "the drag ends on background");
    assert!(covered(&after, to[0], to[1]), "the dragged point is drawn under the pointer");
    let scene_changes = (0..SCENE_WIDTH)
        .flat_map(|x| (0..WINDOW.1).map(move |y| (x, y)))
        .filter(|&(x, y)| before.get_pixel(x, y) != after.get_pixel(x, y))
        .count();
    assert!(scene_changes > 5_000, "only {scene_changes} pixels of the scene changed");

    // One drag is one drag_point edit on the tube's sweep; `sweepffd pose` applies it to the
    // same pose, to the byte.
    let edits: Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("edits.json")).unwrap()).unwrap();
    let edits = edits.as_array().unwrap();
    assert_eq!(edits.len(), 1, "{edits:?}");
    assert_eq!(edits[0]["op"], "drag_point");
    assert_eq!(edits[0]["sweep"], "tube");
    let status = sweepffd(dir.path())
        .args(["--quiet", "pose", "--rig", "demo/rig.json", "--edits", "edits.json", "--out", "cli-pose.json"])
        .status()
        .unwrap();
    assert!(status.success());
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    assert_eq!(read("pose.json"), read("cli-pose.json"));

    // Undo goes back to the rest keys; redo to the dragged pose.
    let rig = sweepffd::rig::Rig::load(&dir.path().join("demo/rig.json")).unwrap();
    let rest: Vec<Vec<_>> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
    assert_eq!(read("undone.json"), rig.pose_document(&rest).to_json());
    assert_eq!(read("redone.json"), read("pose.json"));
}

#[test]
fn mesh_without_a_rig_gets_a_sweep_fitted_to_a_clicked_part() {
    let Some(display) = display() else { return };
    let dir = tempfile::tempdir().unwrap();
    demo_tube(dir.path());
    let center = [SCENE_WIDTH / 2, WINDOW.1 / 2];
    write(
        &dir.path().join("fit.json"),
        &format!(
            r#"[{{"click": {{"at": {center:?}}}}}, {{"wait": 0.1}}, {{"key": "f"}}, {{"wait": 0.1}},
                {{"save_rig": "fitted-rig.json"}}, {{"screenshot": "fitted"}}]"#
        ),
    );
    let Some(report) = view(&display, dir.path(), &["--mesh", "demo/rest.obj", "--script", "fit.json"]) else { return };
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");
    let rig = sweepffd::rig::Rig::load(&dir.path().join("fitted-rig.json")).unwrap();
    assert_eq!(rig.sweeps().len(), 1);
    assert!(rig.sweeps()[0].keys.len() >= 2);
    // The viewer's fit writes the default falloff, a fraction of the part's length.
    let sweep = &rig.sweeps()[0];
    let length: f64 = sweep.keys.windows(2).map(|w| w[0].center.distance(w[1].center)).sum();
    let expected = sweepffd::fit::DEFAULT_FALLOFF_FRACTION * length;
    assert!((sweep.falloff - expected).abs() <= 1e-9 * expected, "falloff {} but {expected}", sweep.falloff);
    // The fitted rig owns vertices of the mesh it was fitted to.
    let mesh = sweepffd::mesh::Mesh::load(&dir.path().join("demo/rest.obj")).unwrap();
    let owners = rig.owners(&mesh, "rest.obj").unwrap();
    assert!(owners.iter().filter(|&&o| o == 0).count() > mesh.positions.len() / 2);
}

/// The auto-rig key (the panel's "Auto-rig" button) rigs a loaded mesh as `sweepffd autorig`
/// does: the star (a ball with five tubes) gets the same five sweeps.
#[test]
fn the_auto_rig_key_rigs_the_loaded_mesh_as_the_command_does() {
    let Some(display) = display() else { return };
    let dir = tempfile::tempdir().unwrap();
    let mesh = LoadedMesh::from(star::star_mesh(0.06));
    mesh.save(&dir.path().join("star.obj"), &mesh.mesh.positions).unwrap();
    write(
        &dir.path().join("auto.json"),
        r#"[{"wait": 0.1}, {"key": "a"}, {"wait": 0.1}, {"save_rig": "auto-rig.json"}]"#,
    );
    let Some(report) = view(&display, dir.path(), &["--mesh", "star.obj", "--script", "auto.json"]) else { return };
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");
    let saved = sweepffd::rig::RigDocument::load(&dir.path().join("auto-rig.json")).unwrap();
    let loaded = sweepffd::mesh::Mesh::load(&dir.path().join("star.obj")).unwrap();
    let command = sweepffd::fit::autorig::autorig(&loaded, &Default::default()).unwrap().document();
    assert_eq!(saved.sweeps.len(), 5);
    assert_eq!(saved, command);
}

/// Pixels drawn in the fold rings' red.
fn red_pixels(picture: &RgbaImage) -> usize {
    picture.pixels().filter(|p| p[0] > 180 && p[1] < 60 && p[2] < 60).count()
}

/// B turns drags on the mesh into bends: one drag on the tube's middle is one `bend` edit of the
/// tube over the panel's span (0.2) around the grabbed point's t, which `sweepffd pose` applies
/// to the same pose, byte for byte. A pose that folds the tube is drawn with red rings across
/// the stretch that folds (and its warning in the panel); the rest pose has none.
#[test]
fn bend_drags_make_bend_edits_and_folds_are_drawn_in_red() {
    let Some(display) = display() else { return };
    let dir = tempfile::tempdir().unwrap();
    demo_tube(dir.path());
    let (from, to) = ([SCENE_WIDTH / 2, WINDOW.1 / 2], [SCENE_WIDTH / 2 - 60, 140]);
    write(
        &dir.path().join("bend.json"),
        &format!(
            r#"[{{"wait": 0.2}}, {{"screenshot": "rest"}}, {{"key": "b"}},
                {{"drag": {{"from": {from:?}, "to": {to:?}, "seconds": 0.5}}}},
                {{"save_pose": "pose.json"}}, {{"save_edits": "edits.json"}}]"#
        ),
    );
    let args = ["--mesh", "demo/rest.obj", "--rig", "demo/rig.json", "--script", "bend.json"];
    let Some(report) = view(&display, dir.path(), &args) else { return };
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");
    let edits: Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("edits.json")).unwrap()).unwrap();
    let edits = edits.as_array().unwrap();
    assert_eq!(edits.len(), 1, "{edits:?}");
    assert_eq!((edits[0]["op"].as_str(), edits[0]["sweep"].as_str()), (Some("bend"), Some("tube")), "{edits:?}");
    assert_eq!(edits[0]["span"], 0.2);
    assert!(edits[0]["angle_deg"].as_f64().unwrap() > 10.0, "{edits:?}");
    let status = sweepffd(dir.path())
        .args(["--quiet", "pose", "--rig", "demo/rig.json", "--edits", "edits.json", "--out", "cli-pose.json"])
        .status()
        .unwrap();
    assert!(status.success());
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    assert_eq!(read("pose.json"), read("cli-pose.json"));
    assert_eq!(red_pixels(&picture(&dir.path().join("rest.png"))), 0, "the rest pose folds nothing");

    // Key 2 turned 130°: the tube folds beside it.
    write(
        &dir.path().join("fold.json"),
        r#"[{"op": "move_key", "sweep": "tube", "key": 2, "rotate": [0.9063, 0, 0, 0.4226], "mode": "local"}]"#,
    );
    let status = sweepffd(dir.path())
        .args(["--quiet", "pose", "--rig", "demo/rig.json", "--edits", "fold.json", "--out", "folded.json"])
        .status()
        .unwrap();
    assert!(status.success());
    write(&dir.path().join("look.json"), r#"[{"wait": 0.2}, {"screenshot": "folded"}]"#);
    let args = ["--mesh", "demo/rest.obj", "--rig", "demo/rig.json", "--pose", "folded.json", "--script", "look.json"];
    let Some(report) = view(&display, dir.path(), &args) else { return };
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");
    let red = red_pixels(&picture(&dir.path().join("folded.png")));
    assert!(red > 200, "only {red} red pixels: the folding stretch is not drawn in red");
}

#[test]
fn a_pose_given_or_loaded_is_the_pose_saved() {
    let Some(display) = display() else { return };
    let dir = tempfile::tempdir().unwrap();
    demo_tube(dir.path());
    // Started from the demo's pose, saved; then the rest loaded over it, saved.
    let rig = sweepffd::rig::Rig::load(&dir.path().join("demo/rig.json")).unwrap();
    let rest: Vec<Vec<_>> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
    write(&dir.path().join("rest-pose.json"), &rig.pose_document(&rest).to_json());
    write(
        &dir.path().join("poses.json"),
        r#"[{"save_pose": "given.json"}, {"load_pose": "rest-pose.json"}, {"save_pose": "loaded.json"}]"#,
    );
    let args =
        ["--mesh", "demo/rest.obj", "--rig", "demo/rig.json", "--pose", "demo/pose.json", "--script", "poses.json"];
    let Some(report) = view(&display, dir.path(), &args) else { return };
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");
    let json = |name: &str| -> Value {
        serde_json::from_str(&std::fs::read_to_string(dir.path().join(name)).unwrap()).unwrap()
    };
    assert_eq!(json("given.json")["sweeps"], json("demo/pose.json")["sweeps"]);
    assert_eq!(json("loaded.json"), json("rest-pose.json"));
}

#[test]
fn bad_script_is_an_error_naming_the_file_before_any_window_opens() {
    let dir = tempfile::tempdir().unwrap();
    demo_tube(dir.path());
    write(&dir.path().join("bad.json"), r#"[{"key": "ctrl+q"}]"#);
    let output = sweepffd(dir.path())
        .args(["view", "--mesh", "demo/rest.obj", "--script", "bad.json"])
        .env("DISPLAY", ":nowhere")
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("bad.json") && stderr.contains("ctrl+q"), "{stderr}");
}

/// Whether a pixel shows the middle of the weight paint's ramp (w ≈ ½, yellow) under any light:
/// shading scales the linear colour, so red and green stay close and blue stays far below
/// (clay, the background, rings, sweeps and the ramp's other stops fail one of the two).
fn halfway_yellow(pixel: &image::Rgba<u8>) -> bool {
    let [r, g, b, _] = pixel.0.map(f32::from);
    r >= 40.0 && g >= 0.85 * r && g <= 1.1 * r && b <= 0.45 * r
}

/// Pixels (x, y) of the scene (left of the panel) that `keep`.
fn scene_count(keep: impl Fn(u32, u32) -> bool) -> usize {
    (0..SCENE_WIDTH).flat_map(|x| (0..WINDOW.1).map(move |y| (x, y))).filter(|&(x, y)| keep(x, y)).count()
}

/// The demo's rig with its sweep owning only the tube's upper half (z ≥ 2), with falloff `width`,
/// in `dir/name`: the band fades into the unowned lower half.
fn half_owned_rig(dir: &Path, width: f64, name: &str) {
    let mesh = sweepffd::mesh::Mesh::load(&dir.join("demo/rest.obj")).unwrap();
    let upper: Vec<u32> = (0..mesh.positions.len() as u32).filter(|&v| mesh.positions[v as usize].z >= 2.0).collect();
    let mut rig: Value = serde_json::from_str(&std::fs::read_to_string(dir.join("demo/rig.json")).unwrap()).unwrap();
    rig["sweeps"][0]["vertices"] = serde_json::json!({ "indices": upper });
    rig["sweeps"][0]["falloff"] = serde_json::json!(width);
    write(&dir.join(name), &rig.to_string());
}

#[test]
fn weight_paint_shows_the_band_and_a_new_falloff_changes_the_posed_mesh() {
    let Some(display) = display() else { return };
    let dir = tempfile::tempdir().unwrap();
    demo_tube(dir.path());
    half_owned_rig(dir.path(), 0.4, "narrow-rig.json");
    half_owned_rig(dir.path(), 1.2, "wide-rig.json");
    // The sweeps hidden (W twice), so that only the mesh is drawn.
    write(
        &dir.path().join("paint.json"),
        r#"[{"key": "w"}, {"key": "w"}, {"wait": 0.2}, {"screenshot": "plain"},
            {"key": "k"}, {"screenshot": "painted"},
            {"falloff": {"sweep": "tube", "width": 1.2}}, {"screenshot": "painted-wide"},
            {"key": "k"}, {"screenshot": "wide"},
            {"save_rig": "saved-rig.json"}, {"save_pose": "saved-pose.json"}]"#,
    );
    let posed = ["--mesh", "demo/rest.obj", "--pose", "demo/pose.json", "--rig"];
    let Some(report) =
        view(&display, dir.path(), &[&posed[..], &["narrow-rig.json", "--script", "paint.json"]].concat())
    else {
        return;
    };
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");
    assert_eq!(report["screenshots"].as_array().unwrap().len(), 4, "{report}");
    // The same pose with the wide falloff from the start.
    write(
        &dir.path().join("fresh.json"),
        r#"[{"key": "w"}, {"key": "w"}, {"wait": 0.2}, {"screenshot": "fresh-wide"}]"#,
    );
    let report =
        view(&display, dir.path(), &[&posed[..], &["wide-rig.json", "--script", "fresh.json"]].concat()).unwrap();
    assert_eq!(report["errors"], Value::Array(vec![]), "{report}");

    let shot = |name: &str| picture(&dir.path().join(format!("{name}.png")));
    let (plain, painted, painted_wide, wide, fresh) =
        (shot("plain"), shot("painted"), shot("painted-wide"), shot("wide"), shot("fresh-wide"));
    let yellow = |p: &RgbaImage| scene_count(|x, y| halfway_yellow(p.get_pixel(x, y)));
    let (none, narrow_band, wide_band) = (yellow(&plain), yellow(&painted), yellow(&painted_wide));
    eprintln!("halfway-yellow pixels: {none} in clay, {narrow_band} with W = 0.4, {wide_band} with W = 1.2");
    assert_eq!(none, 0, "clay shows no band colour");
    assert!(narrow_band > 100, "the paint shows the band: {narrow_band} pixels");
    assert!(wide_band > narrow_band, "a wider band shows more of its middle: {wide_band} ≤ {narrow_band}");

    // The wider falloff moved the posed mesh, and drew what the rig with that falloff draws.
    let changed = scene_count(|x, y| plain.get_pixel(x, y) != wide.get_pixel(x, y));
    let differ = scene_count(|x, y| wide.get_pixel(x, y) != fresh.get_pixel(x, y));
    eprintln!("falloff 0.4 → 1.2: {changed} scene pixels changed; {differ} differ from the rig made with 1.2");
    assert!(changed > 2_000, "only {changed} pixels changed");
    assert!(differ <= 50, "{differ} pixels differ from a viewer started with the wide falloff");

    // The saved rig carries the new falloff, and the saved pose (the session kept) fits it.
    let rig = sweepffd::rig::Rig::load(&dir.path().join("saved-rig.json")).unwrap();
    assert_eq!(rig.sweeps()[0].falloff, 1.2);
    rig.load_pose(&dir.path().join("saved-pose.json")).unwrap();
    let json = |name: &str| -> Value {
        serde_json::from_str(&std::fs::read_to_string(dir.path().join(name)).unwrap()).unwrap()
    };
    assert_eq!(json("saved-pose.json")["sweeps"][0]["keys"], json("demo/pose.json")["sweeps"][0]["keys"]);
}
