//! What can go wrong while posing a rig by edits.

use thiserror::Error;

use crate::sweep::SweepError;

/// Why an edit cannot be applied. Nothing is changed when an edit fails.
#[derive(Debug, Error)]
pub enum EditError {
    #[error("the rig has no sweep {sweep:?}")]
    UnknownSweep { sweep: String },
    #[error("sweep {sweep:?} has {count} keys, so there is no key {key}")]
    KeyOutOfRange { sweep: String, key: usize, count: usize },
    #[error("{0}")]
    Invalid(String),
    #[error("the keys no longer make a sweep: {0}")]
    Degenerate(#[from] SweepError),
    #[error(
        "did not converge in {iterations} iterations: still {remaining:.3e} from the target and {angle:.3e} rad off"
    )]
    NotConverged { iterations: usize, remaining: f64, angle: f64 },
    #[error("while keeping sweep {sweep:?} attached in the hierarchy: {source}")]
    Hierarchy { sweep: String, source: Box<EditError> },
    #[error("sweep {sweep:?} no longer makes a sweep: {source}")]
    Sweep { sweep: String, source: SweepError },
    #[error(
        "the volume rule did not converge in {rounds} rounds: the volumes are still {remaining:.3e} (relative) from their targets"
    )]
    VolumeNotConverged { rounds: usize, remaining: f64 },
    #[error("the volume rule cannot give sweep {sweep:?} the volume {target:.6e}")]
    VolumeUnreachable { sweep: String, target: f64 },
    #[error("the volume rule `ratio` cannot keep sweep {sweep:?}'s volume in ratio: it had no volume before the edit")]
    NoVolumeToKeep { sweep: String },
    #[error("the mesh volume rule needs a closed mesh bound to the rig")]
    MeshNeeded,
}
