//! Target `bindings`: a bindings file read, checked against the scene's rig and tube, and the
//! tube deformed with it on the CPU, as `sweepffd deform --bindings --backend cpu` does.

use std::path::Path;

use sweepffd::bindings_file::BindingsFile;
use sweepffd::deform::deform_vertices;

use super::Outcome;
use super::rig::{POSE_FILE, check_deformed};
use super::scene::scene;

/// The name the bindings input goes by in errors.
pub const BINDINGS_FILE: &str = "bindings.bin";

/// Reads, checks and uses the bindings file `data`.
pub fn bindings(data: &[u8]) -> Outcome {
    let scene = scene();
    let path = Path::new(BINDINGS_FILE);
    let file = BindingsFile::from_bytes(data, path).map_err(|e| e.to_string())?;
    file.check_matches(&scene.rig, &scene.mesh.positions, path).map_err(|e| e.to_string())?;
    let mut deformed = vec![glam::DVec3::ZERO; scene.mesh.positions.len()];
    deform_vertices(scene.rig.rest(), &scene.posed, &file.bindings, &scene.mesh.positions, &mut deformed);
    check_deformed(&deformed, &file.bindings, &scene.rig, POSE_FILE)
}
