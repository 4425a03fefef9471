//! What can be wrong with mesh data, and the size limits of a mesh.
//!
//! Numbers of vertices and faces are zero-based.

use thiserror::Error;

use crate::limits;

/// A count read from a file that is over one of the limits of [`crate::limits`].
#[derive(Clone, Copy, Debug, Error, PartialEq, Eq)]
#[error("{count} {}, over the limit of {} ({})", .limited.noun(), .limited.limit(), .limited.name())]
pub struct LimitError {
    /// What is counted.
    pub limited: Limited,
    /// The count declared by a header, or reached while reading (the limit plus one).
    pub count: u64,
}

/// The counts of a mesh file that [`crate::limits`] bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limited {
    /// Vertices of a mesh ([`limits::MAX_VERTICES`]).
    Vertices,
    /// Polygon faces of a mesh ([`limits::MAX_FACES`]).
    Faces,
    /// Triangles of a mesh once its faces are fan-triangulated ([`limits::MAX_FACES`]).
    Triangles,
    /// Corners of one polygon face ([`limits::MAX_FACE_CORNERS`]).
    FaceCorners,
    /// Entries of a PLY element other than `vertex` and `face` ([`limits::MAX_PLY_ENTRIES`]).
    PlyEntries,
}

impl Limited {
    /// The limit's value.
    pub fn limit(self) -> usize {
        match self {
            Limited::Vertices => limits::MAX_VERTICES,
            Limited::Faces | Limited::Triangles => limits::MAX_FACES,
            Limited::FaceCorners => limits::MAX_FACE_CORNERS,
            Limited::PlyEntries => limits::MAX_PLY_ENTRIES,
        }
    }

    /// The limit's name in [`crate::limits`], as errors show it.
    pub fn name(self) -> &'static str {
        match self {
            Limited::Vertices => "limits::MAX_VERTICES",
            Limited::Faces | Limited::Triangles => "limits::MAX_FACES",
            Limited::FaceCorners => "limits::MAX_FACE_CORNERS",
            Limited::PlyEntries => "limits::MAX_PLY_ENTRIES",
        }
    }

    /// What is counted, in the plural.
    pub fn noun(self) -> &'static str {
        match self {
            Limited::Vertices => "vertices",
            Limited::Faces => "faces",
            Limited::Triangles => "triangles after fan triangulation",
            Limited::FaceCorners => "vertices in one face",
            Limited::PlyEntries => "entries",
        }
    }

    /// `Err` with `count` when it is over the limit.
    #[cfg_attr(not(feature = "formats"), allow(dead_code, reason = "the file readers check their counts"))]
    pub(crate) fn check(self, count: u64) -> Result<(), LimitError> {
        if count > self.limit() as u64 { Err(LimitError { limited: self, count }) } else { Ok(()) }
    }
}

/// What is wrong with mesh data: positions, faces and groups. Numbers are zero-based.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MeshDataError {
    /// The position list is empty.
    #[error("the mesh has no vertices")]
    NoVertices,
    /// [`Faces::offsets`](super::Faces::offsets) does not describe [`Faces::indices`](super::Faces::indices).
    #[error("malformed faces: {reason}")]
    MalformedFaces {
        /// Which invariant is broken.
        reason: &'static str,
    },
    /// A face index past the last vertex (or negative).
    #[error("face {face} refers to vertex {index} but the mesh has {count} vertices")]
    IndexOutOfRange {
        /// Zero-based face number.
        face: usize,
        /// The index as stored.
        index: i64,
        /// The number of vertices.
        count: usize,
    },
    /// A face with fewer than three vertices.
    #[error("face {face} has {count} vertices; a face needs at least 3")]
    ShortFace {
        /// Zero-based face number.
        face: usize,
        /// How many vertices the face has.
        count: usize,
    },
    /// A position with an infinite or NaN coordinate.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// Zero-based vertex number.
        vertex: usize,
    },
    /// A group lists a face past the last face.
    #[error("group \"{group}\" refers to face {face} but the mesh has {count} faces")]
    GroupFaceOutOfRange {
        /// The group's name.
        group: String,
        /// The face number as stored.
        face: u32,
        /// The number of faces.
        count: usize,
    },
    /// A group's face list is not strictly increasing.
    #[error("group \"{group}\": its face list is not strictly increasing")]
    GroupNotIncreasing {
        /// The group's name.
        group: String,
    },
    /// A position list does not have one entry per vertex of the mesh.
    #[error("positions has {found} entries but the mesh has {expected} vertices")]
    PositionCount {
        /// The mesh's vertex count.
        expected: usize,
        /// The length of the list given.
        found: usize,
    },
}
