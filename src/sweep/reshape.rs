//! Rebuilding a sweep after a rigid edit of its keys (§4): moving or turning key cross-sections
//! changes C(t) and R(t) only, so the radius function r(θ, t) — the costly part, one bicubic
//! patch per radius — is kept.

use std::sync::Arc;

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
        Ok(Sweep { knots: self.knots.clone(), segments: axis_segments(keys, &self.knots), radius: self.radius.clone() })
    }

    /// This sweep with every radius scaled by `factor`: r(θ, t) by `factor` ([`RadiusField::scaled`](super::radius::RadiusField::scaled),
    /// equal up to rounding to the sweep built from the scaled radii), C(t) and R(t) kept.
    pub fn with_radii_scaled(&self, factor: f64) -> Sweep {
        Sweep {
            knots: self.knots.clone(),
            segments: self.segments.clone(),
            radius: Arc::new(self.radius.scaled(factor)),
        }
    }

    /// This sweep after the radii of key `key` changed by `delta` (ρ_key,j += delta\[j\]),
    /// C(t) and R(t) kept: see [`RadiusField::add_to_key`](super::radius::RadiusField::add_to_key),
    /// whose changed knot intervals it returns. The caller guarantees `delta` has M entries and
    /// leaves the radii valid.
    pub fn add_to_key_radii(&mut self, key: usize, delta: &[f64]) -> std::ops::Range<usize> {
        Arc::make_mut(&mut self.radius).add_to_key(&self.knots, key, delta)
    }
}
