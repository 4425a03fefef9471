//! `sweepffd render` and the `render` library module on the GPU (lavapipe in CI): pictures have
//! the requested size, show the mesh over the background, change where a pose moved vertices
//! and where sweeps are drawn; refused option combinations and a missing adapter write nothing.
//!
//! GPU tests skip with a notice when no adapter exists (`SWEEPFFD_REQUIRE_GPU=1` makes that a
//! failure); the error cases run everywhere.

use crate::common;

use std::f64::consts::PI;
use std::path::Path;
use std::process::Output;

use glam::{DVec3, Vec3};
use image::RgbaImage;
use sweepffd::bind::bind_vertices;
use sweepffd::deform::deform_hard;
use sweepffd::formats::LoadedMesh;
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};
use sweepffd_cli::render::{BACKGROUND, CLAY, Camera, Renderer, Scene, ViewAngles, union_bounds};

/// A small tube along z, its five-key rig, and a bend-twist-taper pose, written to `dir` as
/// `tube.obj`, `rig.json` and `pose.json`.
fn write_tube_scene(dir: &Path) {
    let tube = Tube { rings: 40, around: 32, length: 4.0, radius: 0.5 };
    let rig = tube_rig(&tube, 5, 16);
    let keys = BendTwistTaper { bend: 0.5 * PI, twist: 0.5 * PI, taper: 0.5 }.keys(&rig);
    LoadedMesh::from(tube.mesh()).save(&dir.join("tube.obj"), &tube.mesh().positions).unwrap();
    std::fs::write(dir.join("rig.json"), rig.to_document().to_json()).unwrap();
    std::fs::write(dir.join("pose.json"), rig.pose_document(&keys).to_json()).unwrap();
}

/// Runs `sweepffd render` in `dir` with `args`.
fn render(dir: &Path, args: &[&str]) -> Output {
    common::sweepffd(dir).arg("render").args(args).output().unwrap()
}

/// Runs `sweepffd render`, expects success and reads the picture it wrote to `out`.
fn render_ok(dir: &Path, args: &[&str], out: &str) -> RgbaImage {
    let output = render(dir, &[args, &["--out", out]].concat());
    assert!(output.status.success(), "{args:?} failed: {}", String::from_utf8_lossy(&output.stderr));
    image::open(dir.join(out)).unwrap().to_rgba8()
}

/// How many pixels are not the background.
fn foreground(picture: &RgbaImage) -> usize {
    picture.pixels().filter(|p| p.0 != BACKGROUND).count()
}

/// How many pixels differ between two pictures of the same size.
fn differing(a: &RgbaImage, b: &RgbaImage) -> usize {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

#[test]
fn picture_has_the_requested_size_and_shows_the_mesh_over_the_background() {
    if common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let picture = render_ok(dir.path(), &["--mesh", "tube.obj", "--size", "160x120", "--view", "90,20"], "a.png");
    assert_eq!(picture.dimensions(), (160, 120));
    for (x, y) in [(0, 0), (159, 0), (0, 119), (159, 119)] {
        assert_eq!(picture.get_pixel(x, y).0, BACKGROUND, "corner ({x}, {y})");
    }
    let covered = foreground(&picture) as f64 / (160.0 * 120.0);
    assert!(covered > 0.1 && covered < 0.9, "the tube covers {:.1}% of the picture", 100.0 * covered);
}

/// The tube scaled by 10⁻²⁵ and the tube moved by 10⁷ draw as the tube does (the renderer
/// draws in the frame of the mesh; the tiny one drew an empty picture, the far one a coarse
/// one).
#[test]
fn a_tiny_or_far_mesh_draws_as_the_mesh_near_the_origin_does() {
    if common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let args = |mesh: &'static str| ["--mesh", mesh, "--size", "160x120", "--view", "90,20"];
    let near = render_ok(dir.path(), &args("tube.obj"), "near.png");
    let tube = Tube { rings: 40, around: 32, length: 4.0, radius: 0.5 };
    for (name, scale, offset) in [("tiny.obj", 1e-25, 0.0), ("far.obj", 1.0, 1e7)] {
        let positions: Vec<_> = tube.mesh().positions.iter().map(|&p| p * scale + offset).collect();
        LoadedMesh::from(tube.mesh()).save(&dir.path().join(name), &positions).unwrap();
        let picture = render_ok(dir.path(), &args(if scale < 1.0 { "tiny.obj" } else { "far.obj" }), "other.png");
        let covered = foreground(&picture) as f64 / foreground(&near) as f64;
        let changed = differing(&picture, &near) as f64 / (160.0 * 120.0);
        assert!((covered - 1.0).abs() < 0.01 && changed < 0.01, "{name}: {covered} of the coverage, {changed} changed");
    }
}

#[test]
fn compare_is_twice_as_wide_and_its_halves_differ() {
    if common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let args = ["--mesh", "tube.obj", "--rig", "rig.json", "--pose", "pose.json", "--compare", "--size", "120x90"];
    let picture = render_ok(dir.path(), &args, "c.png");
    assert_eq!(picture.dimensions(), (240, 90));
    let left = image::imageops::crop_imm(&picture, 0, 0, 120, 90).to_image();
    let right = image::imageops::crop_imm(&picture, 120, 0, 120, 90).to_image();
    assert!(foreground(&left) > 200 && foreground(&right) > 200);
    assert!(differing(&left, &right) > 500, "rest and pose panels differ in {} pixels", differing(&left, &right));
}

#[test]
fn show_sweeps_draws_dark_rings_and_changes_pixels() {
    if common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let base = ["--mesh", "tube.obj", "--rig", "rig.json", "--size", "160x120", "--view", "90,20"];
    let plain = render_ok(dir.path(), &base, "plain.png");
    let with_sweeps = render_ok(dir.path(), &[&base[..], &["--show-sweeps"]].concat(), "sweeps.png");
    // Ring pixels: dark and bluish (clay is always redder than it is blue, even in shadow).
    let dark = |p: &RgbaImage| p.pixels().filter(|p| p.0[..3].iter().all(|&c| c < 100) && p.0[2] > p.0[0]).count();
    assert_eq!(dark(&plain), 0, "the clay mesh alone has no dark blue pixels");
    assert!(dark(&with_sweeps) > 50, "only {} dark ring pixels", dark(&with_sweeps));
    assert!(differing(&plain, &with_sweeps) > 500);
}

/// A rest tube and a pose that moves only its last key sideways, drawn with one camera: every
/// pixel that changes lies in the picture's box around the vertices the move can reach (two
/// pixels of margin), and many change. A moved vertex changes the normals of its face
/// neighbours, and those change the shading of their faces, so the box covers, at rest and
/// posed, every vertex of a face that touches a vertex of a face that touches a moved one.
#[test]
fn pose_changes_pixels_only_where_vertices_moved() {
    let Some(context) = common::gpu() else {
        return;
    };
    let renderer = Renderer::with_context(context.clone());
    let tube = Tube { rings: 40, around: 32, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let rig = tube_rig(&tube, 5, 16);
    let mut keys: Vec<_> = vec![rig.sweeps()[0].keys.clone()];
    keys[0][4].center += DVec3::new(0.8, 0.0, 0.0);
    let posed = rig.pose(&keys).unwrap();
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = bind_vertices(rig.rest(), &owners, &mesh.positions, &|_| {});
    let mut deformed = vec![DVec3::ZERO; mesh.positions.len()];
    deform_hard(&posed, &bindings, &mesh.positions, &mut deformed);

    let (width, height) = (200, 150);
    let scenes: Vec<Scene> = [&mesh.positions, &deformed]
        .iter()
        .map(|positions| {
            let mut scene = Scene::new();
            scene.add_mesh(&mesh, positions, CLAY);
            scene
        })
        .collect();
    let (min, max) = union_bounds(&scenes).unwrap();
    let angles = ViewAngles::try_new(90.0, 20.0).unwrap();
    let camera = Camera::framing(min, max, angles, width as f32 / height as f32);
    let rest_picture = renderer.render(&scenes[0], &camera, width, height).unwrap();
    let posed_picture = renderer.render(&scenes[1], &camera, width, height).unwrap();

    let clip_from_world = camera.view_projection(width as f32 / height as f32);
    let pixel = |p: DVec3| {
        let ndc = clip_from_world.project_point3(p.as_vec3());
        Vec3::new((ndc.x + 1.0) * 0.5 * width as f32, (1.0 - ndc.y) * 0.5 * height as f32, 0.0)
    };
    let moved: Vec<bool> = mesh.positions.iter().zip(&deformed).map(|(r, p)| r.distance(*p) > 1e-4).collect();
    assert!(moved.iter().any(|m| !m), "some vertices stay put");
    let grow = |set: &[bool]| {
        let mut grown = set.to_vec();
        for face in mesh.faces.iter().filter(|f| f.iter().any(|&v| set[v as usize])) {
            face.iter().for_each(|&v| grown[v as usize] = true);
        }
        grown
    };
    let reach = grow(&grow(&moved));
    let moved: Vec<Vec3> = (0..mesh.positions.len())
        .filter(|&i| reach[i])
        .flat_map(|i| [pixel(mesh.positions[i]), pixel(deformed[i])])
        .collect();
    let (lo, hi) = moved.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let mut changed = 0;
    for (x, y, p) in posed_picture.enumerate_pixels() {
        if p != rest_picture.get_pixel(x, y) {
            changed += 1;
            let (x, y) = (x as f32 + 0.5, y as f32 + 0.5);
            assert!(
                x >= lo.x - 2.0 && x <= hi.x + 2.0 && y >= lo.y - 2.0 && y <= hi.y + 2.0,
                "pixel ({x}, {y}) changed outside the moved vertices' box {lo}..{hi}"
            );
        }
    }
    assert!(changed > 300, "only {changed} pixels changed");
}

/// Asserts that `render` with `args` fails with an `error:` line containing `expected` and
/// writes no picture.
fn refused(args: &[&str], expected: &str) {
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let output = render(dir.path(), &[args, &["--out", "x.png"]].concat());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{args:?} succeeded");
    assert!(stderr.contains(expected), "{args:?}: stderr {stderr:?} lacks {expected:?}");
    assert!(!dir.path().join("x.png").exists(), "{args:?} wrote a picture");
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.contains("x.png"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn compare_without_pose_is_an_error() {
    refused(&["--mesh", "tube.obj", "--rig", "rig.json", "--compare"], "error: --compare needs --pose");
}

#[test]
fn pose_without_rig_is_an_error() {
    refused(&["--mesh", "tube.obj", "--pose", "pose.json"], "error: --pose needs --rig");
}

#[test]
fn show_sweeps_without_rig_is_an_error() {
    refused(&["--mesh", "tube.obj", "--show-sweeps"], "error: --show-sweeps needs --rig");
}

#[test]
fn malformed_size_and_view_are_errors() {
    refused(&["--mesh", "tube.obj", "--size", "320"], "expected WIDTHxHEIGHT");
    refused(&["--mesh", "tube.obj", "--size", "0x240"], "zero side");
    refused(&["--mesh", "tube.obj", "--view", "30,120"], "elevation from -90 to 90");
    refused(&["--mesh", "tube.obj", "--view", "thirty"], "expected AZIMUTH,ELEVATION");
}

#[test]
fn bad_zoom_and_look_at_are_errors() {
    refused(&["--mesh", "tube.obj", "--zoom", "0.5"], "--zoom must be a finite number of at least 1");
    refused(&["--mesh", "tube.obj", "--look-at", "0,0,1"], "give --zoom too");
    refused(&["--mesh", "tube.obj", "--zoom", "2", "--look-at", "0,nan,1"], "expected X,Y,Z");
    refused(&["--mesh", "tube.obj", "--zoom", "2", "--look-at", "0,1"], "expected X,Y,Z");
}

/// A close-up: `--zoom 4 --look-at` the tube's top (z = 4) covers more of the picture than the
/// whole tube does, and is centred there: the top's half fills the picture's middle, while a
/// close-up of the bottom (z = 0) differs from it.
#[test]
fn zoom_draws_a_close_up_of_the_point_looked_at() {
    let Some(_) = common::gpu() else { return };
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let whole = render_ok(dir.path(), &["--mesh", "tube.obj", "--size", "200x150"], "whole.png");
    let top = ["--mesh", "tube.obj", "--size", "200x150", "--zoom", "4", "--look-at", "0,0,4"];
    let top = render_ok(dir.path(), &top, "top.png");
    let bottom = ["--mesh", "tube.obj", "--size", "200x150", "--zoom", "4", "--look-at", "0,0,0"];
    let bottom = render_ok(dir.path(), &bottom, "bottom.png");
    assert!(foreground(&top) > 2 * foreground(&whole), "{} against {}", foreground(&top), foreground(&whole));
    let background = image::Rgba(sweepffd_cli::render::BACKGROUND);
    assert_ne!(*top.get_pixel(100, 75), background, "the point looked at is drawn in the middle");
    assert_ne!(top, bottom);
}

#[test]
fn picture_that_is_not_png_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let output = render(dir.path(), &["--mesh", "tube.obj", "--out", "x.jpg"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("name it .png"));
    assert!(!dir.path().join("x.jpg").exists());
}

#[test]
fn missing_adapter_is_a_clear_error_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let output = common::sweepffd(dir.path())
        .env("WGPU_ADAPTER_NAME", "no adapter has this name")
        .args(["render", "--mesh", "tube.obj", "--out", "x.png"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.starts_with("error: render needs a GPU adapter (none found: "), "{stderr}");
    assert!(!dir.path().join("x.png").exists());
}

#[test]
fn help_lists_render_and_its_options() {
    let dir = tempfile::tempdir().unwrap();
    let output = common::sweepffd(dir.path()).args(["render", "--help"]).output().unwrap();
    assert!(output.status.success());
    let help = String::from_utf8_lossy(&output.stdout);
    for option in ["--mesh", "--rig", "--pose", "--show-sweeps", "--size", "--view", "--compare", "--out"] {
        assert!(help.contains(option), "`render --help` does not mention {option}:\n{help}");
    }
    let output = common::sweepffd(dir.path()).arg("--help").output().unwrap();
    assert!(String::from_utf8_lossy(&output.stdout).contains("render"));
}
