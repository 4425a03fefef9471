//! What can be wrong with one line of an OFF file.

use thiserror::Error;

use crate::mesh::LimitError;

/// What is wrong with one line of an OFF file. Vertex numbers are zero-based, as in OFF.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum OffLineError {
    /// The first line is not an OFF header keyword.
    #[error("expected an OFF header (OFF, COFF, NOFF, CNOFF, STOFF, …) but found \"{found}\"")]
    NotOff {
        /// The first token as written (invalid UTF-8 replaced).
        found: String,
    },
    /// A variant of OFF this reader does not handle.
    #[error("{what} is not supported")]
    Unsupported {
        /// `"binary OFF"`, `"4D OFF (4OFF)"` or `"n-dimensional OFF (nOFF)"`.
        what: &'static str,
    },
    /// The counts line has fewer than two numbers (vertices and faces).
    #[error("expected the vertex and face counts (and optionally the edge count)")]
    MissingCounts,
    /// A token that should be a number is not one.
    #[error("{what} \"{token}\" is not a number")]
    NotANumber {
        /// `"vertex count"`, `"vertex coordinate"`, `"face index"`, ….
        what: &'static str,
        /// The token as written (invalid UTF-8 replaced).
        token: String,
    },
    /// A vertex line with fewer numbers than the header asks for.
    #[error("vertex {vertex} has {found} numbers but the header asks for at least {needed}")]
    ShortVertex {
        /// Zero-based vertex number.
        vertex: usize,
        /// How many numbers the line has.
        found: usize,
        /// How many the header implies (3, plus 3 for normals, plus 2 for texture coordinates).
        needed: usize,
    },
    /// A vertex with an infinite or NaN coordinate.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// Zero-based vertex number.
        vertex: usize,
    },
    /// A value after the position of a vertex (normal, colour, texture coordinates) or after
    /// the indices of a face (colour) that is infinite or NaN (as written, or too large for
    /// f64).
    #[error("{what} {index} has the non-finite value \"{token}\"")]
    NonFiniteValue {
        /// `"vertex"` or `"face"`.
        what: &'static str,
        /// Zero-based vertex or face number.
        index: usize,
        /// The token as written.
        token: String,
    },
    /// A count of the header, or the corner count of a face, over a limit.
    #[error(transparent)]
    Limit(LimitError),
    /// The file ends before the counts of the header are met.
    #[error("the file ends after {read} of the {declared} {what} the header declares")]
    Truncated {
        /// `"vertices"` or `"faces"`.
        what: &'static str,
        /// How many were read.
        read: usize,
        /// How many the header declares.
        declared: usize,
    },
    /// A face with fewer than three vertices.
    #[error("face {face} has {count} vertices; a face needs at least 3")]
    ShortFace {
        /// Zero-based face number.
        face: usize,
        /// The vertex count as written.
        count: usize,
    },
    /// A face line with fewer indices than its count says.
    #[error("face {face} declares {declared} vertices but lists {found}")]
    MissingIndices {
        /// Zero-based face number.
        face: usize,
        /// The vertex count as written.
        declared: usize,
        /// How many indices follow it.
        found: usize,
    },
    /// A face index that is negative or past the last vertex.
    #[error("face {face} refers to vertex {index} but the file has {count} vertices (indices start at 0)")]
    IndexOutOfRange {
        /// Zero-based face number.
        face: usize,
        /// The index as written.
        index: i64,
        /// The number of vertices in the file.
        count: usize,
    },
    /// More lines follow the last face the header declares.
    #[error("unexpected data after the last of the {faces} faces the header declares")]
    TrailingData {
        /// The face count of the header.
        faces: usize,
    },
}
