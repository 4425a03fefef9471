//! The examples run (release build, output into a temporary folder) and every file they write
//! parses: meshes load, rigs and poses load, pictures decode.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use sweepffd::mesh::Mesh;
use sweepffd::rig::RigDocument;

/// The example's binary, which `cargo test` builds beside the test binaries.
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let profile = exe.parent().and_then(Path::parent).expect("target/PROFILE/deps/test");
    profile.join("examples").join(format!("{name}{}", std::env::consts::EXE_SUFFIX))
}

/// Runs example `name` into a fresh folder and checks that it wrote `expected` and that every
/// file it wrote parses.
fn run(name: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(example(name)).arg(dir.path()).env("XDG_RUNTIME_DIR", dir.path()).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{name}: {stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    if stdout.contains("nothing to do") {
        eprintln!("skipping: {name} needs ../shared: {stdout}");
        return;
    }
    let pictures = common::gpu().is_some();
    for file in expected {
        if file.ends_with(".png") && !pictures {
            continue;
        }
        assert!(dir.path().join(file).is_file(), "{name} did not write {file}:\n{stdout}");
    }
    for entry in std::fs::read_dir(dir.path()).unwrap() {
        let path = entry.unwrap().path();
        match path.extension().and_then(|e| e.to_str()) {
            Some("obj") => {
                Mesh::load(&path).unwrap();
            }
            Some("json") => {
                RigDocument::load(&path).unwrap();
            }
            Some("png") => {
                let picture = image::open(&path).unwrap();
                assert!(picture.width() > 0 && picture.height() > 0);
            }
            other => panic!("{name} wrote an unexpected file {} ({other:?})", path.display()),
        }
    }
}

#[test]
fn teapot_example() {
    run(
        "teapot",
        &[
            "teapot-rig.json",
            "rest.png",
            "body-edit.obj",
            "body-edit-no-hierarchy.png",
            "squeeze-total-pose.json",
            "local-radius-edit.obj",
        ],
    );
}

#[test]
fn bunny_example() {
    run("bunny", &["ears-rig.json", "ears-fitted.png", "ears-bent.obj", "drag-translate.obj", "drag-rotate.obj"]);
}

#[test]
fn armadillo_leg_example() {
    run("armadillo_leg", &["step0.png", "step2.png", "leg-rig.json"]);
}

#[test]
fn chair_example() {
    run("chair", &["chair-rig.json", "chair-moved.obj", "chair-pose.json", "chair.png"]);
}
