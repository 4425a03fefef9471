//! [`Mesh::load`]: reading a mesh file of either format.

use std::path::Path;

use super::format::Format;
use super::{Mesh, MeshError, gltf, obj, off, ply};

impl Mesh {
    /// Reads an OBJ, PLY, OFF or glTF file, chosen by extension (`.obj`, `.ply`, `.off`,
    /// `.gltf`, `.glb`, case-insensitive).
    ///
    /// Vertices keep the file's order, unused vertices included; faces keep theirs. The mesh
    /// remembers the file so that [`Mesh::save`] can write it back faithfully. A file with
    /// vertices but no face (a point cloud) is allowed; one without vertices is
    /// [`MeshError::Empty`]. Malformed input of any kind is an error naming the file (and the
    /// line, for OBJ and OFF), never a panic. glTF files give world-space positions (node
    /// transforms of the default scene applied) and one group per mesh (see `gltf`).
    pub fn load(path: &Path) -> Result<Mesh, MeshError> {
        Format::of(path)?; // an unknown extension is refused before the file is read
        let bytes = crate::limits::read_input(path).map_err(|e| MeshError::read(path, e))?;
        Mesh::parse(path, bytes)
    }

    /// Reads a mesh from the bytes of the file `path`, the format chosen by its extension as
    /// in [`Mesh::load`]; errors name `path`. A `.gltf` file's external buffers are resolved
    /// in the folder of `path`.
    pub fn parse(path: &Path, bytes: Vec<u8>) -> Result<Mesh, MeshError> {
        match Format::of(path)? {
            Format::Obj => obj::read(path, bytes),
            Format::Ply => ply::read::read(path, bytes),
            Format::Off => off::read::read(path, bytes),
            Format::Gltf | Format::Glb => gltf::read::read(path, &bytes),
        }
    }
}
