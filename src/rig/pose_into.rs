//! Posing every frame without allocating: [`Rig::pose_into`] rebuilds the posed sweeps in a
//! [`PoseBuffer`] made once, instead of returning new ones as [`Rig::pose`] does.

use std::ops::Deref;

use super::{Rig, RigError, RigErrorKind};
use crate::sweep::{Key, RebuildScratch, Sweep, knots};

/// A rig's posed sweeps, kept from frame to frame and refilled in place by
/// [`Rig::pose_into`]; made by [`Rig::pose_buffer`]. Dereferences to the sweeps, in the order
/// of [`Rig::sweeps`], so `deformer.set_pose(&buffer)` takes it as it is.
#[derive(Clone, Debug)]
pub struct PoseBuffer {
    sweeps: Vec<Sweep>,
    scratch: RebuildScratch,
}

impl PoseBuffer {
    /// The posed sweeps, in rig order: the rest sweeps until the first [`Rig::pose_into`].
    pub fn sweeps(&self) -> &[Sweep] {
        &self.sweeps
    }
}

impl Deref for PoseBuffer {
    type Target = [Sweep];

    fn deref(&self) -> &[Sweep] {
        &self.sweeps
    }
}

impl Rig {
    /// Storage for [`Rig::pose_into`], holding the rest sweeps: sized for this rig, so that
    /// posing into it allocates nothing.
    pub fn pose_buffer(&self) -> PoseBuffer {
        let keys = self.sweeps.iter().map(|sweep| sweep.keys.len()).max().unwrap_or(0);
        let samples = self.rest.iter().map(Sweep::radius_samples).max().unwrap_or(0);
        PoseBuffer {
            sweeps: self.rest.iter().map(Sweep::detached).collect(),
            scratch: RebuildScratch::with_capacity(keys, samples),
        }
    }

    /// [`Rig::pose`] into `out`: the posed sweeps for `keys[i]` on sweep i (rest knots), bit
    /// for bit those `pose` returns, checked as it checks them (the same errors: a missing
    /// sweep, a key or radius count that differs from the rest rig's, a key
    /// [`Sweep::try_new`] rejects).
    ///
    /// Allocates nothing once `out` holds sweeps of this rig's structure (as from
    /// [`Rig::pose_buffer`], or after one `pose_into`) and the keys are valid: the spline
    /// systems of the rest knots are factorized once, in the rig, and `out`'s vectors are
    /// refilled. On an error `out` is left as it was. Keys beyond the rig's sweeps are ignored,
    /// as by `pose`. A hierarchy (branch, loop or virtual parents, [`super::Link`]) changes
    /// nothing here: as for `pose`, the keys given are the keys posed, children included.
    pub fn pose_into<K: AsRef<[Key]>>(&self, keys: &[K], out: &mut PoseBuffer) -> Result<(), RigError> {
        for index in 0..self.sweeps.len() {
            self.check_pose_keys(index, keys.get(index).map(AsRef::as_ref))
                .map_err(|kind| RigError::new(None, kind))?;
        }
        out.sweeps.truncate(self.rest.len());
        for rest in &self.rest[out.sweeps.len()..] {
            out.sweeps.push(rest.detached());
        }
        for (((posed, rest), systems), keys) in out.sweeps.iter_mut().zip(&self.rest).zip(&self.systems).zip(keys) {
            posed.rebuild_valid(keys.as_ref(), rest.knots(), systems, &mut out.scratch);
        }
        Ok(())
    }

    /// The checks [`Rig::pose`] makes of the keys of sweep `index` (`None`: the pose has none),
    /// in its order, without building the sweep.
    fn check_pose_keys(&self, index: usize, keys: Option<&[Key]>) -> Result<(), RigErrorKind> {
        let name = || self.sweeps[index].name.clone();
        let Some(keys) = keys else {
            return Err(RigErrorKind::PoseMissingSweep { sweep: name() });
        };
        self.check_pose_structure(index, keys)?;
        Sweep::validate(keys)
            .and_then(|()| knots::validate_knots(self.rest[index].knots(), keys.len()))
            .map_err(|source| RigErrorKind::Sweep { sweep: name(), source })
    }
}
