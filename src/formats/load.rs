//! [`LoadedMesh::load`] and [`Mesh::load`]: reading a mesh file of any of the formats.

use std::path::Path;
use std::sync::Arc;

use super::format::Format;
use super::loaded::Source;
use super::{LoadedMesh, MeshError, gltf, obj, off, ply};
use crate::mesh::Mesh;

impl LoadedMesh {
    /// Reads an OBJ, PLY, OFF or glTF file, chosen by extension (`.obj`, `.ply`, `.off`,
    /// `.gltf`, `.glb`, case-insensitive).
    ///
    /// Vertices keep the file's order, unused vertices included; faces keep theirs. The file is
    /// kept beside the mesh so that [`LoadedMesh::save`] can write it back faithfully. A file with
    /// vertices but no face (a point cloud) is allowed; one without vertices is
    /// [`MeshError::Empty`]. Malformed input of any kind is an error naming the file (and the
    /// line, for OBJ and OFF), never a panic. glTF files give world-space positions (node
    /// transforms of the default scene applied) and one group per mesh (see `gltf`).
    pub fn load(path: &Path) -> Result<LoadedMesh, MeshError> {
        Format::of(path)?; // an unknown extension is refused before the file is read
        let bytes = crate::limits::read_input(path).map_err(|e| MeshError::read(path, e))?;
        LoadedMesh::parse(path, bytes)
    }

    /// Reads a mesh from the bytes of the file `path`, the format chosen by its extension as
    /// in [`LoadedMesh::load`]; errors name `path`. A `.gltf` file's external buffers are
    /// resolved in the folder of `path`.
    pub fn parse(path: &Path, bytes: Vec<u8>) -> Result<LoadedMesh, MeshError> {
        match Format::of(path)? {
            Format::Obj => {
                let (mesh, file) = obj::read(path, bytes)?;
                Ok(LoadedMesh { mesh, source: Source::Obj(Arc::new(file)) })
            }
            Format::Ply => ply::read::read(path, bytes),
            Format::Off => off::read::read(path, bytes),
            Format::Gltf | Format::Glb => gltf::read::read(path, &bytes),
        }
    }
}

impl Mesh {
    /// Reads the mesh data of an OBJ, PLY, OFF or glTF file, as [`LoadedMesh::load`] does, for
    /// callers that do not write the file back (the file is not kept).
    pub fn load(path: &Path) -> Result<Mesh, MeshError> {
        LoadedMesh::load(path).map(LoadedMesh::into_mesh)
    }

    /// Reads the mesh data from the bytes of the file `path`, as [`LoadedMesh::parse`] does.
    pub fn parse(path: &Path, bytes: Vec<u8>) -> Result<Mesh, MeshError> {
        LoadedMesh::parse(path, bytes).map(LoadedMesh::into_mesh)
    }
}
