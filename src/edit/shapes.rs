//! The posed sweeps of the keys being edited, kept between the rebuilds of an edit: a memo, so
//! that its results are those of building every sweep afresh (bit for bit after moves of some
//! keys, up to rounding after rescales and after moves of a whole sweep).
//!
//! The controls (§4), the hierarchy (§5) and the volume rules rebuild a sweep after every step,
//! and most steps move keys rigidly. A kept sweep whose keys moved is rebuilt by
//! [`Sweep::try_with_axis`] (C(t) and R(t) only, linear in the keys), and its volume (Eq. 1)
//! reuses the area polynomials A(t), so such a step costs time independent of the number of
//! radii. A sweep carried whole by its parent (§5) is not even rebuilt: its C(t) and R(t) are
//! moved with it ([`Sweep::try_move_rigidly`]), and rebuilt from its keys after
//! [`MAX_SCALED`] such moves, so that it stays within a few ulps of the rebuilt one.
//!
//! The memo compares the keys' frames (centers and rotations), not their radii: whoever
//! changes radii says so, by [`Shape::forget`], [`Shape::change_key_radii`] or
//! [`Shape::scale_radii`]. Within `edit` the radii change in two places only: a `scale_radii`
//! edit (one key's radii, added to r(θ, t) in place on the knot intervals it reaches) and a
//! volume rule's rescale.
//!
//! A volume rule rescales whole sweeps: there the kept r(θ, t) and A(t) are scaled instead of
//! rebuilt ([`Shape::scale_radii`]), in time independent of the radii (r keeps one factor,
//! [`RadiusField::scaled`](crate::sweep::radius::RadiusField::scaled)), and the volume of Eq. 1
//! scales with A. Such a sweep is rebuilt from its keys after [`MAX_SCALED`] scalings (or changes of one key), so that
//! it stays within 10⁻¹³ relative of the keys' radii, which are rounded at every rescale.

use glam::{DQuat, DVec3};

use super::rigid::Motion;
use crate::limits::MAX_RIG_COORDINATE;
use crate::sweep::radius::AreaPolynomial;
use crate::sweep::{Key, RotationInterpolation, Sweep, SweepError};

/// One sweep's memo.
#[derive(Clone, Debug, Default)]
pub struct Shape {
    kept: Option<Kept>,
    /// The rotation interpolation of the sweeps it builds.
    rotation: RotationInterpolation,
}

#[derive(Clone, Debug)]
struct Kept {
    /// The frames of the keys the sweep was built from.
    frames: Vec<(DVec3, DQuat)>,
    sweep: Sweep,
    areas: Option<Vec<AreaPolynomial>>,
    volume: Option<f64>,
    /// How many [`Shape::scale_radii`] the radius function carries since it was built.
    scaled: usize,
    /// How many [`Shape::move_rigidly`] C(t) carries since it was last built from the keys.
    moved: usize,
    /// The largest radius of the keys, scaled with them.
    largest: f64,
}

/// The most scalings of a kept radius function before it is rebuilt: each rounds the keys'
/// radii, and the field's one factor, by at most ½ ulp (1.1·10⁻¹⁶) relative, so 512 keep the
/// two within 10⁻¹³ of each other, and the rebuild costs 1/512 of one per scaling.
const MAX_SCALED: usize = 512;

impl Shape {
    /// An empty memo for a sweep with rotation interpolation `rotation`.
    pub fn new(rotation: RotationInterpolation) -> Shape {
        Shape { kept: None, rotation }
    }

    /// An empty memo for sweeps like `sweep` (its rotation interpolation).
    pub fn like(sweep: &Sweep) -> Shape {
        Shape::new(sweep.rotation_interpolation())
    }

    /// The sweep through `keys` at `knots`, as [`Sweep::try_new_with`] builds it with the memo's
    /// rotation interpolation. A memo is for one
    /// sweep: `knots` must be the same on every call, and `keys` must have the radii of the
    /// last call unless the memo was told otherwise.
    pub fn sweep(&mut self, keys: &[Key], knots: &[f64]) -> Result<&Sweep, SweepError> {
        Ok(&self.update(keys, knots)?.sweep)
    }

    /// Its volume, [`Sweep::volume`].
    pub fn volume(&mut self, keys: &[Key], knots: &[f64]) -> Result<f64, SweepError> {
        let kept = self.update(keys, knots)?;
        if kept.volume.is_none() {
            let areas = kept.areas.get_or_insert_with(|| kept.sweep.area_polynomials());
            kept.volume = Some(kept.sweep.volume_with_areas(areas));
        }
        Ok(kept.volume.expect("set above"))
    }

    /// The memo of `sweep`, which is the sweep [`Sweep::try_new_with`] builds through `keys` at its
    /// knots (e.g. a rig's rest sweep and its rest keys): nothing is rebuilt.
    pub fn of(sweep: &Sweep, keys: &[Key]) -> Shape {
        let kept = Kept {
            frames: frames(keys),
            sweep: sweep.clone(),
            areas: None,
            volume: None,
            scaled: 0,
            moved: 0,
            largest: largest_radius(keys),
        };
        Shape { kept: Some(kept), rotation: sweep.rotation_interpolation() }
    }

    /// Forgets the sweep: the keys' radii changed, so the next call rebuilds it from them.
    pub fn forget(&mut self) {
        self.kept = None;
    }

    /// Whether a sweep is kept: then the keys' radii are those it was built from (or scaled
    /// to), which were valid, and only their frames need checking.
    pub fn checked_radii(&self) -> bool {
        self.kept.is_some()
    }

    /// An upper bound on the radii of the keys of the kept sweep, scaled with it by
    /// [`Shape::scale_radii`] (so including factors the caller has deferred); `None` when no
    /// sweep is kept.
    pub fn largest_radius(&self) -> Option<f64> {
        self.kept.as_ref().map(|kept| kept.largest)
    }

    fn update(&mut self, keys: &[Key], knots: &[f64]) -> Result<&mut Kept, SweepError> {
        let same_frames = self.kept.as_ref().is_some_and(|kept| same_frames(&kept.frames, keys));
        if !same_frames {
            let rebuilt = match &self.kept {
                Some(kept) => kept.sweep.try_with_axis(keys),
                None => Sweep::try_new_with(keys, Some(knots), self.rotation),
            };
            let rebuilt = rebuilt.inspect_err(|_| self.kept = None)?;
            let (areas, scaled, largest) = match self.kept.take() {
                Some(kept) => (kept.areas, kept.scaled, kept.largest),
                None => (None, 0, largest_radius(keys)),
            };
            self.kept =
                Some(Kept { frames: frames(keys), sweep: rebuilt, areas, volume: None, scaled, moved: 0, largest });
        }
        Ok(self.kept.as_mut().expect("kept above"))
    }

    /// Moves every key of `keys` by `motion` (radii unchanged). When the memo holds the sweep of
    /// `keys` before the move, it moves C(t) and R(t) with them ([`Sweep::try_move_rigidly`],
    /// no system solved; rebuilt from the keys every [`MAX_SCALED`] moves) and keeps the
    /// volume: Eq. 1 is invariant under a rigid motion of the whole sweep (A(t) is unchanged,
    /// N(t) and C′(t) turn together), so a child carried by its parent (§5) costs no
    /// quadrature. The kept volume differs from one integrated afresh by the quadrature's
    /// error, under 10⁻¹².
    pub fn move_rigidly(&mut self, keys: &mut [Key], motion: &Motion) {
        let before = self.kept.as_ref().is_some_and(|kept| same_frames(&kept.frames, keys));
        for key in keys.iter_mut() {
            motion.apply(key);
        }
        let Some(kept) = self.kept.as_mut().filter(|_| before) else { return };
        let rebuild = kept.moved + 1 >= MAX_SCALED;
        let moved = if rebuild {
            kept.sweep.try_with_axis(keys).map(|sweep| kept.sweep = sweep)
        } else {
            kept.sweep.try_move_rigidly(keys, motion.rotation)
        };
        match moved {
            Ok(()) => {
                for (frame, key) in kept.frames.iter_mut().zip(keys.iter()) {
                    *frame = (key.center, key.rotation);
                }
                kept.moved = if rebuild { 0 } else { kept.moved + 1 };
            }
            // The caller's check of the frames reports it.
            Err(_) => self.kept = None,
        }
    }

    /// Scales the kept sweep as if every radius of its keys were multiplied by `factor` (a
    /// volume rule's uniform rescale, §5): r(θ, t) by `factor`, and A(t) and the volume (Eq. 1)
    /// by factor², in time linear in the keys. Returns whether it did; then the caller may
    /// defer multiplying the keys' radii (several factors into one pass), provided it does so
    /// before the memo is asked to rebuild from them.
    ///
    /// Returns false, forgetting the sweep, when none is kept, after [`MAX_SCALED`] scalings,
    /// or when the largest radius would exceed [`MAX_RIG_COORDINATE`]: the caller scales the
    /// keys now, and the rebuild reports radii out of range.
    #[must_use = "when false the caller must scale the keys' radii itself"]
    pub fn scale_radii(&mut self, factor: f64) -> bool {
        let Some(kept) = &mut self.kept else { return false };
        let largest = kept.largest * factor;
        if kept.scaled + 1 >= MAX_SCALED || largest.is_nan() || largest > MAX_RIG_COORDINATE {
            self.kept = None;
            return false;
        }
        kept.sweep = kept.sweep.with_radii_scaled(factor);
        kept.areas = kept.areas.take().map(|areas| areas.iter().map(|area| area.scaled(factor)).collect());
        // Eq. 1 is linear in A, and A scales by factor²: the volume does (up to rounding, and
        // the quadrature's 1e-12, whose subdivision the scaling leaves alone).
        kept.volume = kept.volume.map(|volume| volume * (factor * factor));
        kept.largest *= factor;
        kept.scaled += 1;
        true
    }

    /// Notes that the radii of key `key` of `keys` changed from `before` (a `scale_radii`
    /// edit): r(θ, t) takes the change in place ([`Sweep::add_to_key_radii`]), on the knot
    /// intervals it reaches only, and A(t) is recomputed there, in time proportional to the
    /// radii of about 30 keys rather than all. Forgets the sweep instead when the new radii are
    /// not valid (so that rebuilding reports them) or after [`MAX_SCALED`] changes.
    pub fn change_key_radii(&mut self, keys: &[Key], key: usize, before: &[f64]) {
        let Some(kept) = &mut self.kept else { return };
        let radii = &keys[key].radii;
        let valid = radii.iter().all(|&r| r.is_finite() && (0.0..=MAX_RIG_COORDINATE).contains(&r));
        if !valid || radii.len() != before.len() || kept.scaled + 1 >= MAX_SCALED {
            self.kept = None;
            return;
        }
        let delta: Vec<f64> = radii.iter().zip(before).map(|(after, before)| after - before).collect();
        let changed = kept.sweep.add_to_key_radii(key, &delta);
        if let Some(areas) = &mut kept.areas {
            for k in changed {
                areas[k] = AreaPolynomial::new(kept.sweep.radius_field(), k);
            }
        }
        kept.volume = None;
        kept.largest = kept.largest.max(largest_radius(&keys[key..=key]));
        kept.scaled += 1;
    }
}

fn largest_radius(keys: &[Key]) -> f64 {
    keys.iter().flat_map(|key| &key.radii).fold(0.0, |largest, &r| largest.max(r))
}

fn frames(keys: &[Key]) -> Vec<(DVec3, DQuat)> {
    keys.iter().map(|key| (key.center, key.rotation)).collect()
}

/// Whether `keys` have the centers and rotations `frames`, bit for bit (so that a rebuilt
/// sweep would be bit for bit the kept one).
fn same_frames(frames: &[(DVec3, DQuat)], keys: &[Key]) -> bool {
    // Element by element: comparing arrays of bits calls memcmp, which costs more than the
    // comparison itself on seven words.
    let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
    frames.len() == keys.len()
        && frames.iter().zip(keys).all(|(&(center, rotation), key)| {
            same(center.x, key.center.x)
                && same(center.y, key.center.y)
                && same(center.z, key.center.z)
                && same(rotation.x, key.rotation.x)
                && same(rotation.y, key.rotation.y)
                && same(rotation.z, key.rotation.z)
                && same(rotation.w, key.rotation.w)
        })
}

/// The memos of every sweep of a rig.
pub type Shapes = Vec<Shape>;
