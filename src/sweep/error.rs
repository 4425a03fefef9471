//! What can be wrong with the keys and knots a sweep is built from.

use thiserror::Error;

/// A reason the keys or knots of one sweep cannot define a sweep surface. Key indices are
/// zero-based, as in rig files; the rig loader adds the file and sweep name.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SweepError {
    #[error("needs at least 2 keys, found {count}")]
    TooFewKeys { count: usize },
    #[error("has {count} keys, more than {}, the most a sweep may have", crate::limits::MAX_KEYS_PER_SWEEP)]
    TooManyKeys { count: usize },
    #[error("key {key}: has {count} radii, more than {}, the most a key may have", crate::limits::MAX_RADII_PER_KEY)]
    TooManyRadii { key: usize, count: usize },
    #[error("key {key}: needs at least 3 radii, found {count}")]
    TooFewRadii { key: usize, count: usize },
    #[error("key {key}: has {found} radii but key 0 has {expected}; every key of a sweep needs the same number")]
    RadiusCountMismatch { key: usize, expected: usize, found: usize },
    #[error("key {key}: {field} is not a finite number")]
    NonFinite { key: usize, field: &'static str },
    #[error("key {key}: rotation is the zero quaternion")]
    ZeroRotation { key: usize },
    #[error("key {key}: rotation cannot be normalized: its squared length {length_squared:e} under- or overflows")]
    RotationScale { key: usize, length_squared: f64 },
    #[error(
        "key {key}: center coordinate {value:e} lies beyond ±{:e} mesh units, the largest a rig may have",
        crate::limits::MAX_RIG_COORDINATE
    )]
    CenterOutOfRange { key: usize, value: f64 },
    #[error(
        "key {key}: radius {index} ({value:e}) is larger than {:e} mesh units, the largest a rig may have",
        crate::limits::MAX_RIG_COORDINATE
    )]
    RadiusOutOfRange { key: usize, index: usize, value: f64 },
    #[error("key {key}: radius {index} is negative ({value})")]
    NegativeRadius { key: usize, index: usize, value: f64 },
    #[error("key {key}: the distance from the center of key {previous} is too large to represent")]
    ChordOverflow { key: usize, previous: usize },
    #[error("key {key}: center coincides with the center of key {previous}, so the chord-length knot is undefined")]
    CoincidentCenters { key: usize, previous: usize },
    #[error("has {found} knots for {keys} keys")]
    KnotCount { keys: usize, found: usize },
    #[error("knot {index} is not a finite number")]
    NonFiniteKnot { index: usize },
    #[error("knots must run from 0 to 1, found {first} … {last}")]
    KnotRange { first: f64, last: f64 },
    #[error("knot {index} ({value}) does not increase on knot {previous}")]
    KnotsNotIncreasing { index: usize, previous: f64, value: f64 },
    #[error(
        "knot {index} ({value:e}) is less than {:e} above the knot before it ({previous:e}); knots must be at least that far apart",
        crate::limits::MIN_KNOT_SPACING
    )]
    KnotsTooClose { index: usize, previous: f64, value: f64 },
    #[error(
        "key {key}: center lies {fraction:e} of the sweep's chord length from the center of key {previous}; the chord-length knots need at least {:e}",
        crate::limits::MIN_KNOT_SPACING
    )]
    CentersTooClose { key: usize, previous: usize, fraction: f64 },
}
