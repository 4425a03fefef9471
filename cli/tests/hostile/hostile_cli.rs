//! Hostile input through the command line: bindings files with values no binding can have,
//! sizes past the limits (subdivision, fitting, benches), signals in the middle of a write, a
//! symbolic link at `--out`, and the exit statuses. Each refusal is one exact `error: …` line,
//! exit status 1, and leaves the folder as it was.

use crate::common;

use std::f64::consts::TAU;
use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use sweepffd::bind::{Binding, MeshBindings, VertexBinding};
use sweepffd::bindings_file::{BindingsFile, check};
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::synthetic::{Tube, attached_tube_rig, split_tube_rig, tube_rig};
use tempfile::TempDir;

/// The tube of the bindings tests: 6 rings of 8 and two cap centers, 50 vertices.
const TUBE: Tube = Tube { rings: 6, around: 8, length: 2.0, radius: 0.5 };

/// Where a bindings file's vertex records start, and their size.
const RECORDS_AT: usize = 40;
const RECORD_BYTES: usize = 40;

/// Where the band records start (after the band count) in a file of `vertices` vertices.
fn bands_at(vertices: usize) -> usize {
    RECORDS_AT + RECORD_BYTES * vertices + 8
}

/// A temporary folder in which the command line runs, with relative paths.
struct Scene {
    dir: TempDir,
}

impl Scene {
    /// `tube.obj` ([`TUBE`]) and `rig.json` (the rig `rig` makes of the tube), with the rest
    /// pose as `pose.json`.
    fn tube(rig: impl Fn(&Tube) -> Rig) -> Scene {
        let scene = Scene { dir: tempfile::tempdir().unwrap() };
        let mesh = LoadedMesh::from(TUBE.mesh());
        mesh.save(&scene.path("tube.obj"), &mesh.mesh.positions).unwrap();
        let json = rig(&TUBE).to_document().to_json();
        scene.write("rig.json", &json);
        scene.write("pose.json", &json);
        scene
    }

    fn path(&self, name: &str) -> std::path::PathBuf {
        self.dir.path().join(name)
    }

    fn write(&self, name: &str, contents: impl AsRef<[u8]>) {
        fs::write(self.path(name), contents).unwrap();
    }

    fn read(&self, name: &str) -> Vec<u8> {
        fs::read(self.path(name)).unwrap()
    }

    fn run(&self, args: &[&str]) -> Output {
        common::sweepffd(self.dir.path()).args(args).output().unwrap()
    }

    /// Sorted names in the folder.
    fn entries(&self) -> Vec<String> {
        entries(self.dir.path())
    }

    /// Runs `args`, expects exit status `code` without a panic, nothing on stdout and no new
    /// or changed file, and returns stderr.
    fn fail_with(&self, code: i32, args: &[&str]) -> String {
        let before: Vec<(String, Vec<u8>)> = self.entries().into_iter().map(|n| (n.clone(), self.read(&n))).collect();
        let output = self.run(args);
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(output.status.code(), Some(code), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(output.stdout.is_empty(), "{args:?} printed on stdout: {}", String::from_utf8_lossy(&output.stdout));
        let after: Vec<(String, Vec<u8>)> = self.entries().into_iter().map(|n| (n.clone(), self.read(&n))).collect();
        assert_eq!(after, before, "{args:?} left the folder changed");
        stderr
    }

    /// [`Scene::fail_with`] exit status 1.
    fn fail(&self, args: &[&str]) -> String {
        self.fail_with(1, args)
    }

    /// Runs `args` and expects success; returns stdout.
    fn succeed(&self, args: &[&str]) -> String {
        let output = self.run(args);
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        String::from_utf8(output.stdout).unwrap()
    }

    /// Binds `tube.obj` to `rig.json` on the CPU into `b.sffd` and returns its bytes.
    fn bind(&self) -> Vec<u8> {
        self.succeed(&[
            "--quiet",
            "bind",
            "--mesh",
            "tube.obj",
            "--rig",
            "rig.json",
            "--out",
            "b.sffd",
            "--backend",
            "cpu",
        ]);
        self.read("b.sffd")
    }

    /// `deform` with the bindings file `bindings` on `backend` into `out`.
    fn deform_args<'a>(bindings: &'a str, backend: &'a str, out: &'a str) -> Vec<&'a str> {
        let mut args = vec!["--quiet", "deform", "--mesh", "tube.obj", "--rig", "rig.json", "--pose", "pose.json"];
        args.extend(["--bindings", bindings, "--backend", backend, "--out", out]);
        args
    }

    /// Writes `bytes` as `bad.sffd` and expects `deform --bindings bad.sffd` to fail on both
    /// backends with the same message, which it returns.
    fn bindings_refused(&self, bytes: &[u8]) -> String {
        self.write("bad.sffd", bytes);
        let cpu = self.fail(&Scene::deform_args("bad.sffd", "cpu", "out.obj"));
        // The file is refused before any device is looked for, so even without an adapter the
        // GPU backend gives the same message.
        let gpu = self.fail(&Scene::deform_args("bad.sffd", "gpu", "out.obj"));
        assert_eq!(gpu, cpu, "the GPU backend refuses the file differently");
        fs::remove_file(self.path("bad.sffd")).unwrap();
        cpu
    }
}

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// `bytes` with the f64 at `at` set to `value`.
fn with_f64(bytes: &[u8], at: usize, value: f64) -> Vec<u8> {
    let mut bytes = bytes.to_vec();
    bytes[at..at + 8].copy_from_slice(&value.to_le_bytes());
    bytes
}

/// `bytes` with the u32 at `at` set to `value`.
fn with_u32(bytes: &[u8], at: usize, value: u32) -> Vec<u8> {
    let mut bytes = bytes.to_vec();
    bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
    bytes
}

/// Offsets of vertex `i`'s sweep, t, θ, d and h in a bindings file.
fn record(i: usize) -> [usize; 5] {
    let at = RECORDS_AT + RECORD_BYTES * i;
    [at, at + 8, at + 16, at + 24, at + 32]
}

/// The largest |d| and |h| the bindings of the tube scene may have, as messages print it.
fn tube_bound(rig: &Rig) -> String {
    check::number(check::offset_bound(rig.rest(), &TUBE.mesh().positions))
}

#[test]
fn theta_out_of_range_is_refused_on_both_backends() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let good = scene.bind();
    let [_, _, theta, _, _] = record(3);
    for (value, shown) in [(1e300, "1e300"), (6.5, "6.5"), (-0.25, "-0.25"), (f64::NAN, "NaN")] {
        assert_eq!(
            scene.bindings_refused(&with_f64(&good, theta, value)),
            format!("error: bad.sffd: vertex 3: θ = {shown} is outside [0, 2π]\n")
        );
    }
}

#[test]
fn t_out_of_range_and_non_finite_offsets_are_refused() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let good = scene.bind();
    let [_, t, _, d, h] = record(7);
    assert_eq!(
        scene.bindings_refused(&with_f64(&good, t, 1.5)),
        "error: bad.sffd: vertex 7: t = 1.5 is outside [0, 1]\n"
    );
    assert_eq!(
        scene.bindings_refused(&with_f64(&good, d, f64::INFINITY)),
        "error: bad.sffd: vertex 7: d = inf is not finite\n"
    );
    assert_eq!(
        scene.bindings_refused(&with_f64(&good, h, f64::NAN)),
        "error: bad.sffd: vertex 7: h = NaN is not finite\n"
    );
}

#[test]
fn huge_offsets_are_refused_against_the_rig_on_both_backends() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let good = scene.bind();
    let bound = tube_bound(&tube_rig(&TUBE, 4, 8));
    // B = 2·(√6 + 0.5) for a 1 × 1 × 2 box and radius 0.5.
    assert!(bound.starts_with("5.89897948556"), "{bound}");
    let [_, _, _, d, h] = record(0);
    assert_eq!(
        scene.bindings_refused(&with_f64(&good, d, 1e308)),
        format!(
            "error: bad.sffd: vertex 0: d = 1e308 is out of range: |d| and |h| are at most {bound} for this mesh and rig\n"
        )
    );
    assert_eq!(
        scene.bindings_refused(&with_f64(&good, h, -6.0)),
        format!(
            "error: bad.sffd: vertex 0: h = -6 is out of range: |d| and |h| are at most {bound} for this mesh and rig\n"
        )
    );
}

#[test]
fn sweeps_out_of_range_are_refused() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let good = scene.bind();
    let [sweep, ..] = record(2);
    assert_eq!(
        scene.bindings_refused(&with_u32(&good, sweep, 1)),
        "error: bad.sffd: vertex 2: sweep 1 is out of range: the rig has 1 sweep\n"
    );
}

#[test]
fn edited_bindings_in_range_deform_alike_on_the_cpu_and_the_gpu() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let good = scene.bind();
    // Vertex 5 moved by hand: another angle, off the surface, off its plane.
    let [_, t, theta, d, h] = record(5);
    let edited = with_f64(&with_f64(&with_f64(&with_f64(&good, theta, TAU), d, 0.3), h, -0.2), t, 1.0);
    scene.write("edited.sffd", &edited);
    scene.succeed(&Scene::deform_args("edited.sffd", "cpu", "cpu.obj"));
    let cpu = Mesh::load(&scene.path("cpu.obj")).unwrap();
    assert!(cpu.positions.iter().all(|p| p.is_finite()));
    if common::gpu().is_none() {
        return;
    }
    scene.succeed(&Scene::deform_args("edited.sffd", "gpu", "gpu.obj"));
    let gpu = Mesh::load(&scene.path("gpu.obj")).unwrap();
    let (worst, at) = gpu
        .positions
        .iter()
        .zip(&cpu.positions)
        .map(|(g, c)| g.distance(*c))
        .enumerate()
        .fold((0.0, 0), |(w, at), (i, e)| if e > w { (e, i) } else { (w, at) });
    assert!(worst <= 1e-5 * cpu.diagonal(), "the GPU differs from the CPU by {worst:e} at vertex {at}");
}

/// The tube attached at its first ring, fading to rest: (scene, bindings bytes, first band
/// vertex, vertex count).
fn attached_scene() -> (Scene, Vec<u8>, u32) {
    let scene = Scene::tube(|t| attached_tube_rig(t, 4, 8, 0.8));
    let good = scene.bind();
    let n = TUBE.vertex_count();
    let count = u64::from_le_bytes(good[bands_at(n) - 8..bands_at(n)].try_into().unwrap());
    assert!(count >= 2, "the falloff puts vertices in a band");
    let first = u32::from_le_bytes(good[bands_at(n)..bands_at(n) + 4].try_into().unwrap());
    (scene, good, first)
}

#[test]
fn band_weights_outside_the_unit_interval_are_refused() {
    let (scene, good, first) = attached_scene();
    let weight = bands_at(TUBE.vertex_count()) + 8;
    for (value, shown) in [(2.0, "2"), (1.0, "1"), (-0.5, "-0.5"), (f64::NAN, "NaN")] {
        assert_eq!(
            scene.bindings_refused(&with_f64(&good, weight, value)),
            format!("error: bad.sffd: band vertex 0 (vertex {first}): weight {shown} is outside [0, 1)\n")
        );
    }
}

#[test]
fn band_vertices_out_of_range_unowned_or_out_of_order_are_refused() {
    let (scene, good, first) = attached_scene();
    let n = TUBE.vertex_count();
    let at = bands_at(n);
    assert_eq!(
        scene.bindings_refused(&with_u32(&good, at, 1_000_000)),
        format!(
            "error: bad.sffd: band vertex 0 (vertex 1000000): the vertex is out of range: the file has {n} vertices\n"
        )
    );
    // Vertex 0 is on the first ring, which the attached rig leaves at rest.
    assert_eq!(
        scene.bindings_refused(&with_u32(&good, at, 0)),
        "error: bad.sffd: band vertex 0 (vertex 0): the vertex is unowned, so it has no sweep to fade from\n"
    );
    // The second record names the first's vertex again.
    assert_eq!(
        scene.bindings_refused(&with_u32(&good, at + 48, first)),
        format!(
            "error: bad.sffd: band vertex 1 (vertex {first}): listed after vertex {first}; band vertices must be \
             listed by strictly increasing vertex\n"
        )
    );
    // A second sweep past the one-sweep rig.
    assert_eq!(
        scene.bindings_refused(&with_u32(&good, at + 4, 3)),
        format!(
            "error: bad.sffd: band vertex 0 (vertex {first}): second sweep 3 is out of range: the rig has 1 sweep\n"
        )
    );
    // Fading into its own sweep.
    assert_eq!(
        scene.bindings_refused(&with_u32(&good, at + 4, 0)),
        format!("error: bad.sffd: band vertex 0 (vertex {first}): its second sweep 0 is its own sweep\n")
    );
}

#[test]
fn second_bindings_out_of_range_are_refused() {
    let scene = Scene::tube(|t| split_tube_rig(t, 4, 8, 0.4));
    let good = scene.bind();
    let n = TUBE.vertex_count();
    let at = bands_at(n);
    let first = u32::from_le_bytes(good[at..at + 4].try_into().unwrap());
    let second = u32::from_le_bytes(good[at + 4..at + 8].try_into().unwrap());
    assert_ne!(second, u32::MAX, "the split rig's bands fade into the other sweep");
    assert_eq!(
        scene.bindings_refused(&with_f64(&good, at + 24, 1e300)),
        format!("error: bad.sffd: band vertex 0 (vertex {first}): second binding: θ = 1e300 is outside [0, 2π]\n")
    );
    let bound = tube_bound(&split_tube_rig(&TUBE, 4, 8, 0.4));
    assert_eq!(
        scene.bindings_refused(&with_f64(&good, at + 32, -1e308)),
        format!(
            "error: bad.sffd: band vertex 0 (vertex {first}): second binding: d = -1e308 is out of range: |d| and \
             |h| are at most {bound} for this mesh and rig\n"
        )
    );
}

/// `view` without any display, so that reaching for a window would fail differently.
fn view_fails(scene: &Scene, args: &[&str]) -> String {
    let before = scene.entries();
    let started = Instant::now();
    let output = common::sweepffd(scene.dir.path())
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .args([&["view", "--mesh", "tube.obj"][..], args].concat())
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(started.elapsed() < Duration::from_secs(20), "took {:?}", started.elapsed());
    assert_eq!(scene.entries(), before);
    stderr
}

#[test]
fn subdivision_past_the_limits_is_refused_before_any_window() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    // 50 vertices and 96 triangles: level k has 96·4^k triangles, and level 10 is the first
    // past 2²⁶.
    assert_eq!(
        view_fails(&scene, &["--subdivide", "30"]),
        "error: tube.obj: subdividing: midpoint subdivision level 10 (of 30) would make 50331650 vertices and \
         100663296 faces, over the limits of 33554432 vertices and 67108864 faces\n"
    );
    assert_eq!(
        view_fails(&scene, &["--subdivide-to", "1000000000000"]),
        "error: tube.obj: subdividing: a target of 1000000000000 vertices is over the limit of 33554432 vertices\n"
    );
}

#[test]
fn fit_sizes_past_the_limits_are_refused() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let fit = |extra: &[&str]| {
        scene.fail(&[&["fit", "--mesh", "tube.obj", "--group", "wall", "--out", "fit.json"][..], extra].concat())
    };
    assert_eq!(
        fit(&["--radii", "10000000"]),
        "error: tube.obj: fitting sweep \"wall\": --radii 10000000 is over the limit of 4096 radii per key; \
         nothing was written\n"
    );
    assert_eq!(
        fit(&["--keys", "5000", "--max-keys", "5000"]),
        "error: tube.obj: fitting sweep \"wall\": --keys 5000 is over the limit of 1024 keys per sweep; \
         nothing was written\n"
    );
    assert_eq!(
        fit(&["--max-keys", "2000"]),
        "error: tube.obj: fitting sweep \"wall\": --max-keys 2000 is over the limit of 1024 keys per sweep; \
         nothing was written\n"
    );
}

#[test]
fn bench_sizes_and_run_counts_it_cannot_honour_are_refused() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let bench = |extra: &[&str]| scene.fail(&[&["bench", "--backend", "cpu"][..], extra].concat());
    let small = "is below the smallest synthetic tube, 770 vertices (3 rings of 256 and 2 cap centers)";
    assert_eq!(bench(&["--vertices", "0"]), format!("error: --vertices 0 {small}\n"));
    assert_eq!(bench(&["--vertices", "769"]), format!("error: --vertices 769 {small}\n"));
    assert_eq!(
        bench(&["--vertices", "2000000000"]),
        "error: --vertices 2000000000 is over the limit of 1073741824 vertices on this backend\n"
    );
    assert_eq!(bench(&["--runs", "0"]), "error: --runs must be at least 1, found 0\n");
    assert_eq!(bench(&["--runs", "10001"]), "error: --runs 10001 is over the limit of 10000 runs\n");
}

#[test]
fn bench_reports_the_size_of_the_tube_it_measures() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let output = scene.run(&["bench", "--backend", "cpu", "--vertices", "1000", "--runs", "1", "--json"]);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(output.status.success(), "{stderr}");
    assert_eq!(
        stderr,
        "note: measuring 770 vertices, the largest synthetic tube with at most --vertices 1000 (tubes have 256·k + 2 \
         vertices)\n"
    );
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["n"], 770);
    assert_eq!(report["runs"], 1);
    // An exact size says nothing more.
    let output = scene.run(&["bench", "--backend", "cpu", "--vertices", "1026", "--runs", "1", "--json"]);
    assert!(output.status.success());
    assert_eq!(String::from_utf8(output.stderr).unwrap(), "");
}

#[test]
fn argument_errors_exit_with_2_and_other_errors_with_1() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    let stderr = scene.fail_with(2, &["deform", "--bogus"]);
    assert!(stderr.starts_with("error: unexpected argument '--bogus' found"), "{stderr}");
    let stderr = scene.fail_with(2, &["bench", "--runs", "many"]);
    assert!(stderr.starts_with("error: invalid value 'many' for '--runs <RUNS>'"), "{stderr}");
    let stderr =
        scene.fail(&["deform", "--mesh", "missing.obj", "--rig", "rig.json", "--pose", "pose.json", "--out", "o.obj"]);
    assert!(stderr.starts_with("error: cannot read missing.obj: "), "{stderr}");
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_at_out_is_written_through() {
    let scene = Scene::tube(|t| tube_rig(t, 4, 8));
    fs::create_dir(scene.path("assets")).unwrap();
    scene.write("assets/deformed.obj", "old");
    std::os::unix::fs::symlink("assets/deformed.obj", scene.path("out.obj")).unwrap();
    let args = ["--quiet", "deform", "--mesh", "tube.obj", "--rig", "rig.json", "--pose", "pose.json"];
    scene.succeed(&[&args[..], &["--out", "out.obj", "--backend", "cpu"]].concat());
    assert!(fs::symlink_metadata(scene.path("out.obj")).unwrap().file_type().is_symlink());
    assert_eq!(fs::read_link(scene.path("out.obj")).unwrap(), Path::new("assets/deformed.obj"));
    let written = Mesh::load(&scene.path("assets/deformed.obj")).unwrap();
    assert_eq!(written.positions.len(), TUBE.vertex_count());
    assert_eq!(scene.entries(), ["assets", "out.obj", "pose.json", "rig.json", "tube.obj"]);
    assert_eq!(entries(&scene.path("assets")), ["deformed.obj"]);
}

/// A scene whose `deform` writes a large OBJ quickly: a tube of about `vertices` vertices and
/// saved bindings (every vertex at the same in-range parameters, so no binding is computed),
/// with `out.obj` holding the bytes `old`.
fn large_scene(vertices: usize) -> Scene {
    let scene = Scene { dir: tempfile::tempdir().unwrap() };
    let tube = Tube::with_vertex_count(vertices, 4.0, 0.5);
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&scene.path("tube.obj"), &mesh.mesh.positions).unwrap();
    let json = tube_rig(&tube, 4, 8).to_document().to_json();
    scene.write("rig.json", &json);
    scene.write("pose.json", &json);
    // Fingerprints of what the command line reads back.
    let (mesh, rig) = (Mesh::load(&scene.path("tube.obj")).unwrap(), Rig::load(&scene.path("rig.json")).unwrap());
    let params = VertexBinding { t: 0.5, theta: 1.0, d: 0.0, h: 0.0 };
    let bindings = MeshBindings::hard(vec![Binding { sweep: 0, params }; mesh.positions.len()]);
    BindingsFile::new(&rig, &mesh.positions, bindings).save(&scene.path("b.sffd")).unwrap();
    scene.write("out.obj", "old");
    scene
}

/// Starts `deform` of the large scene, sends `signal` once its temporary output file appears,
/// and returns its exit status code.
fn interrupted_deform(scene: &Scene, signal: &str) -> Option<i32> {
    let args = Scene::deform_args("b.sffd", "cpu", "out.obj");
    let mut child =
        common::sweepffd(scene.dir.path()).args(&args).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap();
    let prefix = ".out.obj.";
    let started = Instant::now();
    loop {
        if entries(scene.dir.path()).iter().any(|n| n.starts_with(prefix) && n.ends_with(".tmp")) {
            break;
        }
        if let Some(status) = child.try_wait().unwrap() {
            panic!("deform ended ({status}) before its temporary file was seen");
        }
        assert!(started.elapsed() < Duration::from_secs(120), "no temporary file appeared");
        std::thread::sleep(Duration::from_millis(1));
    }
    let killed = Command::new("kill").args([signal, &child.id().to_string()]).status().unwrap();
    assert!(killed.success());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    output.status.code()
}

#[test]
fn sigterm_and_sigint_during_a_write_leave_no_temporary_and_the_old_target() {
    let scene = large_scene(400_000);
    let before = scene.entries();
    for (signal, code) in [("-TERM", 143), ("-INT", 130)] {
        assert_eq!(interrupted_deform(&scene, signal), Some(code), "{signal}");
        assert_eq!(scene.entries(), before, "{signal} left a file behind");
        assert_eq!(scene.read("out.obj"), b"old", "{signal} changed the target");
    }
}
