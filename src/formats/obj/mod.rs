//! Wavefront OBJ files, read in f64 and written back faithfully.
//!
//! We do not use the `tobj` crate: it re-indexes vertices per model and drops the vertices no
//! face uses, which breaks "vertex i of the mesh is the i-th `v` line of the file" (the Stanford
//! bunny has 1,113 unused vertices, and a rig binds vertices by index). Other OBJ crates read
//! f32 only or panic on free-form statements. So a small line scanner ([`scan`]) is shared by
//! the reader ([`read`]) and the faithful writer ([`mod@write`]): one tokenizer, so they always
//! agree on which line is which vertex. Large files are read, and written, in pieces on every
//! core (see [`read`]).
//!
//! Understood statements: `v x y z [w]` and `v x y z r g b` (the first three numbers are the
//! position), `f`/`fo` with `p`, `p/t`, `p//n`, `p/t/n` (1-based, or negative relative to the
//! vertices read so far), `g name…` and `o name` (both name groups, see [`read`]). Every other
//! statement (`vt`, `vn`, `usemtl`, `mtllib`, `s`, `l`, `p`, …) is kept verbatim and ignored.

mod as_read;
mod float;
mod join;
mod part;
mod pieces;
mod plain;
pub(crate) mod read;
pub(crate) mod scan;
pub(crate) mod texcoords;
pub(crate) mod write;

use std::path::Path;

use as_read::AsRead;

use super::MeshError;
use crate::mesh::{FaceGroup, Mesh};

/// An OBJ file as read, for the faithful writer: its bytes and what they gave ([`AsRead`]:
/// the positions, the faces and where each vertex's `v` statement starts, the byte offset of
/// its logical line, so that a write visits only the statements of moved vertices).
pub(crate) struct ObjFile {
    /// The file.
    pub bytes: Vec<u8>,
    /// The positions, faces and vertex lines read from it.
    pub read: AsRead,
    /// The groups read from it.
    pub groups: Vec<FaceGroup>,
}

impl ObjFile {
    /// Whether `mesh` still has this file's connectivity (vertex count, faces and groups),
    /// so that the file can be written back with only positions changed.
    pub fn describes(&self, mesh: &Mesh) -> bool {
        mesh.positions.len() == self.read.vertex_count()
            && mesh.groups == self.groups
            && self.read.has_faces(&mesh.faces)
    }
}

/// Reads the OBJ file `bytes` (read from `path`, which errors name): the mesh, and the file for
/// the faithful writer.
pub(crate) fn read(path: &Path, bytes: Vec<u8>) -> Result<(Mesh, ObjFile), MeshError> {
    let (mesh, read) = match pieces::read_in_pieces(&bytes) {
        Some(read) => read,
        None => read::read_whole(path, &bytes)?,
    };
    let file = ObjFile { bytes, read, groups: mesh.groups.clone() };
    Ok((mesh, file))
}
