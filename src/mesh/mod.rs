//! Meshes in and out: OBJ, PLY, OFF and glTF files, and the enclosed volume of a closed mesh.
//!
//! Data flow: rig → sweep → sweep coefficients → bind → deform → normals → **output**.
//!
//! A [`Mesh`] keeps what deformation needs (positions in file order, polygon faces, named face
//! groups) and, privately, what it needs to write the file back faithfully: a deformed file
//! differs from its input only in the positions of the vertices that moved (and, for glTF,
//! the normals around them).
//!
//! - [`Mesh::load`] reads, by extension, `.obj` (our own scanner, f64, vertex order kept; see
//!   `obj`), `.ply` (header through `ply-rs-bw`, data straight from the bytes; see `ply`), `.off` (ASCII OFF with the `C`, `N` and
//!   `ST` variants, our own reader; see `off`) or `.gltf` / `.glb` (through the `gltf` crate:
//!   every triangle primitive of the default scene, node transforms applied, one group per
//!   mesh; see `gltf`); [`Mesh::from_parts`] builds a mesh in code.
//! - [`Mesh::save`] writes faithfully over the loaded file when the format is the same (for
//!   glTF: `.gltf` or `.glb` from either), generically otherwise, always atomically (temporary
//!   file + rename, [`write_atomically`], which other file writers of the crate share).
//! - [`Mesh::enclosed_volume`], [`Mesh::bounds`], [`Mesh::group_vertices`] measure it.
//! - [`MeshError`] names the file (and the OBJ or OFF line) at fault; malformed input never
//!   panics, every number read must be finite, and counts are checked against
//!   [`crate::limits`] ([`LimitError`]) before anything is allocated for them.

mod atomic;
mod bounds;
#[cfg(feature = "formats")]
mod decimal;
mod error;
mod faces;
#[cfg(feature = "formats")]
mod format;
#[cfg(feature = "formats")]
mod gltf;
mod groups;
#[cfg(feature = "formats")]
mod load;
#[cfg(feature = "formats")]
mod obj;
#[cfg(feature = "formats")]
mod off;
mod parts;
#[cfg(feature = "formats")]
mod ply;
#[cfg(feature = "formats")]
mod save;
mod source;
mod subdivide;
mod triangles;
mod volume;
pub mod weld;

use glam::DVec3;

pub use atomic::{exit_removing_temporaries, write_atomically};
pub use error::{LimitError, Limited, MeshDataError, MeshError, ObjLineError};
#[cfg(feature = "formats")]
pub use format::Format;
#[cfg(feature = "formats")]
pub use gltf::GltfDataError;
#[cfg(feature = "formats")]
pub use off::OffLineError;
#[cfg(feature = "formats")]
pub use ply::PlyHeaderError;
pub use subdivide::{Parents, Subdivision, SubdivisionError};

use source::Source;

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

/// A polygon mesh read from a file ([`Mesh::load`]) or built in code ([`Mesh::from_parts`]).
///
/// Cloning is cheap for the remembered source file, which clones share.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Vertex positions in file order, including vertices no face uses.
    pub positions: Vec<DVec3>,
    /// Polygon faces, in file order.
    pub faces: Faces,
    /// Named face groups in order of first appearance.
    pub groups: Vec<FaceGroup>,
    /// The file the mesh was read from, for faithful saving.
    #[cfg_attr(not(feature = "formats"), expect(dead_code, reason = "only the file readers and writers use it"))]
    source: Source,
}
