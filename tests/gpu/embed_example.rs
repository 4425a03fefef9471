//! The engine users' example (`examples/embed.rs`) runs: five instances posed in the app's own
//! frame loop, drawn by the app's render pass, each checked against the f64 path by the example
//! itself.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common;

/// The example's binary, which `cargo test` builds beside the test binaries.
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let profile = exe.parent().and_then(Path::parent).expect("target/PROFILE/deps/test");
    profile.join("examples").join(format!("{name}{}", std::env::consts::EXE_SUFFIX))
}

#[test]
fn embed_example() {
    // The engine users' example: five instances posed in the app's own frame loop, drawn by the
    // app's render pass, each checked against the f64 path by the example itself.
    if common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(example("embed")).arg(dir.path()).env("XDG_RUNTIME_DIR", dir.path()).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "embed: {stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("5 instances x 1536 vertices: worst |GPU - f64|"), "{stdout}");
    assert_eq!(stdout.matches("bounds [").count(), 5, "{stdout}");
    let picture = image::open(dir.path().join("embed.png")).unwrap().to_rgba8();
    // The instances are drawn: clay pixels in each fifth of the picture's width.
    let width = picture.width();
    for i in 0..5 {
        let clay = picture.enumerate_pixels().filter(|(x, _, p)| *x * 5 / width == i && p[0] > p[2] + 40).count();
        assert!(clay > 500, "instance {i} is not in its fifth of the picture ({clay} clay pixels)");
    }
}
