//! What can be wrong with a rig, a pose or the ownership of vertices.

use std::fmt;
use std::path::PathBuf;

use thiserror::Error;

use crate::sweep::SweepError;

/// A rig or pose that cannot be used, with the file it came from when there is one.
#[derive(Debug, Error)]
pub struct RigError {
    /// The rig or pose file at fault, if the rig came from a file.
    pub file: Option<PathBuf>,
    /// What is wrong.
    #[source]
    pub kind: RigErrorKind,
}

impl fmt::Display for RigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(file) => write!(f, "{}: {}", file.display(), self.kind),
            None => write!(f, "{}", self.kind),
        }
    }
}

impl RigError {
    pub(crate) fn new(file: Option<PathBuf>, kind: RigErrorKind) -> RigError {
        RigError { file, kind }
    }
}

/// What is wrong with a rig, pose or vertex ownership; sweeps are named, keys and vertices are
/// zero-based indices.
#[derive(Debug, Error)]
pub enum RigErrorKind {
    #[error("cannot read the file: {0}")]
    Io(#[from] std::io::Error),
    #[cfg(feature = "json")]
    #[error("not a valid rig file: {0}")]
    Json(#[from] serde_json::Error),
    #[error("\"format\" is {found:?}, expected \"sweepffd-rig\"")]
    Format { found: String },
    #[error("\"version\" is {found}, this release reads version 1")]
    Version { found: u32 },
    #[error("the rig has no sweeps")]
    NoSweeps,
    #[error("the rig has {count} sweeps, more than {}, the most a rig may have", crate::limits::MAX_SWEEPS)]
    TooManySweeps { count: usize },
    #[error(
        "sweep {sweep:?}: the rig holds more than {} radii in all, the most a rig may have",
        crate::limits::MAX_RADII_PER_RIG
    )]
    TooManyRadii { sweep: String },
    #[error("sweep {sweep:?}: {place} is {value}, not a finite number; nothing was written")]
    NonFiniteOutput { sweep: String, place: String, value: f64 },
    #[error("two sweeps are named {name:?}")]
    DuplicateName { name: String },
    #[error("sweep {sweep:?}: {source}")]
    Sweep { sweep: String, source: SweepError },
    #[error("the pose has no sweep {sweep:?}, which the rest rig has")]
    PoseMissingSweep { sweep: String },
    #[error("the pose has a sweep {sweep:?}, which the rest rig does not have")]
    PoseUnknownSweep { sweep: String },
    #[error("sweep {sweep:?}: the pose has {found} keys but the rest rig has {expected}")]
    PoseKeyCount { sweep: String, expected: usize, found: usize },
    #[error("sweep {sweep:?}: key {key}: the pose has {found} radii but the rest rig has {expected}")]
    PoseRadiusCount { sweep: String, key: usize, expected: usize, found: usize },
    #[error("sweep {sweep:?}: the mesh {mesh} has no group {group:?} (its groups: {available})")]
    UnknownGroup { sweep: String, group: String, mesh: String, available: String },
    #[error(
        "sweep {sweep:?}: vertex index {index} (zero-based) is out of range (the mesh {mesh} has {count} vertices)"
    )]
    VertexOutOfRange { sweep: String, index: u32, mesh: String, count: usize },
    #[error("sweep {sweep:?}: its parent {parent:?} is not a sweep of the rig")]
    UnknownParent { sweep: String, parent: String },
    #[error("the hierarchy has a cycle: {chain}")]
    ParentCycle { chain: String },
    #[error(
        "sweep {sweep:?}: a loop child needs at least 3 keys (its first and last are bound to the parent), found {keys}"
    )]
    LoopTooShort { sweep: String, keys: usize },
    #[error(
        "sweep {sweep:?}: key {key} cannot be bound to its parent {parent:?}: its center lies beyond the parent's ends"
    )]
    LinkUnbound { sweep: String, key: usize, parent: String },
    #[error("sweep {sweep:?}: falloff {falloff} must be a finite width of at least 0 (mesh units)")]
    BadFalloff { sweep: String, falloff: f64 },
    #[error("sweep {sweep:?}: a virtual sweep (one that owns no vertices) cannot have a falloff")]
    VirtualFalloff { sweep: String },
    #[error(
        "sweep {sweep:?}: falloff {falloff} is larger than the mesh {mesh} (its bounding box diagonal is {diagonal})"
    )]
    FalloffTooLarge { sweep: String, falloff: f64, mesh: String, diagonal: f64 },
    #[error(
        "sweep {sweep:?}, key {key}: radius {radius:e} is more than {most:e} times the mesh {mesh} (its bounding box \
         diagonal is {diagonal}), beyond what f64 places accurately (limits::MAX_RADIUS_PER_MESH_SIZE)",
        most = crate::limits::MAX_RADIUS_PER_MESH_SIZE
    )]
    RadiusTooLarge { sweep: String, key: usize, radius: f64, mesh: String, diagonal: f64 },
    #[error("vertex index {vertex} (zero-based) is claimed by both sweep {first:?} and sweep {second:?}")]
    VertexClaimedTwice { vertex: u32, first: String, second: String },
}
