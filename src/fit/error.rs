//! Why a sweep could not be fitted to a part.

use thiserror::Error;

use crate::limits::{MAX_KEYS_PER_SWEEP, MAX_RADII_PER_KEY};
use crate::sweep::SweepError;

/// A fit that could not be made; the caller adds the mesh and the part's name.
#[derive(Debug, Error, PartialEq)]
pub enum FitError {
    /// The options themselves are unusable.
    #[error("{0}")]
    Options(#[from] OptionError),
    /// A selected vertex is not in the mesh.
    #[error("vertex {index} is out of range: the mesh has {count} vertices")]
    VertexOutOfRange { index: u32, count: usize },
    /// A vertex lies beyond the coordinates a rig may hold
    /// ([`MAX_RIG_COORDINATE`](crate::limits::MAX_RIG_COORDINATE)), so no sweep could reach it.
    #[error(
        "vertex {vertex} has the coordinate {value:e}, beyond the ±{:e} a rig may hold (limits::MAX_RIG_COORDINATE)",
        crate::limits::MAX_RIG_COORDINATE
    )]
    BeyondRig { vertex: u32, value: f64 },
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
    #[error("no key plane cuts the part; give an axis that runs through it")]
    NoSection,
    /// The fitted keys do not make a sweep.
    #[error("the fitted keys do not make a sweep: {0}")]
    Sweep(#[from] SweepError),
}

/// An option of [`FitOptions`](super::FitOptions) or
/// [`AutorigOptions`](super::autorig::AutorigOptions) that cannot be honoured: the field at
/// fault (as [`OptionError::field`] names it) and its value.
#[derive(Debug, Error, Clone, Copy, PartialEq)]
pub enum OptionError {
    #[error("keys must be at least 2, found {0}")]
    TooFewKeys(usize),
    #[error("radii must be at least 3, found {0}")]
    TooFewRadii(usize),
    #[error("radii {0} is over the limit of {MAX_RADII_PER_KEY} radii per key")]
    TooManyRadii(usize),
    #[error("keys {0} is over the limit of {MAX_KEYS_PER_SWEEP} keys per sweep")]
    TooManyKeys(usize),
    #[error("max_keys {0} is over the limit of {MAX_KEYS_PER_SWEEP} keys per sweep")]
    TooManyMaxKeys(usize),
    #[error("max_keys ({max_keys}) must be at least keys ({keys})")]
    MaxKeysBelowKeys { max_keys: usize, keys: usize },
    #[error("tolerance must be a positive number, found {0}")]
    Tolerance(f64),
    #[error("falloff must be a finite width of at least 0 (mesh units), found {0}")]
    Falloff(f64),
    #[error("min_length must be a positive fraction of the mesh's size, found {0}")]
    MinLength(f64),
    /// More keys or radii than the part's vertices determine: at most the larger of the
    /// default and the part's vertex count, so that a fit's cost follows its part.
    #[error("{field} {value} is more than a part of {vertices} vertices determines (at most {most})")]
    BeyondPart {
        /// The option: `keys`, `max_keys` or `radii`.
        field: &'static str,
        /// Its value.
        value: usize,
        /// The most the part allows.
        most: usize,
        /// The part's vertex count.
        vertices: usize,
    },
    /// More parts asked for than a rig may hold ([`crate::limits::MAX_SWEEPS`]).
    #[error("max_parts {0} is over the limit of {max} sweeps per rig", max = crate::limits::MAX_SWEEPS)]
    TooManyParts(usize),
}

impl OptionError {
    /// The field of the options at fault (the first named, where two are compared).
    pub fn field(&self) -> &'static str {
        match self {
            OptionError::TooFewKeys(_) | OptionError::TooManyKeys(_) => "keys",
            OptionError::TooFewRadii(_) | OptionError::TooManyRadii(_) => "radii",
            OptionError::TooManyMaxKeys(_) | OptionError::MaxKeysBelowKeys { .. } => "max_keys",
            OptionError::Tolerance(_) => "tolerance",
            OptionError::Falloff(_) => "falloff",
            OptionError::MinLength(_) => "min_length",
            OptionError::TooManyParts(_) => "max_parts",
            OptionError::BeyondPart { field, .. } => field,
        }
    }
}
