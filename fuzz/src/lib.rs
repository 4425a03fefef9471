//! What each fuzz target does with its input, as plain functions: an `Err` is an accepted
//! outcome (its text is what the command line would print after `error: `), a panic or an abort
//! is a finding.
//!
//! The fuzz targets in `fuzz_targets/` call these; the command line's test
//! `cli/tests/hostile/fuzz_regressions.rs` includes this file as a module and replays the
//! committed regression corpus through [`run`], on stable Rust, without depending on this crate.

pub mod bindings;
pub mod edits;
pub mod mesh;
pub mod rig;
pub mod round_trip;
pub mod scene;
#[cfg(feature = "viewer")]
pub mod script;

pub use bindings::bindings;
pub use edits::edits;
pub use mesh::{gltf, obj, off, ply};
pub use rig::{pose, rig};
pub use round_trip::write_round_trip;
#[cfg(feature = "viewer")]
pub use script::script;

/// The outcome of one input: `Err` holds the error's text.
pub type Outcome = Result<(), String>;

/// The fuzz targets by name, in the order of `fuzz/Cargo.toml`.
pub const TARGETS: &[&str] =
    &["obj", "ply", "off", "gltf", "write_round_trip", "rig", "pose", "edits", "bindings", "script"];

/// Runs the target named `target` on `data`; `None` for an unknown target (or `script`
/// without the feature `viewer`).
pub fn run(target: &str, data: &[u8]) -> Option<Outcome> {
    Some(match target {
        "obj" => obj(data),
        "ply" => ply(data),
        "off" => off(data),
        "gltf" => gltf(data),
        "write_round_trip" => write_round_trip(data),
        "rig" => rig(data),
        "pose" => pose(data),
        "edits" => edits(data),
        "bindings" => bindings(data),
        #[cfg(feature = "viewer")]
        "script" => script(data),
        _ => return None,
    })
}

/// `text` with every occurrence of the temporary folder `dir` replaced by `<tmp>`, so that an
/// error naming a file written there reads the same on every run.
pub fn without_dir(text: &str, dir: &std::path::Path) -> String {
    text.replace(&dir.display().to_string(), "<tmp>")
}
