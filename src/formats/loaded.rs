//! [`LoadedMesh`]: a [`Mesh`] with the file it was read from, so that [`LoadedMesh::save`] can
//! write the file back faithfully: the file itself and the data as loaded.

use std::fmt;
use std::sync::Arc;

use glam::DVec3;

use super::gltf::GltfFile;
use super::obj::ObjFile;
use super::off::OffFile;
use super::ply::PlyFile;
use crate::mesh::{FaceGroup, Faces, Mesh};

/// A mesh read from a file ([`LoadedMesh::load`]), with what is needed to write the file back
/// faithfully ([`LoadedMesh::save`]): a deformed file differs from its input only in the
/// positions of the vertices that moved (and, for glTF, the normals around them).
///
/// [`Mesh::load`] reads the mesh data alone, for callers that do not write the file back. A mesh
/// built in code becomes one with no file behind it by `LoadedMesh::from(mesh)`, and is saved
/// generically. Cloning is cheap for the file, which clones share.
#[derive(Clone, Debug)]
pub struct LoadedMesh {
    /// The mesh as read: positions in file order, faces, groups. Editing its connectivity makes
    /// [`LoadedMesh::save`] write a generic file instead of the faithful one.
    pub mesh: Mesh,
    /// The file it was read from.
    pub(crate) source: Source,
}

impl LoadedMesh {
    /// The mesh data, without the file.
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }
}

impl From<Mesh> for LoadedMesh {
    /// A mesh with no file behind it: [`LoadedMesh::save`] writes a generic file.
    fn from(mesh: Mesh) -> Self {
        LoadedMesh { mesh, source: Source::Code }
    }
}

/// Where a mesh came from. Cloning shares it.
#[derive(Clone, Default)]
pub(crate) enum Source {
    /// Built in code: no file to be faithful to.
    #[default]
    Code,
    /// Read from an OBJ file: its bytes, what they gave and where each vertex's statement lies.
    Obj(Arc<ObjFile>),
    /// Read from a PLY file: its bytes and where the vertices lie, or every element as parsed.
    Ply(Arc<Original<PlyFile>>),
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
            Source::Obj(o) => write!(f, "Obj({} bytes)", o.bytes.len()),
            Source::Ply(p) => write!(f, "Ply({:?})", p.file.header().encoding),
            Source::Off(o) => write!(f, "Off({} bytes)", o.file.bytes.len()),
            Source::Gltf(g) => write!(f, "Gltf({} buffers)", g.file.buffers.len()),
        }
    }
}
