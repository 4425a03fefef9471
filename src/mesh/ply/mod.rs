//! Stanford PLY files (ASCII, binary little and big endian), through the `ply-rs-bw` crate.
//!
//! The mesh is the `vertex` element's float or double `x`, `y`, `z` and the `face` element's
//! integer list `vertex_indices` (or `vertex_index`); other elements and properties are kept
//! for the faithful writer ([`mod@write`]) and otherwise ignored, but every `float` and
//! `double` value of the file must be finite. The header is checked ([`header`]) before the
//! parser reads the file: no name declared twice, counts within [`crate::limits`]. PLY has no
//! groups. Vertex and face numbers in errors are zero-based, as PLY indices are.

mod error;
mod header;
pub(crate) mod read;
pub(crate) mod write;

pub use error::PlyHeaderError;
