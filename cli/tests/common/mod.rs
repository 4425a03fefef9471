//! Shared helpers for the command line's integration tests: the engine's test helpers
//! (`tests/common` at the workspace root) and the `sweepffd` binary.

#![allow(dead_code, reason = "each test binary uses a different subset of the helpers")]

#[path = "../../../tests/common/mod.rs"]
mod engine;

#[allow(unused_imports, reason = "each test binary uses a different subset of the helpers")]
pub use engine::*;

/// The `sweepffd` binary, run in `dir` with `XDG_RUNTIME_DIR` pointing at `dir` (a private
/// temporary folder): on a machine with no desktop session Mesa's Vulkan drivers otherwise
/// print warnings about it on stderr, which the tests compare.
pub fn sweepffd(dir: &std::path::Path) -> std::process::Command {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_sweepffd"));
    command.current_dir(dir).env("XDG_RUNTIME_DIR", dir);
    command
}
