//! What a [`Mesh`] remembers of the file it was read from, so that [`Mesh::save`] can write the
//! file back faithfully: the file itself and the data as loaded.

use std::fmt;
use std::sync::Arc;

use glam::DVec3;

#[cfg(feature = "formats")]
use super::gltf::GltfFile;
#[cfg(feature = "formats")]
use super::obj::ObjFile;
#[cfg(feature = "formats")]
use super::off::OffFile;
#[cfg(feature = "formats")]
use super::ply::PlyFile;
use super::{FaceGroup, Faces, Mesh};

/// Where a mesh came from. Cloning a mesh shares its source.
#[derive(Clone, Default)]
pub(crate) enum Source {
    /// Built in code by [`Mesh::from_parts`]: no file to be faithful to.
    #[default]
    Code,
    /// Read from an OBJ file: its bytes, what they gave and where each vertex's statement lies.
    #[cfg(feature = "formats")]
    Obj(Arc<ObjFile>),
    /// Read from a PLY file: its bytes and where the vertices lie, or every element as parsed.
    #[cfg(feature = "formats")]
    Ply(Arc<Original<PlyFile>>),
    /// Read from an OFF file: its bytes and where each vertex's coordinates lie.
    #[cfg(feature = "formats")]
    Off(Arc<Original<OffFile>>),
    /// Read from a glTF or GLB file: its JSON, its buffers and where each vertex came from.
    #[cfg(feature = "formats")]
    Gltf(Arc<Original<GltfFile>>),
}

/// A file as read, with the mesh data it gave.
#[cfg_attr(not(feature = "formats"), expect(dead_code, reason = "only the file readers and writers use it"))]
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

#[cfg_attr(not(feature = "formats"), expect(dead_code, reason = "only the file readers and writers use it"))]
impl<F> Original<F> {
    /// Wraps `file` with a copy of the mesh data read from it (the positions and the faces
    /// copied at once on two cores, with the feature `parallel`).
    pub fn new(file: F, mesh: &Mesh) -> Arc<Self> {
        let (positions, faces) = crate::parallel::join(|| mesh.positions.clone(), || mesh.faces.clone());
        Arc::new(Self { file, positions, faces, groups: mesh.groups.clone() })
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
            #[cfg(feature = "formats")]
            Source::Obj(o) => write!(f, "Obj({} bytes)", o.bytes.len()),
            #[cfg(feature = "formats")]
            Source::Ply(p) => write!(f, "Ply({:?})", p.file.header().encoding),
            #[cfg(feature = "formats")]
            Source::Off(o) => write!(f, "Off({} bytes)", o.file.bytes.len()),
            #[cfg(feature = "formats")]
            Source::Gltf(g) => write!(f, "Gltf({} buffers)", g.file.buffers.len()),
        }
    }
}
