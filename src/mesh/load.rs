//! [`Mesh::load`]: reading a mesh file of either format.

use std::path::Path;

use super::format::Format;
use super::{Mesh, MeshError, obj, ply};

impl Mesh {
    /// Reads an OBJ or PLY file, chosen by extension (`.obj` / `.ply`, case-insensitive).
    ///
    /// Vertices keep the file's order, unused vertices included; faces keep theirs. The mesh
    /// remembers the file so that [`Mesh::save`] can write it back faithfully. A file with
    /// vertices but no face (a point cloud) is allowed; one without vertices is
    /// [`MeshError::Empty`]. Malformed input of any kind is an error naming the file (and the
    /// line, for OBJ), never a panic.
    pub fn load(path: &Path) -> Result<Mesh, MeshError> {
        let format = Format::of(path)?;
        let bytes = std::fs::read(path).map_err(|e| MeshError::read(path, e))?;
        match format {
            Format::Obj => obj::read::read(path, bytes),
            Format::Ply => ply::read::read(path, &bytes),
        }
    }
}
