//! The cubic rotation interpolation through the command line: `fit --rotation-interpolation
//! cubic` writes it on the sweep, a rig file's top-level field sets it for every sweep, `deform`
//! follows it on the reference and the CPU backends alike, and an unknown value is an error
//! naming the rig file.

use crate::common;

use std::fs;
use std::path::Path;

use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::RotationInterpolation;

fn run(dir: &Path, args: &[&str]) -> std::process::Output {
    common::sweepffd(dir).args(args).output().unwrap()
}

fn succeed(dir: &Path, args: &[&str]) {
    let out = run(dir, args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
}

fn deform(dir: &Path, rig: &str, backend: &str, out: &str) -> Mesh {
    let pose = "sweepffd-demo/pose.json";
    succeed(
        dir,
        &[
            "-q",
            "deform",
            "--mesh",
            "sweepffd-demo/rest.obj",
            "--rig",
            rig,
            "--pose",
            pose,
            "--out",
            out,
            "--backend",
            backend,
        ],
    );
    Mesh::load(&dir.join(out)).unwrap()
}

fn largest_distance(a: &Mesh, b: &Mesh) -> f64 {
    a.positions.iter().zip(&b.positions).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max)
}

#[test]
fn a_cubic_rig_deforms_alike_on_every_cpu_backend_and_unlike_the_linear_one() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    succeed(dir, &["-q", "demo"]);
    let rig = fs::read_to_string(dir.join("sweepffd-demo/rig.json")).unwrap();
    let cubic = rig.replacen("\"version\": 1,", "\"version\": 1,\n  \"rotation_interpolation\": \"cubic\",", 1);
    assert_ne!(cubic, rig);
    fs::write(dir.join("cubic.json"), &cubic).unwrap();
    let loaded = Rig::load(&dir.join("cubic.json")).unwrap();
    assert!(loaded.rest().iter().all(|s| s.rotation_interpolation() == RotationInterpolation::Cubic));

    let linear = deform(dir, "sweepffd-demo/rig.json", "reference", "linear.obj");
    let reference = deform(dir, "cubic.json", "reference", "cubic-reference.obj");
    let cpu = deform(dir, "cubic.json", "cpu", "cubic-cpu.obj");
    let diagonal = linear.diagonal();
    let (apart, agree) = (largest_distance(&reference, &linear), largest_distance(&cpu, &reference));
    println!("cubic vs linear: {:.2e} × diagonal apart; cpu vs reference {:.2e}", apart / diagonal, agree / diagonal);
    assert!(apart > 1e-4 * diagonal, "the cubic rig deforms as the linear one: {apart:e}");
    assert!(agree <= 1e-5 * diagonal, "the cpu backend is off the reference by {agree:e}");

    let bad = rig.replacen("\"version\": 1,", "\"version\": 1,\n  \"rotation_interpolation\": \"spline\",", 1);
    fs::write(dir.join("bad.json"), bad).unwrap();
    let out = run(
        dir,
        &[
            "deform",
            "--mesh",
            "sweepffd-demo/rest.obj",
            "--rig",
            "bad.json",
            "--pose",
            "sweepffd-demo/pose.json",
            "--out",
            "bad.obj",
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("bad.json") && stderr.contains("spline"), "{stderr}");
    assert!(!dir.join("bad.obj").exists(), "an output was written");
}

#[test]
fn fit_writes_the_rotation_interpolation_it_is_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    succeed(dir, &["-q", "demo"]);
    let fit = ["-q", "fit", "--mesh", "sweepffd-demo/rest.obj", "--group", "wall", "--out"];
    succeed(dir, &[&fit[..], &["cubic.json", "--rotation-interpolation", "cubic"]].concat());
    succeed(dir, &[&fit[..], &["linear.json"]].concat());
    let interpolation = |file: &str| Rig::load(&dir.join(file)).unwrap().rest()[0].rotation_interpolation();
    assert_eq!(interpolation("cubic.json"), RotationInterpolation::Cubic);
    assert_eq!(interpolation("linear.json"), RotationInterpolation::Linear);
    assert!(fs::read_to_string(dir.join("cubic.json")).unwrap().contains("\"rotation_interpolation\": \"cubic\""));
    assert!(!fs::read_to_string(dir.join("linear.json")).unwrap().contains("rotation_interpolation"));
}
