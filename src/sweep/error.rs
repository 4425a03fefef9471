//! What can be wrong with the keys and knots a sweep is built from.

use thiserror::Error;

/// A reason the keys or knots of one sweep cannot define a sweep surface. Key indices are
/// zero-based, as in rig files; the rig loader adds the file and sweep name.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SweepError {
    #[error("needs at least 2 keys, found {count}")]
    TooFewKeys { count: usize },
    #[error("key {key}: needs at least 3 radii, found {count}")]
    TooFewRadii { key: usize, count: usize },
    #[error("key {key}: has {found} radii but key 0 has {expected}; every key of a sweep needs the same number")]
    RadiusCountMismatch { key: usize, expected: usize, found: usize },
    #[error("key {key}: {field} is not a finite number")]
    NonFinite { key: usize, field: &'static str },
    #[error("key {key}: rotation is the zero quaternion")]
    ZeroRotation { key: usize },
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
}
