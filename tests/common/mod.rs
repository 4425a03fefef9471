//! Shared helpers for the integration tests: locating the test meshes in `../shared/meshes`.

#![allow(dead_code, reason = "each test binary uses a different subset of the helpers")]

use std::path::PathBuf;

/// The folder of shared test meshes, `../shared/meshes` relative to the crate root.
pub fn shared_meshes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/meshes")
}

/// The path of a shared test mesh, or `None` (with a notice on stderr) when `../shared` is
/// missing. Under `CI=true` a missing mesh fails the test instead of skipping it.
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    let path = shared_meshes_dir().join(name);
    if path.is_file() {
        return Some(path);
    }
    if std::env::var("CI").is_ok_and(|v| v == "true" || v == "1") {
        panic!("CI=true but the shared test mesh {} is missing", path.display());
    }
    eprintln!("skipping: shared test mesh {} not found (the ../shared folder is not beside this clone)", path.display());
    None
}
