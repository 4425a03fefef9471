//! Why a sweep could not be fitted to a part.

use thiserror::Error;

use crate::sweep::SweepError;

/// A fit that could not be made; the caller adds the mesh and the part's name.
#[derive(Debug, Error, PartialEq)]
pub enum FitError {
    /// The options themselves are unusable.
    #[error("{0}")]
    Options(String),
    /// A selected vertex is not in the mesh.
    #[error("vertex {index} is out of range: the mesh has {count} vertices")]
    VertexOutOfRange { index: u32, count: usize },
    /// Too few vertices to fit anything.
    #[error("the part has {0} vertices; a sweep needs at least 4")]
    TooFewVertices(usize),
    /// No face lies wholly in the part, so there is nothing to cut.
    #[error("no face of the mesh has all its vertices in the part, so the part cannot be cut into cross-sections")]
    NoFaces,
    /// The axis polyline is unusable.
    #[error("the axis needs at least two distinct finite points")]
    Axis,
    /// The part has no length along its axis.
    #[error("the part has no extent along its axis")]
    Flat,
    /// No key plane cuts the part.
    #[error("no key plane cuts the part; give an --axis that runs through it")]
    NoSection,
    /// The fitted keys do not make a sweep.
    #[error("the fitted keys do not make a sweep: {0}")]
    Sweep(#[from] SweepError),
}
