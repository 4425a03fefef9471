//! Bad input through the command line: every case exits with status 1 and one `error: …` line
//! that names the file (and the sweep and key) at fault, never panics, and writes nothing: no
//! output file, no temporary file, and an existing output file keeps its bytes.
//!
//! Each test runs in its own temporary folder with relative paths, so the messages are exact.

use crate::common;

use std::fs;
use std::path::Path;
use std::process::Output;

use sweepffd::mesh::Mesh;
use tempfile::TempDir;

/// A square prism of radius 1 from z = 0 to z = 2: 8 vertices, group `neck` on two sides and
/// group `body` on the other two. The groups share vertices 0, 2, 4 and 6 (zero-based).
const PRISM: &str = "\
v 1 0 0
v 0 1 0
v -1 0 0
v 0 -1 0
v 1 0 2
v 0 1 2
v -1 0 2
v 0 -1 2
g neck
f 1 2 6 5
f 2 3 7 6
g body
f 3 4 8 7
f 4 1 5 8
";

const IDENTITY: &str = "0, 0, 0, 1";
const UNIT_RADII: &str = "1, 1, 1, 1";
const NECK_GROUP: &str = r#"{"groups": ["neck"]}"#;

/// One key of a rig file, centered at (0, 0, `z`).
fn key(z: &str, rotation: &str, radii: &str) -> String {
    format!(r#"{{"center": [0, 0, {z}], "rotation": [{rotation}], "radii": [{radii}]}}"#)
}

/// The two unit keys at z = 0 and z = 2 that fit [`PRISM`].
fn unit_keys() -> Vec<String> {
    vec![key("0", IDENTITY, UNIT_RADII), key("2", IDENTITY, UNIT_RADII)]
}

/// One sweep of a rig file, each key on its own line.
fn sweep(name: &str, vertices: &str, keys: &[String]) -> String {
    format!("  {{\"name\": \"{name}\", \"vertices\": {vertices}, \"keys\": [\n    {}\n  ]}}", keys.join(",\n    "))
}

/// A rig (or pose) file with these sweeps.
fn rig(sweeps: &[String]) -> String {
    format!("{{\"format\": \"sweepffd-rig\", \"version\": 1, \"sweeps\": [\n{}\n]}}\n", sweeps.join(",\n"))
}

/// A rig of one sweep, `neck`, owning the group `neck`, with these keys.
fn neck_rig(keys: &[String]) -> String {
    rig(&[sweep("neck", NECK_GROUP, keys)])
}

/// A temporary folder holding `mesh.obj` ([`PRISM`]), a valid `rig.json` and `pose.json` (the
/// rest pose), in which the command line runs.
struct Scene {
    dir: TempDir,
}

impl Scene {
    fn new() -> Scene {
        let scene = Scene { dir: tempfile::tempdir().unwrap() };
        scene.write("mesh.obj", PRISM);
        scene.write("rig.json", neck_rig(&unit_keys()));
        scene.write("pose.json", neck_rig(&unit_keys()));
        scene
    }

    fn write(&self, name: &str, contents: impl AsRef<[u8]>) {
        fs::write(self.dir.path().join(name), contents).unwrap();
    }

    fn read(&self, name: &str) -> Vec<u8> {
        fs::read(self.dir.path().join(name)).unwrap()
    }

    fn run(&self, args: &[&str]) -> Output {
        common::sweepffd(self.dir.path()).args(args).output().unwrap()
    }

    /// Sorted names in the folder: a run that fails must leave them as they were.
    fn entries(&self) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(self.dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    /// Runs `args`, expects exit status 1 without a panic and without any new file, and returns
    /// stderr.
    fn fail(&self, args: &[&str]) -> String {
        let before = self.entries();
        let output = self.run(args);
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(output.stdout.is_empty(), "{args:?} printed on stdout");
        assert_eq!(self.entries(), before, "{args:?} left a file behind");
        stderr
    }

    /// `deform --mesh mesh --rig rig --pose pose --out out.obj`, expected to fail.
    fn deform_fails(&self, mesh: &str, rig: &str, pose: &str) -> String {
        let args = ["deform", "--mesh", mesh, "--rig", rig, "--pose", pose, "--out", "out.obj"];
        let stderr = self.fail(&args);
        assert!(!self.dir.path().join("out.obj").exists());
        stderr
    }

    /// Binds `mesh.obj` to `rig.json` into `name`, expected to succeed.
    fn bind(&self, name: &str) {
        let output = self.run(&["--quiet", "bind", "--mesh", "mesh.obj", "--rig", "rig.json", "--out", name]);
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    }

    /// `deform` of `mesh` with `rig.json`, `pose.json` and the bindings file `bindings`,
    /// expected to fail.
    fn deform_with_bindings_fails(&self, mesh: &str, rig: &str, bindings: &str) -> String {
        let args =
            ["deform", "--mesh", mesh, "--rig", rig, "--pose", "pose.json", "--out", "out.obj", "--bindings", bindings];
        self.fail(&args)
    }
}

/// Asserts a one-line message that starts with `prefix` (for messages that end in text from
/// the operating system or a parser).
fn assert_one_line_starting(stderr: &str, prefix: &str) {
    assert!(stderr.starts_with(prefix), "{stderr}");
    assert!(stderr.ends_with('\n'), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

#[test]
fn the_valid_scene_deforms() {
    // The scenes below differ from this one only in the file at fault.
    let scene = Scene::new();
    // The rest pose gives the rest positions back, up to f64 round-off on the reference path and
    // f32 round-off on the fast CPU path and the default backend (the GPU where one is available).
    for (backend, tolerance) in [("reference", 1e-12), ("cpu", 1e-6), ("auto", 1e-6)] {
        let args = ["deform", "--mesh", "mesh.obj", "--rig", "rig.json", "--pose", "pose.json", "--out", "out.obj"];
        let output = scene.run(&[&args[..], &["--backend", backend]].concat());
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let rest = Mesh::load(&scene.dir.path().join("mesh.obj")).unwrap();
        let out = Mesh::load(&scene.dir.path().join("out.obj")).unwrap();
        assert_eq!(out.faces, rest.faces);
        for (i, (p, q)) in out.positions.iter().zip(&rest.positions).enumerate() {
            assert!(p.distance(*q) < tolerance, "--backend {backend}, vertex {i}: {p} vs {q}");
        }
    }
}

#[test]
fn sweep_with_one_key() {
    let scene = Scene::new();
    scene.write("bad.json", neck_rig(&[key("0", IDENTITY, UNIT_RADII)]));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": needs at least 2 keys, found 1\n"
    );
}

#[test]
fn coincident_consecutive_centers() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("2", IDENTITY, UNIT_RADII), key("2", IDENTITY, UNIT_RADII)];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": key 2: center coincides with the center of key 1, \
         so the chord-length knot is undefined\n"
    );
}

#[test]
fn key_with_two_radii() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, "1, 1"), key("2", IDENTITY, "1, 1")];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": key 0: needs at least 3 radii, found 2\n"
    );
}

#[test]
fn keys_with_different_radius_counts() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("2", IDENTITY, "1, 1, 1")];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": key 1: has 3 radii but key 0 has 4; \
         every key of a sweep needs the same number\n"
    );
}

#[test]
fn rig_number_out_of_range() {
    // JSON has no infinity; a number too large for f64 is serde's "number out of range".
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("1e999", IDENTITY, UNIT_RADII)];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: not a valid rig file: number out of range at line 4 column 27\n"
    );
}

#[test]
fn obj_vertex_nan() {
    let scene = Scene::new();
    scene.write("bad.obj", PRISM.replacen("v -1 0 0", "v nan 0 0", 1));
    assert_eq!(
        scene.deform_fails("bad.obj", "rig.json", "pose.json"),
        "error: bad.obj:3: vertex 3 has a non-finite coordinate\n"
    );
}

#[test]
fn obj_vertex_inf() {
    let scene = Scene::new();
    scene.write("bad.obj", PRISM.replacen("v 0 1 2", "v 0 inf 2", 1));
    assert_eq!(
        scene.deform_fails("bad.obj", "rig.json", "pose.json"),
        "error: bad.obj:6: vertex 6 has a non-finite coordinate\n"
    );
}

#[test]
fn zero_quaternion() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("2", "0, 0, 0, 0", UNIT_RADII)];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": key 1: rotation is the zero quaternion\n"
    );
}

#[test]
fn negative_radius() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("2", IDENTITY, "1, 1, -0.5, 1")];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": key 1: radius 2 is negative (-0.5)\n"
    );
}

/// A rig of two sweeps on [`PRISM`]: `neck` (its group) and `body` (vertices 3 and 7, which no
/// face of `neck` uses).
fn two_sweep_rig() -> String {
    rig(&[sweep("neck", NECK_GROUP, &unit_keys()), sweep("body", r#"{"indices": [3, 7]}"#, &unit_keys())])
}

#[test]
fn pose_missing_a_sweep() {
    let scene = Scene::new();
    scene.write("two.json", two_sweep_rig());
    assert_eq!(
        scene.deform_fails("mesh.obj", "two.json", "pose.json"),
        "error: pose.json: the pose has no sweep \"body\", which the rest rig has\n"
    );
}

#[test]
fn pose_with_an_unknown_sweep() {
    let scene = Scene::new();
    scene.write("two.json", two_sweep_rig());
    scene.write(
        "bad.json",
        rig(&[
            sweep("neck", NECK_GROUP, &unit_keys()),
            sweep("body", r#"{"indices": [3, 7]}"#, &unit_keys()),
            sweep("tail", r#""all""#, &unit_keys()),
        ]),
    );
    assert_eq!(
        scene.deform_fails("mesh.obj", "two.json", "bad.json"),
        "error: bad.json: the pose has a sweep \"tail\", which the rest rig does not have\n"
    );
}

#[test]
fn pose_with_another_key_count() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("1", IDENTITY, UNIT_RADII), key("2", IDENTITY, UNIT_RADII)];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "rig.json", "bad.json"),
        "error: bad.json: sweep \"neck\": the pose has 3 keys but the rest rig has 2\n"
    );
}

#[test]
fn pose_with_another_radius_count() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("2", IDENTITY, "1, 1, 1, 1, 1")];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "rig.json", "bad.json"),
        "error: bad.json: sweep \"neck\": key 1: the pose has 5 radii but the rest rig has 4\n"
    );
}

#[test]
fn unknown_group_lists_the_mesh_groups() {
    let scene = Scene::new();
    scene.write("bad.json", rig(&[sweep("neck", r#"{"groups": ["head"]}"#, &unit_keys())]));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": the mesh mesh.obj has no group \"head\" \
         (its groups: neck, body)\n"
    );
}

#[test]
fn vertex_claimed_by_two_sweeps() {
    let scene = Scene::new();
    let both = rig(&[sweep("neck", NECK_GROUP, &unit_keys()), sweep("body", r#"{"groups": ["body"]}"#, &unit_keys())]);
    scene.write("bad.json", &both);
    scene.write("both_pose.json", &both);
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "both_pose.json"),
        "error: bad.json: vertex index 0 (zero-based) is claimed by both sweep \"neck\" and sweep \"body\"\n"
    );
}

#[test]
fn vertex_index_out_of_range() {
    let scene = Scene::new();
    scene.write("bad.json", rig(&[sweep("neck", r#"{"indices": [0, 8]}"#, &unit_keys())]));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": vertex index 8 (zero-based) is out of range \
         (the mesh mesh.obj has 8 vertices)\n"
    );
}

#[test]
fn truncated_rig_reports_line_and_column() {
    let scene = Scene::new();
    let text = neck_rig(&unit_keys());
    let cut = text.find("{\"center\": [0, 0, 2]").unwrap();
    scene.write("bad.json", &text[..cut]);
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: not a valid rig file: EOF while parsing a value at line 4 column 4\n"
    );
}

#[test]
fn wrong_format_field() {
    let scene = Scene::new();
    let text = neck_rig(&unit_keys()).replace("sweepffd-rig", "sweepffd-pose");
    scene.write("bad.json", text);
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: \"format\" is \"sweepffd-pose\", expected \"sweepffd-rig\"\n"
    );
}

#[test]
fn wrong_version_field() {
    let scene = Scene::new();
    let text = neck_rig(&unit_keys()).replace("\"version\": 1", "\"version\": 2");
    scene.write("bad.json", text);
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: \"version\" is 2, this release reads version 1\n"
    );
}

#[test]
fn unknown_field_centre() {
    let scene = Scene::new();
    let text = neck_rig(&unit_keys()).replacen("\"center\": [0, 0, 2]", "\"centre\": [0, 0, 2]", 1);
    scene.write("bad.json", text);
    assert_eq!(
        scene.deform_fails("mesh.obj", "rig.json", "bad.json"),
        "error: bad.json: not a valid rig file: unknown field `centre`, \
         expected one of `center`, `rotation`, `radii` at line 4 column 13\n"
    );
}

#[test]
fn obj_face_index_not_a_number() {
    let scene = Scene::new();
    scene.write("bad.obj", PRISM.replacen("f 2 3 7 6", "f 2 3 x7 6", 1));
    assert_eq!(
        scene.deform_fails("bad.obj", "rig.json", "pose.json"),
        "error: bad.obj:11: face index \"x7\" is not a number\n"
    );
}

#[test]
fn obj_face_index_past_the_last_vertex() {
    let scene = Scene::new();
    scene.write("bad.obj", PRISM.replacen("f 3 4 8 7", "f 3 4 9 7", 1));
    assert_eq!(
        scene.deform_fails("bad.obj", "rig.json", "pose.json"),
        "error: bad.obj:13: face refers to vertex 9 but the file has 8 vertices\n"
    );
}

#[test]
fn obj_garbage_coordinate() {
    let scene = Scene::new();
    scene.write("bad.obj", PRISM.replacen("v 0 -1 0", "v 0 -1x 0", 1));
    assert_eq!(
        scene.deform_fails("bad.obj", "rig.json", "pose.json"),
        "error: bad.obj:4: vertex coordinate \"-1x\" is not a number\n"
    );
}

#[test]
fn ply_bad_header() {
    let scene = Scene::new();
    scene.write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_heade\n");
    let stderr = scene.deform_fails("bad.ply", "rig.json", "pose.json");
    assert_one_line_starting(&stderr, "error: bad.ply: not a valid PLY file: Line 5: ");
    assert!(stderr.contains("end_heade"), "{stderr}");
}

#[test]
fn ply_truncated_binary_body() {
    let scene = Scene::new();
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n\
        property float x\nproperty float y\nproperty float z\nelement face 1\n\
        property list uchar int vertex_indices\nend_header\n"
        .to_vec();
    // One and a half of the three 12-byte vertices, and no face.
    bytes.extend_from_slice(&[0; 18]);
    scene.write("bad.ply", bytes);
    let stderr = scene.deform_fails("bad.ply", "rig.json", "pose.json");
    assert_one_line_starting(&stderr, "error: bad.ply: not a valid PLY file: ");
    assert!(stderr.contains("end of file"), "{stderr}");
    assert!(stderr.contains("'vertex'"), "{stderr}");
}

#[test]
fn mesh_without_vertices() {
    let scene = Scene::new();
    scene.write("empty.obj", "# nothing but a group\ng neck\n");
    assert_eq!(
        scene.deform_fails("empty.obj", "rig.json", "pose.json"),
        "error: empty.obj: the mesh has no vertices\n"
    );
    scene.write("zero.obj", "");
    assert_eq!(scene.deform_fails("zero.obj", "rig.json", "pose.json"), "error: zero.obj: the mesh has no vertices\n");
    scene.write(
        "empty.ply",
        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n\
         property float z\nend_header\n",
    );
    assert_eq!(
        scene.deform_fails("empty.ply", "rig.json", "pose.json"),
        "error: empty.ply: the mesh has no vertices\n"
    );
}

#[test]
fn unsupported_input_extension() {
    let scene = Scene::new();
    scene.write("mesh.stl", PRISM);
    assert_eq!(
        scene.deform_fails("mesh.stl", "rig.json", "pose.json"),
        "error: mesh.stl: unsupported mesh format (expected .obj, .ply, .off, .gltf or .glb)\n"
    );
}

#[test]
fn unsupported_output_extension() {
    let scene = Scene::new();
    let stderr =
        scene.fail(&["deform", "--mesh", "mesh.obj", "--rig", "rig.json", "--pose", "pose.json", "--out", "out.stl"]);
    assert_eq!(stderr, "error: out.stl: unsupported mesh format (expected .obj, .ply, .off, .gltf or .glb)\n");
}

#[test]
fn missing_input_files() {
    let scene = Scene::new();
    assert_one_line_starting(
        &scene.deform_fails("missing.obj", "rig.json", "pose.json"),
        "error: cannot read missing.obj: ",
    );
    assert_one_line_starting(
        &scene.deform_fails("mesh.obj", "missing.json", "pose.json"),
        "error: missing.json: cannot read the file: ",
    );
    assert_one_line_starting(
        &scene.deform_fails("mesh.obj", "rig.json", "missing.json"),
        "error: missing.json: cannot read the file: ",
    );
    assert_one_line_starting(
        &scene.deform_with_bindings_fails("mesh.obj", "rig.json", "missing.sffd"),
        "error: cannot read missing.sffd: ",
    );
}

#[test]
fn bindings_for_another_rig() {
    let scene = Scene::new();
    scene.bind("b.sffd");
    let keys = [key("0", IDENTITY, "1.5, 1.5, 1.5, 1.5"), key("2", IDENTITY, UNIT_RADII)];
    scene.write("other.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_with_bindings_fails("mesh.obj", "other.json", "b.sffd"),
        "error: b.sffd: the bindings were made for another rig (run `sweepffd bind` again)\n"
    );
}

#[test]
fn bindings_for_another_mesh() {
    let scene = Scene::new();
    scene.bind("b.sffd");
    scene.write("moved.obj", PRISM.replacen("v 1 0 0", "v 1.5 0 0", 1));
    assert_eq!(
        scene.deform_with_bindings_fails("moved.obj", "rig.json", "b.sffd"),
        "error: b.sffd: the bindings were made for another mesh with the same vertex count \
         (run `sweepffd bind` again)\n"
    );
    let seven = PRISM.replacen("v 0 -1 2\n", "", 1).replace(" 8", " 7");
    scene.write("seven.obj", seven);
    assert_eq!(
        scene.deform_with_bindings_fails("seven.obj", "rig.json", "b.sffd"),
        "error: b.sffd: the bindings were made for 8 vertices, the mesh has 7\n"
    );
}

#[test]
fn corrupt_bindings_file() {
    let scene = Scene::new();
    scene.bind("b.sffd");
    let bytes = scene.read("b.sffd");
    // The header, 8 vertex records and a band count of 0 (version 2).
    assert_eq!(bytes.len(), 40 + 40 * 8 + 8);

    scene.write("truncated.sffd", &bytes[..100]);
    assert_eq!(
        scene.deform_with_bindings_fails("mesh.obj", "rig.json", "truncated.sffd"),
        "error: truncated.sffd: not a sweepffd bindings file \
         (100 bytes for 8 vertices and a band count)\n"
    );

    scene.write("garbage.sffd", "not bindings at all, just some text\n");
    assert_eq!(
        scene.deform_with_bindings_fails("mesh.obj", "rig.json", "garbage.sffd"),
        "error: garbage.sffd: not a sweepffd bindings file (missing the SFFDBIND header)\n"
    );

    // Vertex 0's record names sweep 5 of a one-sweep rig.
    let mut bad_sweep = bytes.clone();
    bad_sweep[40..44].copy_from_slice(&5u32.to_le_bytes());
    scene.write("bad_sweep.sffd", bad_sweep);
    assert_eq!(
        scene.deform_with_bindings_fails("mesh.obj", "rig.json", "bad_sweep.sffd"),
        "error: bad_sweep.sffd: vertex 0: sweep 5 is out of range: the rig has 1 sweep\n"
    );
}

#[test]
fn output_into_a_missing_folder() {
    let scene = Scene::new();
    let stderr = scene.fail(&[
        "deform",
        "--mesh",
        "mesh.obj",
        "--rig",
        "rig.json",
        "--pose",
        "pose.json",
        "--out",
        "missing/out.obj",
    ]);
    let out = Path::new("missing").join("out.obj");
    assert_one_line_starting(&stderr, &format!("error: cannot write {}: ", out.display()));
    assert!(!scene.dir.path().join("missing").exists());
}

#[test]
fn bind_into_a_missing_folder() {
    let scene = Scene::new();
    let stderr = scene.fail(&["bind", "--mesh", "mesh.obj", "--rig", "rig.json", "--out", "missing/b.sffd"]);
    let out = Path::new("missing").join("b.sffd");
    assert_one_line_starting(&stderr, &format!("error: cannot write {}: ", out.display()));
    assert!(!scene.dir.path().join("missing").exists());
}

#[test]
fn pose_that_overflows_writes_nothing() {
    // Every number is finite, but radii of 1e308 would put the deformed vertices at infinity:
    // the pose is refused for radii beyond the largest rig coordinate.
    let scene = Scene::new();
    let huge = "1e308, 1e308, 1e308, 1e308";
    scene.write("bad.json", neck_rig(&[key("0", IDENTITY, huge), key("2", IDENTITY, huge)]));
    assert_eq!(
        scene.deform_fails("mesh.obj", "rig.json", "bad.json"),
        "error: bad.json: sweep \"neck\": key 0: radius 0 (1e308) is larger than 1e15 mesh units, the largest a \
         rig may have\n"
    );
}

#[test]
fn failed_deform_keeps_an_existing_output() {
    let scene = Scene::new();
    scene.write("out.obj", "old contents\n");
    let keys = [key("0", IDENTITY, UNIT_RADII), key("2", IDENTITY, "1, 1, -0.5, 1")];
    scene.write("bad.json", neck_rig(&keys));
    let stderr =
        scene.fail(&["deform", "--mesh", "mesh.obj", "--rig", "rig.json", "--pose", "bad.json", "--out", "out.obj"]);
    assert_eq!(stderr, "error: bad.json: sweep \"neck\": key 1: radius 2 is negative (-0.5)\n");
    assert_eq!(scene.read("out.obj"), b"old contents\n");
}

#[test]
fn volume_and_bind_report_rig_errors_like_deform() {
    let scene = Scene::new();
    let keys = [key("0", IDENTITY, UNIT_RADII), key("2", IDENTITY, "1, 1, -0.5, 1")];
    scene.write("bad.json", neck_rig(&keys));
    let expected = "error: bad.json: sweep \"neck\": key 1: radius 2 is negative (-0.5)\n";
    assert_eq!(scene.deform_fails("mesh.obj", "bad.json", "pose.json"), expected);
    assert_eq!(scene.fail(&["volume", "--rig", "bad.json"]), expected);
    assert_eq!(scene.fail(&["bind", "--mesh", "mesh.obj", "--rig", "bad.json", "--out", "b.sffd"]), expected);
    // A bad pose reads the same in `volume --pose` as in `deform`.
    assert_eq!(scene.fail(&["volume", "--rig", "rig.json", "--pose", "bad.json"]), expected);
    assert_eq!(scene.deform_fails("mesh.obj", "rig.json", "bad.json"), expected);
}

#[test]
fn volume_that_overflows_is_an_error() {
    let scene = Scene::new();
    let keys = [key("-1e308", IDENTITY, UNIT_RADII), key("1e308", IDENTITY, UNIT_RADII)];
    scene.write("huge.json", neck_rig(&keys));
    let output = scene.run(&["volume", "--rig", "rig.json", "--pose", "huge.json"]);
    assert_eq!(output.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&output.stderr),
        "error: huge.json: sweep \"neck\": key 0: center coordinate -1e308 lies beyond ±1e15 mesh units, the \
         largest a rig may have\n"
    );
    assert!(output.stdout.is_empty());
}

#[test]
fn rest_keys_too_far_apart_for_chord_length() {
    let scene = Scene::new();
    let keys = [key("-1e308", IDENTITY, UNIT_RADII), key("1e308", IDENTITY, UNIT_RADII)];
    scene.write("bad.json", neck_rig(&keys));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": key 0: center coordinate -1e308 lies beyond ±1e15 mesh units, the largest \
         a rig may have\n"
    );
}

/// The neck sweep of [`Scene`]'s rig with `"falloff": value` (the text as given).
fn neck_with_falloff(value: &str) -> String {
    sweep("neck", NECK_GROUP, &unit_keys()).replace("\"keys\"", &format!("\"falloff\": {value}, \"keys\""))
}

#[test]
fn negative_falloff() {
    let scene = Scene::new();
    scene.write("bad.json", rig(&[neck_with_falloff("-0.5")]));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"neck\": falloff -0.5 must be a finite width of at least 0 (mesh units)\n"
    );
}

#[test]
fn infinite_falloff() {
    let scene = Scene::new();
    scene.write("bad.json", rig(&[neck_with_falloff("1e999")]));
    let stderr = scene.deform_fails("mesh.obj", "bad.json", "pose.json");
    assert_one_line_starting(&stderr, "error: bad.json: ");
}

#[test]
fn falloff_larger_than_the_mesh() {
    let scene = Scene::new();
    scene.write("bad.json", rig(&[neck_with_falloff("40")]));
    let stderr = scene.deform_fails("mesh.obj", "bad.json", "pose.json");
    assert_one_line_starting(
        &stderr,
        "error: bad.json: sweep \"neck\": falloff 40 is larger than the mesh mesh.obj (its bounding box diagonal is 3.46",
    );
    // The same through `bind` and `render`, which write nothing either.
    let stderr = scene.fail(&["bind", "--mesh", "mesh.obj", "--rig", "bad.json", "--out", "b.sffd"]);
    assert_one_line_starting(&stderr, "error: bad.json: sweep \"neck\": falloff 40 is larger than the mesh");
}

#[test]
fn falloff_on_a_virtual_sweep() {
    let scene = Scene::new();
    let virtual_sweep =
        format!("  {{\"name\": \"joint\", \"falloff\": 0.5, \"keys\": [\n    {}\n  ]}}", unit_keys().join(",\n    "));
    scene.write("bad.json", rig(&[sweep("neck", NECK_GROUP, &unit_keys()), virtual_sweep]));
    assert_eq!(
        scene.deform_fails("mesh.obj", "bad.json", "pose.json"),
        "error: bad.json: sweep \"joint\": a virtual sweep (one that owns no vertices) cannot have a falloff\n"
    );
}

#[test]
fn bindings_file_with_a_bad_band_record() {
    let scene = Scene::new();
    scene.write("rig.json", rig(&[neck_with_falloff("1.5")]));
    scene.write("pose.json", rig(&[neck_with_falloff("1.5")]));
    scene.bind("good.sffd");
    let good = scene.read("good.sffd");
    // The band count follows the 40-byte header and 8 vertex records of 40 bytes.
    let bands_at = 40 + 8 * 40;
    let count = u64::from_le_bytes(good[bands_at..bands_at + 8].try_into().unwrap());
    assert!(count > 0, "the falloff puts vertices in a band");
    // The first band record's weight (after its vertex and second sweep) set to 2.
    let mut bad = good.clone();
    let weight_at = bands_at + 8 + 8;
    bad[weight_at..weight_at + 8].copy_from_slice(&2.0f64.to_le_bytes());
    scene.write("bad.sffd", &bad);
    assert_eq!(
        scene.deform_with_bindings_fails("mesh.obj", "rig.json", "bad.sffd"),
        "error: bad.sffd: band vertex 0 (vertex 0): weight 2 is outside [0, 1)\n"
    );
    // A truncated band section.
    scene.write("short.sffd", &good[..good.len() - 4]);
    let stderr = scene.deform_with_bindings_fails("mesh.obj", "rig.json", "short.sffd");
    assert_one_line_starting(&stderr, "error: short.sffd: not a sweepffd bindings file (");
}

#[test]
fn version_1_bindings_files_still_load() {
    let scene = Scene::new();
    scene.bind("v2.sffd");
    let v2 = scene.read("v2.sffd");
    // Without falloff a version 2 file is the version 1 file plus a band count of 0.
    assert_eq!(&v2[v2.len() - 8..], &[0u8; 8]);
    let mut v1 = v2[..v2.len() - 8].to_vec();
    v1[8..12].copy_from_slice(&1u32.to_le_bytes());
    scene.write("v1.sffd", &v1);
    let args =
        ["--quiet", "deform", "--mesh", "mesh.obj", "--rig", "rig.json", "--pose", "pose.json", "--out", "o.obj"];
    let output = scene.run(&[&args[..], &["--bindings", "v1.sffd", "--backend", "cpu"]].concat());
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
}
