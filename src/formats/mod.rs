//! Mesh files in and out: OBJ, PLY, OFF and glTF/GLB (feature `formats`).
//!
//! Data flow: rig → sweep → sweep coefficients → bind → deform → normals → **output**.
//!
//! - [`LoadedMesh::load`] reads, by extension, `.obj` (our own scanner, f64, vertex order kept;
//!   see `obj`), `.ply` (header through `ply-rs-bw`, data straight from the bytes; see `ply`),
//!   `.off` (ASCII OFF with the `C`, `N` and `ST` variants, our own reader; see `off`) or
//!   `.gltf` / `.glb` (through the `gltf` crate: every triangle primitive of the default scene,
//!   node transforms applied, one group per mesh; see `gltf`). It keeps the file beside the
//!   [`Mesh`](crate::mesh::Mesh); `Mesh::load` reads the mesh data alone.
//! - [`LoadedMesh::save`] writes faithfully over the loaded file when the format is the same
//!   (for glTF: `.gltf` or `.glb` from either), generically otherwise, always atomically
//!   (temporary file + rename, [`crate::atomic_file::write_atomically`]).
//! - [`MeshError`] names the file (and the OBJ or OFF line) at fault; malformed input never
//!   panics, every number read must be finite, and counts are checked against
//!   [`crate::limits`] before anything is allocated for them.

mod animation;
mod decimal;
mod error;
mod format;
mod gltf;
mod load;
mod loaded;
mod obj;
mod off;
mod ply;
mod save;

pub use animation::save_morph_animation;
pub use error::{MeshError, ObjLineError};
pub use format::Format;
pub use gltf::GltfDataError;
pub use gltf::morph::MorphPose;
pub use loaded::LoadedMesh;
pub use off::OffLineError;
pub use ply::PlyHeaderError;
