//! Object File Format (`.off`, Geomview / CGAL / Princeton shape benchmark), ASCII.
//!
//! A header keyword `[ST][C][N]OFF` (so `OFF`, `COFF`, `NOFF`, `CNOFF`, `STOFF`, …), the
//! counts `V F [E]` (on the header line or the next one), then one vertex per line
//! (`x y z`, then `nx ny nz` with `N`, colour values with `C` — RGB or RGBA, integers or
//! floats —, then `s t` with `ST`), then one face per line (`n i0 … i(n−1)`, zero-based, any
//! `n ≥ 3`, optionally followed by a face colour). `#` starts a comment anywhere; blank lines
//! are skipped. Binary OFF, `4OFF` and `nOFF` are rejected with an error.
//!
//! Only positions and faces become the [`Mesh`](super::Mesh); the faithful writer
//! ([`mod@write`]) copies the file byte for byte except the three coordinates of moved
//! vertices, so normals, colours and comments survive a deformation. Errors name the file and
//! the 1-based line ([`OffLineError`]).

mod error;
mod lines;
pub(crate) mod read;
pub(crate) mod write;

pub use error::OffLineError;

/// An OFF file as read: its bytes and where each vertex's `x y z` lies in them.
pub(crate) struct OffFile {
    /// The file, unchanged.
    pub bytes: Vec<u8>,
    /// For each vertex, the byte range from the start of `x` to the end of `z`.
    pub coordinates: Vec<std::ops::Range<usize>>,
}
