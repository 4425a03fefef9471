//! Rebuilding a sweep after a rigid edit of its keys (§4): moving or turning key cross-sections
//! changes C(t) and R(t) only, so the radius function r(θ, t) — the costly part, one bicubic
//! patch per radius — is kept.

use std::sync::Arc;

use glam::{DQuat, DVec3};

use super::cubic::CubicPiece;
use super::curve::CurvePiece;
use super::orientation;
use super::{Key, Sweep, SweepError, axis_segments, validate_count, validate_frame};

impl Sweep {
    /// The sweep through `keys` at this sweep's knots, keeping its radius function r(θ, t): the
    /// same as [`Sweep::try_new`] with these knots when `keys` hold the radii this sweep was
    /// built from, in time linear in the keys whatever the radii.
    ///
    /// The caller guarantees the radii; they are not read. Fails as [`Sweep::try_new`] does on
    /// the key count (which must also be this sweep's) and on each key's center and rotation.
    pub fn try_with_axis(&self, keys: &[Key]) -> Result<Sweep, SweepError> {
        validate_count(keys)?;
        for (index, key) in keys.iter().enumerate() {
            validate_frame(index, key)?;
        }
        if keys.len() != self.knots.len() {
            return Err(SweepError::KnotCount { keys: keys.len(), found: self.knots.len() });
        }
        Ok(Sweep {
            knots: self.knots.clone(),
            segments: axis_segments(keys, &self.knots, self.rotation),
            radius: self.radius.clone(),
            rotation: self.rotation,
        })
    }

    /// Carries this sweep by a rigid motion with rotation `rotation` onto `keys`: this sweep's
    /// keys moved by that motion (radii unchanged). C(t) is linear in the centers and the
    /// natural spline commutes with rigid motions, so the moved curve interpolates the moved
    /// centers exactly (its pieces take them as end values) with its second derivatives turned
    /// by `rotation`; R(t) is rebuilt from the moved rotations and r(θ, t) is kept. Equal to
    /// [`Sweep::try_with_axis`] on `keys` up to rounding (a few ulps of C″), in place and
    /// without solving the knots' system: a few multiplications per key.
    ///
    /// Fails as [`Sweep::try_with_axis`] does, leaving the sweep as it was.
    pub fn try_move_rigidly(&mut self, keys: &[Key], rotation: DQuat) -> Result<(), SweepError> {
        validate_count(keys)?;
        for (index, key) in keys.iter().enumerate() {
            validate_frame(index, key)?;
        }
        if keys.len() != self.knots.len() {
            return Err(SweepError::KnotCount { keys: keys.len(), found: self.knots.len() });
        }
        let turned = |piece: &CurvePiece, end: fn(&CubicPiece) -> f64| {
            let [x, y, z] = &piece.axes;
            rotation * DVec3::new(end(x), end(y), end(z))
        };
        for (segment, ends) in self.segments.iter_mut().zip(keys.windows(2)) {
            let (m0, m1) = (turned(&segment.curve, |c| c.m0), turned(&segment.curve, |c| c.m1));
            let (p0, p1) = (ends[0].center, ends[1].center);
            for (c, axis) in segment.curve.axes.iter_mut().enumerate() {
                *axis = CubicPiece { y0: p0[c], y1: p1[c], m0: m0[c], m1: m1[c], h: axis.h };
            }
        }
        let segments = &mut self.segments;
        orientation::for_each_piece(
            self.rotation,
            &self.knots,
            |i| keys[i].rotation.normalize(),
            |k, piece| {
                segments[k].orientation = piece;
            },
        );
        Ok(())
    }

    /// This sweep with every radius scaled by `factor`: r(θ, t) by `factor` (`RadiusField::scaled`,
    /// equal up to rounding to the sweep built from the scaled radii), C(t) and R(t) kept.
    pub fn with_radii_scaled(&self, factor: f64) -> Sweep {
        Sweep {
            knots: self.knots.clone(),
            segments: self.segments.clone(),
            radius: Arc::new(self.radius.scaled(factor)),
            rotation: self.rotation,
        }
    }

    /// This sweep after the radii of key `key` changed by `delta` (ρ_key,j += delta\[j\]),
    /// C(t) and R(t) kept: see `RadiusField::add_to_key`,
    /// whose changed knot intervals it returns. The caller guarantees `delta` has M entries and
    /// leaves the radii valid.
    pub fn add_to_key_radii(&mut self, key: usize, delta: &[f64]) -> std::ops::Range<usize> {
        Arc::make_mut(&mut self.radius).add_to_key(&self.knots, key, delta)
    }
}
