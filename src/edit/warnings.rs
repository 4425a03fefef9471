//! Warnings before a posed sweep folds ([`Sweep::folds`]): where its cross-sections cross
//! (r·κ ≥ 1), its keys step backwards or its frame flips. A warning is not an error: the pose
//! is still used, and whoever made it is told which sweep folds, where and by how much.

use crate::rig::Rig;
use crate::sweep::{Fold, Sweep};

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
/// not have: a fold of the rest sweep (a fitted sweep whose keys step back over a bump) is
/// the rig's, not the pose's, and is reported only where the pose makes it worse (a larger
/// amount, or a stretch the rest's folds of that kind do not cover).
pub fn pose_warnings(rig: &Rig, posed: &[Sweep]) -> Vec<PoseWarning> {
    let mut warnings = Vec::new();
    for ((sweep, rest), posed) in rig.sweeps().iter().zip(rig.rest()).zip(posed) {
        let at_rest = rest.folds();
        let the_rigs = |fold: &Fold| {
            at_rest.iter().any(|r| {
                r.kind == fold.kind
                    && r.t[0] <= fold.t[0]
                    && r.t[1] >= fold.t[1]
                    && r.amount >= fold.amount * (1.0 - 1e-9)
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
