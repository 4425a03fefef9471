//! Targets `obj`, `ply`, `off` and `gltf`: [`Mesh::parse`] of the input bytes.
//!
//! The file name lies in a folder that does not exist, so that a `.gltf` buffer given by a
//! relative uri reads nothing; an absolute uri still reaches the file system.

use std::path::{Path, PathBuf};

use sweepffd::formats::LoadedMesh;

use super::Outcome;

/// The folder the parsed files pretend to lie in; it does not exist.
pub const MISSING_FOLDER: &str = "/nonexistent/sweepffd-fuzz";

/// The path of a mesh file named `name` in [`MISSING_FOLDER`].
pub fn mesh_path(name: &str) -> PathBuf {
    Path::new(MISSING_FOLDER).join(name)
}

/// Parses `data` as the mesh file `name` (format by its extension).
pub fn parse(name: &str, data: &[u8]) -> Result<LoadedMesh, String> {
    LoadedMesh::parse(&mesh_path(name), data.to_vec()).map_err(|e| e.to_string())
}

/// An OBJ file.
pub fn obj(data: &[u8]) -> Outcome {
    parse("mesh.obj", data).map(drop)
}

/// A PLY file (ASCII or binary).
pub fn ply(data: &[u8]) -> Outcome {
    parse("mesh.ply", data).map(drop)
}

/// An OFF file.
pub fn off(data: &[u8]) -> Outcome {
    parse("mesh.off", data).map(drop)
}

/// A glTF file: a binary `.glb` when the input starts with the GLB magic `glTF`, else `.gltf`
/// JSON.
pub fn gltf(data: &[u8]) -> Outcome {
    let name = if data.starts_with(b"glTF") { "mesh.glb" } else { "mesh.gltf" };
    parse(name, data).map(drop)
}
