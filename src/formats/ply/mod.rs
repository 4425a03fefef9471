//! Stanford PLY files (ASCII, binary little and big endian): the header through the
//! `ply-rs-bw` crate, the data straight from the bytes ([`direct`]; written back by patching
//! them, [`patch`]), or, for what that reader leaves aside or refuses, through `ply-rs-bw` as
//! well, whose errors name the fault.
//!
//! The mesh is the `vertex` element's float or double `x`, `y`, `z` and the `face` element's
//! integer list `vertex_indices` (or `vertex_index`); other elements and properties are kept
//! for the faithful writer ([`mod@write`]) and otherwise ignored, but every `float` and
//! `double` value of the file must be finite. The header is checked ([`header`]) before the
//! parser reads the file: no name declared twice, counts within [`crate::limits`]. PLY has no
//! groups. Vertex and face numbers in errors are zero-based, as PLY indices are.

mod direct;
mod error;
mod header;
mod index_list;
mod patch;
pub(crate) mod read;
pub(crate) mod write;

use ply_rs_bw::ply::{DefaultElement, Header, Ply};

pub use error::PlyHeaderError;

/// A PLY file as read, for the faithful writer.
#[derive(Debug)]
pub(crate) enum PlyFile {
    /// Read straight from its bytes, which are kept.
    Bytes(direct::PlyBytes),
    /// Read through `ply-rs-bw`: its header and every element as parsed.
    Parsed(Ply<DefaultElement>),
}

impl PlyFile {
    /// The file's header.
    pub fn header(&self) -> &Header {
        match self {
            PlyFile::Bytes(file) => &file.header,
            PlyFile::Parsed(ply) => &ply.header,
        }
    }
}
