//! The command line end to end: `demo` writes a scene that `deform` reproduces; a pose that
//! bends, twists and tapers the Stanford bunny comes out as valid OBJ and PLY with the input's
//! faces; `volume` matches πr²L for straight sweeps; `bind` writes a bindings file the library
//! reads; and every subcommand documents its options.

use crate::common;

use std::f64::consts::PI;
use std::fs;
use std::path::Path;
use std::process::Output;

use glam::DVec3;
use sweepffd::bind::bind_vertices;
use sweepffd::bindings_file::BindingsFile;
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

/// Runs the command line in `dir`.
fn run(dir: &Path, args: &[&str]) -> Output {
    common::sweepffd(dir).args(args).output().unwrap()
}

/// Runs the command line in `dir`, expects success, and returns stdout.
fn succeed(dir: &Path, args: &[&str]) -> String {
    let output = run(dir, args);
    assert!(output.status.success(), "{args:?} failed: {}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8(output.stdout).unwrap()
}

/// The largest distance between corresponding positions and the index where it occurs.
fn worst_distance(a: &[DVec3], b: &[DVec3]) -> (f64, usize) {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| p.distance(*q))
        .enumerate()
        .fold((0.0, 0), |(max, at), (i, d)| if d > max { (d, i) } else { (max, at) })
}

/// Asserts equal face lists, naming the first face that differs.
fn assert_same_faces(output: &Mesh, input: &Mesh, what: &str) {
    assert_eq!(output.faces.len(), input.faces.len(), "{what}: face count");
    if let Some(f) = (0..input.faces.len()).find(|&f| output.faces.face(f) != input.faces.face(f)) {
        panic!("{what}: face {f} is {:?}, the input's is {:?}", output.faces.face(f), input.faces.face(f));
    }
}

/// Whether an OBJ line is a `v` statement.
fn is_vertex_line(line: &[u8]) -> bool {
    let line = line.trim_ascii_start();
    line.starts_with(b"v ") || line.starts_with(b"v\t")
}

/// Asserts that `output` is `input` with only `v` lines changed: the same number of lines, and
/// every other line byte-identical and in the same place.
fn assert_only_vertex_lines_differ(output: &[u8], input: &[u8]) {
    let output: Vec<&[u8]> = output.split(|&b| b == b'\n').collect();
    let input: Vec<&[u8]> = input.split(|&b| b == b'\n').collect();
    assert_eq!(output.len(), input.len(), "line count");
    for (number, (out, inp)) in output.iter().zip(&input).enumerate() {
        if is_vertex_line(inp) {
            assert!(is_vertex_line(out), "line {}: a v line became {:?}", number + 1, String::from_utf8_lossy(out));
        } else {
            assert_eq!(
                out,
                inp,
                "line {}: {:?} became {:?}",
                number + 1,
                String::from_utf8_lossy(inp),
                String::from_utf8_lossy(out)
            );
        }
    }
}

#[test]
fn demo_writes_its_scene_and_deform_reproduces_it() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = succeed(dir.path(), &["demo"]);
    let out = Path::new("sweepffd-demo");
    for name in ["rest.obj", "deformed.obj", "rig.json", "pose.json"] {
        let path = out.join(name);
        assert!(dir.path().join(&path).is_file(), "{} missing", path.display());
        assert!(
            stdout.contains(&format!("wrote {}", path.display())),
            "stdout does not say where {name} went:\n{stdout}"
        );
    }

    let demo = dir.path().join(out);
    let rest = Mesh::load(&demo.join("rest.obj")).unwrap();
    let deformed = Mesh::load(&demo.join("deformed.obj")).unwrap();
    assert_same_faces(&deformed, &rest, "deformed.obj");
    let (moved, _) = worst_distance(&deformed.positions, &rest.positions);
    assert!(moved > 0.1 * rest.diagonal(), "the demo pose moves vertices by at most {moved}");

    succeed(
        dir.path(),
        &[
            "--quiet",
            "deform",
            "--mesh",
            "sweepffd-demo/rest.obj",
            "--rig",
            "sweepffd-demo/rig.json",
            "--pose",
            "sweepffd-demo/pose.json",
            "--out",
            "again.obj",
            "--backend",
            "reference",
        ],
    );
    let again = Mesh::load(&dir.path().join("again.obj")).unwrap();
    assert_same_faces(&again, &rest, "again.obj");
    let (error, at) = worst_distance(&again.positions, &deformed.positions);
    assert!(
        error <= 1e-12 * rest.diagonal(),
        "deform differs from the demo by {:.3e} × diagonal at vertex {at}",
        error / rest.diagonal()
    );
}

#[test]
fn demo_out_names_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = succeed(dir.path(), &["demo", "--out", "elsewhere/scene"]);
    let out = Path::new("elsewhere").join("scene");
    for name in ["rest.obj", "deformed.obj", "rig.json", "pose.json"] {
        assert!(dir.path().join(out.join(name)).is_file(), "{name} missing");
    }
    assert!(stdout.contains(&format!("wrote {}", out.join("rest.obj").display())));
    assert!(!dir.path().join("sweepffd-demo").exists());
}

#[test]
fn quiet_demo_prints_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // The flag is global: before or after the subcommand.
    for args in [&["--quiet", "demo", "--out", "before"][..], &["demo", "--out", "after", "-q"][..]] {
        let output = run(dir.path(), args);
        assert!(output.status.success(), "{args:?}");
        assert!(output.stdout.is_empty(), "{args:?} printed {:?}", String::from_utf8_lossy(&output.stdout));
        assert!(output.stderr.is_empty(), "{args:?}");
    }
    for out in ["before", "after"] {
        assert!(dir.path().join(out).join("deformed.obj").is_file());
    }
}

/// A reader that has gone (`sweepffd demo | head -0`) ends the command as a shell's SIGPIPE would:
/// status 141, no panic (it panicked with status 101 on its first line before), and no
/// temporary file left behind. Standard output is a pipe whose reading end is closed before the
/// command starts, so every line it prints meets the closed pipe.
#[test]
fn a_reader_that_has_gone_ends_the_command_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let output = common::sweepffd(dir.path()).args(["demo"]).stdout(writer).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(141), "stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let left: Vec<_> = std::fs::read_dir(dir.path().join("sweepffd-demo"))
        .map(|entries| entries.map(|e| e.unwrap().file_name()).collect())
        .unwrap_or_default();
    assert!(left.iter().all(|name| !name.to_string_lossy().ends_with(".tmp")), "{left:?}");
    // The same for standard error: an error message that cannot be read.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let missing = ["deform", "--mesh", "missing.obj", "--rig", "r.json", "--pose", "p.json", "--out", "o.obj"];
    let output = common::sweepffd(dir.path()).args(missing).stderr(writer).output().unwrap();
    assert_eq!(output.status.code(), Some(141));
}

/// The pose of the acceptance test: a quarter-turn bend, a 0.4π twist and a taper to 60%.
const BUNNY_POSE: BendTwistTaper = BendTwistTaper { bend: 0.5 * PI, twist: 0.4 * PI, taper: 0.6 };

/// Poses the shared mesh `name` through the command line into each of `outputs`, once with
/// bindings from `bind` and once binding anew, and checks each result against the input.
fn pose_shared_mesh(name: &str, outputs: &[&str]) {
    let Some(source) = common::shared_mesh(name) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let input_name = format!("input.{}", source.extension().unwrap().to_str().unwrap());
    fs::copy(&source, dir.path().join(&input_name)).unwrap();
    let input = Mesh::load(&source).unwrap();
    let rig = common::axis_rig(&input, 9, 16);
    fs::write(dir.path().join("rig.json"), rig.to_document().to_json()).unwrap();
    let pose = rig.pose_document(&BUNNY_POSE.keys(&rig));
    fs::write(dir.path().join("pose.json"), pose.to_json()).unwrap();

    let stdout = succeed(dir.path(), &["bind", "--mesh", input_name.as_str(), "--rig", "rig.json", "--out", "b.sffd"]);
    assert!(stdout.contains("-> b.sffd"), "{stdout}");

    for output in outputs {
        let with = format!("with_bindings_{output}");
        let without = format!("without_bindings_{output}");
        let deform = |out: &str, bindings: Option<&str>| {
            let mut args =
                vec!["deform", "--mesh", input_name.as_str(), "--rig", "rig.json", "--pose", "pose.json", "--out", out];
            args.extend(bindings.iter().flat_map(|b| ["--bindings", *b]));
            let stdout = succeed(dir.path(), &args);
            assert!(stdout.contains(&format!("-> {out}")), "{stdout}");
        };
        deform(&with, Some("b.sffd"));
        deform(&without, None);

        let loaded = Mesh::load(&dir.path().join(&with)).unwrap();
        let rebound = Mesh::load(&dir.path().join(&without)).unwrap();
        for (mesh, what) in [(&loaded, &with), (&rebound, &without)] {
            assert_eq!(mesh.positions.len(), input.positions.len(), "{what}");
            assert_same_faces(mesh, &input, what);
            assert!(mesh.positions.iter().all(|p| p.is_finite()), "{what} has a non-finite coordinate");
        }
        if let Some(i) =
            (0..input.positions.len()).find(|&i| loaded.positions[i].to_array() != rebound.positions[i].to_array())
        {
            panic!(
                "{output}: vertex {i} is {} with bindings and {} without",
                loaded.positions[i], rebound.positions[i]
            );
        }
        let (moved, at) = worst_distance(&loaded.positions, &input.positions);
        println!("{name} -> {output}: largest displacement {:.3} × diagonal at vertex {at}", moved / input.diagonal());
        assert!(
            moved > 0.2 * input.diagonal(),
            "{output}: the pose moves vertices by only {:.3e} × diagonal",
            moved / input.diagonal()
        );
        if input_name.ends_with(".obj") && output.ends_with(".obj") {
            assert_only_vertex_lines_differ(&fs::read(dir.path().join(&with)).unwrap(), &fs::read(&source).unwrap());
        }
    }
}

#[test]
fn bunny_obj_bend_twist_taper_writes_obj_and_ply_with_the_input_faces() {
    pose_shared_mesh("bunny_stanford_zipper.obj", &["out.obj", "out.ply"]);
}

#[test]
fn bunny_ply_bend_twist_taper_writes_ply_with_the_input_faces() {
    pose_shared_mesh("bunny_stanford_zipper.ply", &["out.ply"]);
}

/// Two straight sweeps of constant radius: `straight` along +z from (2, −1, 1), radius 0.75,
/// length 3, and `thin` along +x from the origin (normal turned onto x), radius 0.25, length 1.
const STRAIGHT_RIG: &str = r#"{"format": "sweepffd-rig", "version": 1, "sweeps": [
  {"name": "straight", "keys": [
    {"center": [2, -1, 1], "rotation": [0, 0, 0, 1], "radii": [0.75, 0.75, 0.75, 0.75, 0.75, 0.75]},
    {"center": [2, -1, 2.5], "rotation": [0, 0, 0, 1], "radii": [0.75, 0.75, 0.75, 0.75, 0.75, 0.75]},
    {"center": [2, -1, 4], "rotation": [0, 0, 0, 1], "radii": [0.75, 0.75, 0.75, 0.75, 0.75, 0.75]}]},
  {"name": "thin", "keys": [
    {"center": [0, 0, 0], "rotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "radii": [0.25, 0.25, 0.25]},
    {"center": [1, 0, 0], "rotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "radii": [0.25, 0.25, 0.25]}]}
]}
"#;

/// A pose of [`STRAIGHT_RIG`]: `straight` stretched to length 4 and thinned to radius 0.5,
/// `thin` as it was.
const STRAIGHT_POSE: &str = r#"{"format": "sweepffd-rig", "version": 1, "sweeps": [
  {"name": "straight", "keys": [
    {"center": [2, -1, 1], "rotation": [0, 0, 0, 1], "radii": [0.5, 0.5, 0.5, 0.5, 0.5, 0.5]},
    {"center": [2, -1, 3], "rotation": [0, 0, 0, 1], "radii": [0.5, 0.5, 0.5, 0.5, 0.5, 0.5]},
    {"center": [2, -1, 5], "rotation": [0, 0, 0, 1], "radii": [0.5, 0.5, 0.5, 0.5, 0.5, 0.5]}]},
  {"name": "thin", "keys": [
    {"center": [0, 0, 0], "rotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "radii": [0.25, 0.25, 0.25]},
    {"center": [1, 0, 0], "rotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "radii": [0.25, 0.25, 0.25]}]}
]}
"#;

/// Runs `volume` and returns the (name, volume) pairs and the total of its one line of JSON.
fn volume(dir: &Path, args: &[&str]) -> (Vec<(String, f64)>, f64) {
    let stdout = succeed(dir, args);
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let keys: Vec<&String> = report.as_object().unwrap().keys().collect();
    assert_eq!(keys, ["sweeps", "total"], "{stdout}");
    let sweeps = report["sweeps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| (s["name"].as_str().unwrap().to_string(), s["volume"].as_f64().unwrap()))
        .collect();
    (sweeps, report["total"].as_f64().unwrap())
}

fn assert_relative(found: f64, expected: f64, what: &str) {
    assert!(((found - expected) / expected).abs() <= 1e-9, "{what}: {found} vs {expected}");
}

#[test]
fn volume_of_straight_sweeps_is_pi_r_squared_l() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("rig.json"), STRAIGHT_RIG).unwrap();
    let (sweeps, total) = volume(dir.path(), &["volume", "--rig", "rig.json"]);
    let names: Vec<&str> = sweeps.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["straight", "thin"]);
    let straight = PI * 0.75 * 0.75 * 3.0;
    let thin = PI * 0.25 * 0.25 * 1.0;
    assert_relative(sweeps[0].1, straight, "straight");
    assert_relative(sweeps[1].1, thin, "thin");
    assert_relative(total, straight + thin, "total");
}

#[test]
fn volume_with_pose_reports_the_posed_volume() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("rig.json"), STRAIGHT_RIG).unwrap();
    fs::write(dir.path().join("pose.json"), STRAIGHT_POSE).unwrap();
    let (sweeps, total) = volume(dir.path(), &["volume", "--rig", "rig.json", "--pose", "pose.json"]);
    let straight = PI * 0.5 * 0.5 * 4.0;
    let thin = PI * 0.25 * 0.25 * 1.0;
    assert_eq!(sweeps[0].0, "straight");
    assert_relative(sweeps[0].1, straight, "posed straight");
    assert_relative(sweeps[1].1, thin, "posed thin");
    assert_relative(total, straight + thin, "posed total");
}

#[test]
fn bind_file_round_trips_through_the_library() {
    let dir = tempfile::tempdir().unwrap();
    let tube = Tube { rings: 12, around: 16, length: 3.0, radius: 0.4 };
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.path().join("tube.obj"), &mesh.mesh.positions).unwrap();
    let rig = tube_rig(&tube, 4, 8);
    fs::write(dir.path().join("rig.json"), rig.to_document().to_json()).unwrap();

    let stdout = succeed(
        dir.path(),
        &["bind", "--mesh", "tube.obj", "--rig", "rig.json", "--out", "tube.sffd", "--backend", "reference"],
    );
    let count = tube.vertex_count();
    assert!(stdout.starts_with(&format!("bound {count} of {count} vertices to 1 sweeps")), "{stdout}");

    let path = dir.path().join("tube.sffd");
    let file = BindingsFile::load(&path).unwrap();
    assert_eq!(file.bindings.vertices.len(), count);
    assert_eq!(file.sweep_count, 1);
    assert!(file.bindings.vertices.iter().all(|b| b.sweep == 0));
    let mesh = Mesh::load(&dir.path().join("tube.obj")).unwrap();
    let rig = Rig::load(&dir.path().join("rig.json")).unwrap();
    file.check_matches(&rig, &mesh.positions, &path).unwrap();
    let owners = rig.owners(&mesh, "tube.obj").unwrap();
    let expected = bind_vertices(rig.rest(), &owners, &mesh.positions, &|_| {});
    assert_eq!(file.bindings.vertices, expected);
}

#[test]
fn gpu_backend_binds_and_deforms_like_the_cpu() {
    if common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let tube = Tube { rings: 40, around: 32, length: 3.0, radius: 0.4 };
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.path().join("tube.obj"), &mesh.mesh.positions).unwrap();
    let rig = tube_rig(&tube, 5, 8);
    fs::write(dir.path().join("rig.json"), rig.to_document().to_json()).unwrap();
    let pose = rig.pose_document(&sweepffd::synthetic::BendTwistTaper { bend: 1.0, twist: 1.5, taper: 0.5 }.keys(&rig));
    fs::write(dir.path().join("pose.json"), pose.to_json()).unwrap();
    let base = ["--mesh", "tube.obj", "--rig", "rig.json"];
    let deform = [&base[..], &["--pose", "pose.json"]].concat();

    // Bindings made on the GPU equal the CPU's to f32 precision, whichever backend then deforms.
    succeed(dir.path(), &[&["bind"][..], &base, &["--out", "gpu.sffd", "--backend", "gpu"]].concat());
    succeed(dir.path(), &[&["bind"][..], &base, &["--out", "cpu.sffd", "--backend", "cpu"]].concat());
    let (gpu, cpu) = (
        BindingsFile::load(&dir.path().join("gpu.sffd")).unwrap(),
        BindingsFile::load(&dir.path().join("cpu.sffd")).unwrap(),
    );
    let worst_t = gpu
        .bindings
        .vertices
        .iter()
        .zip(&cpu.bindings.vertices)
        .map(|(g, c)| (g.params.t - c.params.t).abs())
        .fold(0.0, f64::max);
    assert!(worst_t <= 1e-5, "GPU bindings differ from the CPU's by |Δt| = {worst_t:e}");

    let runs = [
        ("cpu", "cpu.sffd", "a.obj"),
        ("gpu", "cpu.sffd", "b.obj"),
        ("gpu", "gpu.sffd", "c.obj"),
        ("cpu", "gpu.sffd", "d.obj"),
    ];
    for (backend, bindings, out) in runs {
        succeed(
            dir.path(),
            &[&["deform"][..], &deform, &["--bindings", bindings, "--out", out, "--backend", backend]].concat(),
        );
    }
    let reference = Mesh::load(&dir.path().join("a.obj")).unwrap();
    for (_, _, out) in &runs[1..] {
        let other = Mesh::load(&dir.path().join(out)).unwrap();
        let (error, at) = worst_distance(&other.positions, &reference.positions);
        assert!(error <= 1e-5 * reference.diagonal(), "{out} differs by {error:e} at vertex {at}");
    }
}

#[test]
fn help_of_each_subcommand_lists_its_options() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 4] = [
        ("bind", &["--mesh", "--rig", "--out", "--quiet"]),
        ("deform", &["--mesh", "--rig", "--pose", "--out", "--bindings", "--quiet"]),
        ("volume", &["--rig", "--pose", "--quiet"]),
        ("demo", &["--out", "--quiet"]),
    ];
    for (command, options) in cases {
        let help = succeed(dir.path(), &[command, "--help"]);
        for option in options {
            assert!(help.contains(option), "`{command} --help` does not mention {option}:\n{help}");
        }
    }
    let help = succeed(dir.path(), &["--help"]);
    for command in ["bind", "deform", "volume", "demo"] {
        assert!(help.contains(command), "--help does not list {command}");
    }
    assert!(fs::read_dir(dir.path()).unwrap().next().is_none());
}

/// A tube mesh, its rig and a bend-twist-taper pose written into `dir`.
fn write_tube_scene(dir: &Path) {
    let tube = Tube { rings: 20, around: 16, length: 2.0, radius: 0.3 };
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.join("tube.obj"), &mesh.mesh.positions).unwrap();
    let rig = tube_rig(&tube, 4, 8);
    fs::write(dir.join("rig.json"), rig.to_document().to_json()).unwrap();
    let keys = BendTwistTaper { bend: 0.8, twist: 1.0, taper: 0.7 }.keys(&rig);
    fs::write(dir.join("pose.json"), rig.pose_document(&keys).to_json()).unwrap();
}

#[test]
fn gpu_backend_without_an_adapter_is_a_clear_error_and_auto_falls_back() {
    let dir = tempfile::tempdir().unwrap();
    write_tube_scene(dir.path());
    let deform = ["deform", "--mesh", "tube.obj", "--rig", "rig.json", "--pose", "pose.json", "--out", "out.obj"];
    // Off Apple platforms WGPU_BACKEND=metal leaves no adapter to pick.
    if cfg!(target_vendor = "apple") {
        return;
    }
    let gpu = common::sweepffd(dir.path())
        .args(deform)
        .args(["--backend", "gpu"])
        .env("WGPU_BACKEND", "metal")
        .output()
        .unwrap();
    assert_eq!(gpu.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&gpu.stderr);
    assert!(stderr.starts_with("error: no GPU adapter is available"), "{stderr}");
    assert!(!dir.path().join("out.obj").exists());

    let auto = common::sweepffd(dir.path()).args(deform).env("WGPU_BACKEND", "metal").output().unwrap();
    assert!(auto.status.success(), "{}", String::from_utf8_lossy(&auto.stderr));
    let stderr = String::from_utf8_lossy(&auto.stderr);
    assert_eq!(stderr.lines().count(), 1, "one notice line: {stderr}");
    assert!(stderr.starts_with("note: using the CPU, the GPU is not available: no GPU adapter"), "{stderr}");
    assert!(dir.path().join("out.obj").exists());
}

#[test]
fn info_names_the_adapter_and_its_limits() {
    if common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let stdout = succeed(dir.path(), &["info"]);
    assert!(stdout.starts_with("adapter:"), "{stdout}");
    assert!(stdout.contains("max_storage_buffer_binding_size:"), "{stdout}");
    assert!(stdout.contains("workgroup size of the kernels:"), "{stdout}");
}

#[test]
fn bench_prints_one_json_line_with_every_figure() {
    let dir = tempfile::tempdir().unwrap();
    let mut backends = vec!["cpu"];
    if common::gpu().is_some() {
        backends.push("gpu");
    }
    for backend in backends {
        let stdout =
            succeed(dir.path(), &["bench", "--vertices", "20000", "--runs", "3", "--backend", backend, "--json"]);
        assert_eq!(stdout.lines().count(), 1, "{stdout}");
        let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        assert_eq!(report["backend"], backend);
        assert!(report["n"].as_u64().unwrap() >= 19_000);
        for field in [
            "bind_verts_per_s",
            "deform_verts_per_s",
            "copy_verts_per_s",
            "lbs_verts_per_s",
            "deform_over_copy",
            "deform_over_lbs",
            "frame_ms",
        ] {
            let value = report[field].as_f64().unwrap_or_else(|| panic!("{backend}: {field} missing in {stdout}"));
            assert!(value.is_finite() && value > 0.0, "{backend}: {field} = {value}");
        }
        if backend == "gpu" {
            // Bindings (16) and positions (12); normals (12) and their pass's lists: the vertex
            // (4), its row start (4) and its fan of neighbours, 6 on the tube's grid, closed
            // without repeating the first (24), fewer on the two boundary rings; on a CPU
            // adapter the cell groups too: 4 bytes a slot, room for a slot a vertex and 3 free
            // ones for each of 112 cells in each block of 256 vertices (9.25), and a counter for
            // each (1.75).
            let bytes = report["device_bytes_per_vertex"].as_f64().unwrap();
            let groups = if report["adapter"].as_str().is_some_and(|a| a.contains("llvmpipe")) { 11.0 } else { 0.0 };
            assert!(bytes > 68.0 + groups && bytes <= 72.5 + groups, "device bytes per vertex {bytes}");
            // The choices for the adapter, and the alternatives timed beside them.
            let cpu_adapter = groups > 0.0;
            let (records, order) =
                if cpu_adapter { ("uniform", "cell groups") } else { ("storage", "staged vertices") };
            assert_eq!(
                (report["cell_records"].as_str(), report["deform_order"].as_str()),
                (Some(records), Some(order))
            );
            let alternatives = report["alternatives"].as_array().unwrap();
            assert_eq!(alternatives.len(), 3, "the other records, and each other order: {stdout}");
            for alternative in alternatives {
                let over = alternative["over_chosen"].as_f64().unwrap();
                assert!(over.is_finite() && over > 0.0, "{alternative}");
                assert_ne!(
                    (alternative["cell_records"].as_str(), alternative["deform_order"].as_str()),
                    (Some(records), Some(order))
                );
            }
            assert_eq!(report["repeats"].as_u64(), Some(if cpu_adapter { 1 } else { 10 }));
            for field in ["ms", "host_ms", "jacobian_normals_ms", "jacobian_normals_host_ms"] {
                let ms = report["creation"][field].as_f64().unwrap_or_else(|| panic!("creation.{field} in {stdout}"));
                assert!(ms.is_finite() && ms > 0.0, "creation.{field} = {ms}");
            }
            // Every pass's traffic, each share of the ceilings a finite positive number; the
            // deform kernel moves a 16-byte binding and a 12-byte position a vertex.
            let memory = &report["memory"];
            let passes = memory["passes"].as_array().unwrap();
            let names: Vec<&str> = passes.iter().map(|p| p["pass"].as_str().unwrap()).collect();
            let expected =
                ["deform", "copy kernel", "lbs", "bands (rest)", "bands (sweep)", "normals", "fused", "bind"];
            assert_eq!(names, expected);
            assert_eq!(passes[0]["bytes_per_vertex"].as_f64(), Some(28.0));
            for pass in passes {
                for field in ["bytes_per_vertex", "gb_per_s", "of_copy_kernel", "of_buffer_copy"] {
                    let value = pass[field].as_f64().unwrap();
                    assert!(value.is_finite() && value > 0.0, "{pass}");
                }
            }
            assert!(memory["buffer_copy_gb_per_s"].as_f64().is_some_and(|rate| rate > 0.0), "{memory}");
            assert!(report["readback_ms"].as_f64().is_some_and(|ms| ms > 0.0));
            assert!(report["frame_cpu_ms"].as_f64().is_some_and(|ms| ms > 0.0));
            for field in ["fused_over_copy", "fused_over_separate", "instances_over_single", "partial_over_full"] {
                let value = report[field].as_f64().unwrap_or_else(|| panic!("{field} missing in {stdout}"));
                assert!(value.is_finite() && value > 0.0, "{field} = {value}");
            }
            // The bench's tube is smooth and fine: the two kinds of normals agree closely.
            let angle = report["normals_angle_p99_deg"].as_f64().unwrap();
            assert!((0.0..2.0).contains(&angle), "normals angle {angle}°");
        } else {
            for field in ["frame_cpu_ms", "fused_over_copy", "normals_angle_p99_deg"] {
                assert!(report[field].is_null(), "{field} in {stdout}");
            }
            // The fast path's figures above, the f64 reference's in the same run.
            let cpu = &report["cpu"];
            assert!(cpu["isa"].is_string(), "{stdout}");
            for field in ["reference_deform_verts_per_s", "reference_bind_verts_per_s", "reference_over_fast"] {
                let value = cpu[field].as_f64().unwrap_or_else(|| panic!("cpu.{field} missing in {stdout}"));
                assert!(value.is_finite() && value > 0.0, "cpu.{field} = {value}");
            }
        }
    }
}
