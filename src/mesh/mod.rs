//! Meshes in code: positions, polygon faces and named face groups, with the measures the
//! engine and the fitting take of them (enclosed volume, bounds, group vertices), welding and
//! subdivision. Reading and writing files is `formats` (feature `formats`).
//!
//! Data flow: rig → sweep → sweep coefficients → bind → deform → normals → output.
//!
//! - [`Mesh::from_parts`] builds a mesh and checks it ([`MeshDataError`]);
//!   [`Faces::from_triangles`] takes an engine's `u32` triangle list.
//! - [`Mesh::enclosed_volume`], [`Mesh::bounds`], [`Mesh::group_vertices`] measure it.
//! - Counts are checked against [`crate::limits`] ([`LimitError`]) before anything is allocated
//!   for them.

mod bounds;
mod closed;
mod error;
mod faces;
mod groups;
mod parts;
mod subdivide;
mod triangles;
mod volume;
pub mod weld;

use glam::DVec3;

pub(crate) use bounds::bounds_of;
pub use closed::OpenEdge;
pub use error::{LimitError, Limited, MeshDataError};
pub use subdivide::{Parents, Subdivision, SubdivisionError};

/// Polygon faces as a flat index list: face `f` has the vertex indices
/// `indices[offsets[f]..offsets[f + 1]]` (zero-based, into [`Mesh::positions`]). An engine's
/// `u32` triangle list becomes one by [`Faces::from_triangles`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Faces {
    /// `offsets.len() == face count + 1`, `offsets[0] == 0`.
    pub offsets: Vec<u32>,
    /// Vertex indices of all faces, face after face.
    pub indices: Vec<u32>,
}

/// A named set of faces: an OBJ group (`g`) or object (`o`), or a glTF mesh.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaceGroup {
    /// The group's name as written in the file.
    pub name: String,
    /// Indices of the faces in the group, increasing.
    pub faces: Vec<u32>,
}

/// A polygon mesh built in code ([`Mesh::from_parts`]) or read from a file (`Mesh::load` and
/// `LoadedMesh`, feature `formats`).
///
/// Its fields can be read and changed; it is built only through [`Mesh::from_parts`] (or a
/// reader), which checks that the faces and groups refer to what exists.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Mesh {
    /// Vertex positions in file order, including vertices no face uses.
    pub positions: Vec<DVec3>,
    /// Polygon faces, in file order.
    pub faces: Faces,
    /// Named face groups in order of first appearance.
    pub groups: Vec<FaceGroup>,
}
