//! Warnings before a posed sweep folds ([`Sweep::folds`]): where its cross-sections cross
//! (r·κ ≥ 1), its keys step backwards or its frame flips. A warning is not an error: the pose
//! is still used, and whoever made it is told which sweep folds, where and by how much.

use crate::rig::Rig;
use crate::sweep::{Fold, SAMPLES_PER_INTERVAL, Sweep};

/// A fold the rest rig has is reported once the pose makes its amount larger by this share.
pub const WORSE: f64 = 0.01;

/// A fold of one posed sweep, named.
#[derive(Clone, Debug, PartialEq)]
pub struct PoseWarning {
    /// The sweep's name.
    pub sweep: String,
    /// Where and how it folds.
    pub fold: Fold,
}

impl std::fmt::Display for PoseWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "sweep {:?} folds: {}", self.sweep, self.fold)
    }
}

/// The folds of `posed` (one sweep per sweep of `rig`, in its order) that its rest sweeps do
/// not have. A fold of the rest sweep (a fitted sweep whose key 0 leans into the plane of its
/// rim, or whose keys step back over a bump) is the rig's, not the pose's: a posed fold within
/// a rest fold of its kind (to a sample's step) is reported only where the pose makes its
/// amount larger by more than [`WORSE`] of it.
pub fn pose_warnings(rig: &Rig, posed: &[Sweep]) -> Vec<PoseWarning> {
    let mut warnings = Vec::new();
    for ((sweep, rest), posed) in rig.sweeps().iter().zip(rig.rest()).zip(posed) {
        let at_rest = rest.folds();
        let step = rest.knots().windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max) / SAMPLES_PER_INTERVAL as f64;
        let the_rigs = |fold: &Fold| {
            at_rest.iter().any(|r| {
                r.kind == fold.kind
                    && r.t[0] - step <= fold.t[0]
                    && fold.t[1] <= r.t[1] + step
                    && fold.amount <= r.amount * (1.0 + WORSE)
            })
        };
        warnings.extend(
            posed
                .folds()
                .into_iter()
                .filter(|fold| !the_rigs(fold))
                .map(|fold| PoseWarning { sweep: sweep.name.clone(), fold }),
        );
    }
    warnings
}
