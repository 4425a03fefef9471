//! Saving a mesh and poses of it as a glTF animation (one morph target per pose) that game
//! engines, web viewers and Blender play: see `gltf::morph`.

use std::io;
use std::path::Path;

use super::error::MeshError;
use super::format::Format;
use super::gltf::morph::{MorphPose, write_morph_animation};
use super::gltf::texcoords::vertex_texcoords;
use super::loaded::{LoadedMesh, Source};
use super::obj::texcoords::corner_texcoords;
use crate::atomic_file::write_atomically;

/// Writes `mesh` at rest with one morph target per pose of `poses`, played in order
/// `seconds_per_pose` apart by one animation, to `path` (`.glb` binary, `.gltf` with its buffer
/// embedded), atomically. An OBJ file whose face corners all have texture coordinates (`v/vt`),
/// or a glTF file whose primitives all have TEXCOORD_0, gives them to the animation's vertices. [`MeshError::Write`] naming `path` for another
/// extension, a pose with another vertex count, a non-finite position, no faces, no poses or a
/// `seconds_per_pose` that is not positive and finite, or a file that cannot be written.
pub fn save_morph_animation(
    path: &Path,
    mesh: &LoadedMesh,
    poses: &[MorphPose],
    seconds_per_pose: f64,
) -> Result<(), MeshError> {
    let binary = match Format::of(path) {
        Ok(Format::Glb) => true,
        Ok(Format::Gltf) => false,
        _ => {
            let why = io::Error::new(io::ErrorKind::InvalidInput, "an animation is written as .glb or .gltf");
            return Err(MeshError::write(path, why));
        }
    };
    let texcoords = match &mesh.source {
        Source::Obj(file) if file.describes(&mesh.mesh) => corner_texcoords(&file.bytes, &mesh.mesh.faces),
        Source::Gltf(file) if file.describes(&mesh.mesh) => vertex_texcoords(&file.file, &mesh.mesh.faces),
        _ => None,
    };
    write_atomically(path, |out| {
        write_morph_animation(out, &mesh.mesh, texcoords.as_ref(), poses, seconds_per_pose, binary)
    })
    .map_err(|e| MeshError::write(path, e))
}
