//! Replays the fuzz regression corpus on stable Rust: every `fuzz/regressions/<target>/<case>`
//! goes through the same code as the fuzz target `<target>` (the fuzz crate's `src/lib.rs`,
//! included here as a module), and its outcome — `ok`, or the error's text — must equal the
//! sidecar `<case>.expected` exactly. A panic, even one caught inside sweepffd (a fuzz target
//! aborts on those), fails the case. `SWEEPFFD_BLESS=1` rewrites the `.expected` files (and
//! the seeds derived from the fuzz scene) instead of comparing.

#[path = "../../../fuzz/src/lib.rs"]
mod harness;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Set to `1` to rewrite the expected outcomes from the current behaviour.
const BLESS: &str = "SWEEPFFD_BLESS";

fn blessing() -> bool {
    std::env::var(BLESS).is_ok_and(|v| v == "1" || v == "true")
}

fn fuzz_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// The messages of every panic since the hook was installed, caught or not, on any thread.
static PANICS: Mutex<Vec<String>> = Mutex::new(Vec::new());

fn record_panics() {
    std::panic::set_hook(Box::new(|info| {
        let message = info.payload_as_str().unwrap_or("(no message)");
        let at = info.location().map(|l| format!(" at {}:{}", l.file(), l.line())).unwrap_or_default();
        PANICS.lock().unwrap_or_else(|e| e.into_inner()).push(format!("{message}{at}"));
    }));
}

fn take_panics() -> Vec<String> {
    std::mem::take(&mut *PANICS.lock().unwrap_or_else(|e| e.into_inner()))
}

/// The cases of the corpus: (target, input file), sorted.
fn cases() -> Vec<(String, PathBuf)> {
    let mut cases = Vec::new();
    for target in std::fs::read_dir(fuzz_dir().join("regressions")).expect("fuzz/regressions") {
        let target = target.expect("a corpus folder").path();
        let name = target.file_name().expect("a folder name").to_string_lossy().into_owned();
        for file in std::fs::read_dir(&target).expect("a target's corpus") {
            let file = file.expect("a corpus file").path();
            if file.extension().is_none_or(|e| e != "expected") {
                cases.push((name.clone(), file));
            }
        }
    }
    cases.sort();
    cases
}

/// The outcome of one case as the `.expected` files spell it, or why the case failed.
fn replay(target: &str, file: &Path) -> Result<Option<String>, String> {
    let data = std::fs::read(file).map_err(|e| format!("cannot read: {e}"))?;
    take_panics();
    let outcome = catch_unwind(AssertUnwindSafe(|| harness::run(target, &data)));
    let panics = take_panics();
    match outcome {
        Ok(_) if !panics.is_empty() => Err(format!("panicked inside, then recovered: {}", panics.join("; "))),
        Ok(None) => Ok(None),
        Ok(Some(Ok(()))) => Ok(Some("ok".to_string())),
        Ok(Some(Err(error))) => Ok(Some(error)),
        Err(_) => Err(format!("panicked: {}", panics.join("; "))),
    }
}

#[test]
fn regressions_replay_with_their_expected_outcomes() {
    record_panics();
    let mut failures = Vec::new();
    let cases = cases();
    assert!(!cases.is_empty(), "the regression corpus is empty");
    for (target, file) in &cases {
        let case = file.strip_prefix(fuzz_dir()).unwrap_or(file).display().to_string();
        let expected_file = file.with_extension("expected");
        let outcome = match replay(target, file) {
            Ok(Some(outcome)) => outcome,
            Ok(None) if target == "script" && !cfg!(feature = "viewer") => {
                eprintln!("skipping {case}: the script target needs the feature `viewer`");
                continue;
            }
            Ok(None) => {
                failures.push(format!("{case}: no fuzz target is named {target:?}"));
                continue;
            }
            Err(why) => {
                failures.push(format!("{case}: {why}"));
                continue;
            }
        };
        if blessing() {
            std::fs::write(&expected_file, format!("{outcome}\n")).expect("the expected outcome is written");
            continue;
        }
        match std::fs::read_to_string(&expected_file) {
            Ok(expected) if expected.strip_suffix('\n').unwrap_or(&expected) == outcome => {}
            Ok(expected) => failures.push(format!("{case}: expected «{}», got «{outcome}»", expected.trim_end())),
            Err(e) => failures.push(format!("{case}: no {}: {e} (got «{outcome}»)", expected_file.display())),
        }
    }
    let _ = std::panic::take_hook();
    assert!(
        failures.is_empty(),
        "{} of {} regression cases failed (set {BLESS}=1 to rewrite the expected outcomes):\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

#[test]
fn every_regression_folder_names_a_fuzz_target() {
    for target in harness::TARGETS {
        assert!(fuzz_dir().join("fuzz_targets").join(format!("{target}.rs")).is_file(), "{target}");
    }
    for (target, file) in cases() {
        assert!(harness::TARGETS.contains(&target.as_str()), "{}: no fuzz target {target:?}", file.display());
    }
}

/// The seeds of the rig-level targets made from the fuzz scene (a bindings file that does not
/// match the scene would stop the `bindings` target at the fingerprint check): each committed
/// seed must equal what the scene makes now.
#[test]
fn scene_seeds_match_the_fuzz_scene() {
    let scene = harness::scene::scene();
    let keys = sweepffd::synthetic::BendTwistTaper { bend: 0.6, twist: 0.3, taper: 0.8 }.keys(&scene.rig);
    let seeds = [
        ("corpus/rig/family.json", scene.rig.to_document().to_json().into_bytes()),
        ("corpus/pose/bend.json", scene.rig.pose_document(&keys).to_json().into_bytes()),
        ("corpus/bindings/tube.bin", scene.bindings_file()),
    ];
    for (name, bytes) in seeds {
        let path = fuzz_dir().join(name);
        if blessing() {
            std::fs::write(&path, &bytes).expect("the seed is written");
        } else {
            let committed = std::fs::read(&path).unwrap_or_default();
            assert!(committed == bytes, "{name} differs from the fuzz scene's (set {BLESS}=1 to rewrite it)");
        }
    }
}
