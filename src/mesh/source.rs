//! What a [`Mesh`] remembers of the file it was read from, so that [`Mesh::save`] can write the
//! file back faithfully: the file itself and the data as loaded.

use std::fmt;
use std::sync::Arc;

use glam::DVec3;
use ply_rs_bw::ply::{DefaultElement, Ply};

use super::gltf::GltfFile;
use super::off::OffFile;
use super::{FaceGroup, Faces, Mesh};

/// Where a mesh came from. Cloning a mesh shares its source.
#[derive(Clone, Default)]
pub(crate) enum Source {
    /// Built in code by [`Mesh::from_parts`]: no file to be faithful to.
    #[default]
    Code,
    /// Read from an OBJ file: its bytes.
    Obj(Arc<Original<Vec<u8>>>),
    /// Read from a PLY file: its header and every element, as parsed.
    Ply(Arc<Original<Ply<DefaultElement>>>),
    /// Read from an OFF file: its bytes and where each vertex's coordinates lie.
    Off(Arc<Original<OffFile>>),
    /// Read from a glTF or GLB file: its JSON, its buffers and where each vertex came from.
    Gltf(Arc<Original<GltfFile>>),
}

/// A file as read, with the mesh data it gave.
pub(crate) struct Original<F> {
    /// The file, in whatever form its faithful writer needs.
    pub file: F,
    /// The positions as read.
    pub positions: Vec<DVec3>,
    /// The faces as read.
    pub faces: Faces,
    /// The groups as read.
    pub groups: Vec<FaceGroup>,
}

impl<F> Original<F> {
    /// Wraps `file` with a copy of the mesh data read from it.
    pub fn new(file: F, mesh: &Mesh) -> Arc<Self> {
        Arc::new(Self {
            file,
            positions: mesh.positions.clone(),
            faces: mesh.faces.clone(),
            groups: mesh.groups.clone(),
        })
    }

    /// Whether `mesh` still has this file's connectivity (vertex count, faces and groups),
    /// so that the file can be written back with only positions changed.
    pub fn describes(&self, mesh: &Mesh) -> bool {
        mesh.positions.len() == self.positions.len() && mesh.faces == self.faces && mesh.groups == self.groups
    }
}

impl fmt::Debug for Source {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Source::Code => f.write_str("Code"),
            Source::Obj(o) => write!(f, "Obj({} bytes)", o.file.len()),
            Source::Ply(p) => write!(f, "Ply({:?})", p.file.header.encoding),
            Source::Off(o) => write!(f, "Off({} bytes)", o.file.bytes.len()),
            Source::Gltf(g) => write!(f, "Gltf({} buffers)", g.file.buffers.len()),
        }
    }
}
