//! The posed sweeps of the keys being edited, kept between the rebuilds of an edit: a memo, so
//! that its results are exactly those of building every sweep afresh.
//!
//! The controls (§4), the hierarchy (§5) and the volume rules rebuild a sweep after every step,
//! and most steps move keys rigidly. A kept sweep whose keys still have the radii it was built
//! from is rebuilt by [`Sweep::try_with_axis`] (C(t) and R(t) only, linear in the keys), and
//! its volume (Eq. 1) reuses the area polynomials A(t), so such a step costs time independent
//! of the number of radii, beyond comparing them.
//!
//! A volume rule rescales whole sweeps: there the kept r(θ, t) and A(t) are scaled instead of
//! rebuilt ([`Shape::scale_radii`]), exact up to rounding, and the volume of Eq. 1 scales with A.
//! Such a sweep is rebuilt from its keys after [`MAX_SCALED`] scalings, so the rounding it
//! carries stays under 10⁻¹³ relative.

use crate::sweep::radius::AreaPolynomial;
use crate::sweep::{Key, Sweep, SweepError};

/// One sweep's memo.
#[derive(Clone, Debug, Default)]
pub struct Shape {
    kept: Option<Kept>,
}

#[derive(Clone, Debug)]
struct Kept {
    /// The keys the sweep was built from.
    keys: Vec<Key>,
    sweep: Sweep,
    areas: Option<Vec<AreaPolynomial>>,
    volume: Option<f64>,
    /// How many [`Shape::scale_radii`] the radius function carries since it was built.
    scaled: usize,
}

/// The most scalings of a kept radius function before it is rebuilt: each adds a rounding of
/// about 1 ulp (1.1·10⁻¹⁶) relative to r and A, so 64 stay under 10⁻¹⁴, and the rebuild costs
/// 1/64 of one per scaling.
const MAX_SCALED: usize = 64;

impl Shape {
    /// The sweep through `keys` at `knots`, as [`Sweep::try_new`] builds it. A memo is for one
    /// sweep: `knots` must be the same on every call.
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

    fn update(&mut self, keys: &[Key], knots: &[f64]) -> Result<&mut Kept, SweepError> {
        let (same_frames, same_radii) = match &self.kept {
            Some(kept) => (same_frames(&kept.keys, keys), same_radii(&kept.keys, keys)),
            None => (false, false),
        };
        if !(same_frames && same_radii) {
            let rebuilt = match &self.kept {
                Some(kept) if same_radii => kept.sweep.try_with_axis(keys),
                _ => Sweep::try_new(keys, Some(knots)),
            };
            let rebuilt = rebuilt.inspect_err(|_| self.kept = None)?;
            let (areas, scaled) = match self.kept.take() {
                Some(kept) if same_radii => (kept.areas, kept.scaled),
                _ => (None, 0),
            };
            self.kept = Some(Kept { keys: keys.to_vec(), sweep: rebuilt, areas, volume: None, scaled });
        }
        Ok(self.kept.as_mut().expect("kept above"))
    }
}

impl Shape {
    /// Notes that `keys` are the kept keys with every radius multiplied by `factor` (a volume
    /// rule's uniform rescale, §5): r(θ, t) is scaled by `factor`, and A(t) and the volume (Eq. 1)
    /// by factor², in time linear in the radii but without solving the splines again. Forgets the sweep instead when `keys` are not that, when the scaled
    /// radii are invalid (so that rebuilding reports them), or after [`MAX_SCALED`] scalings.
    pub fn scale_radii(&mut self, keys: &[Key], factor: f64) {
        let Some(kept) = &mut self.kept else { return };
        let scaled_by = |a: &Key, b: &Key| {
            a.radii.len() == b.radii.len()
                && a.radii.iter().zip(&b.radii).all(|(x, y)| (x * factor).to_bits() == y.to_bits())
        };
        let follows = kept.keys.len() == keys.len()
            && same_frames(&kept.keys, keys)
            && kept.keys.iter().zip(keys).all(|(a, b)| scaled_by(a, b));
        if !follows || kept.scaled + 1 >= MAX_SCALED || Sweep::validate(keys).is_err() {
            self.kept = None;
            return;
        }
        kept.sweep = kept.sweep.with_radii_scaled(factor);
        kept.areas = kept.areas.take().map(|areas| areas.iter().map(|area| area.scaled(factor)).collect());
        // Eq. 1 is linear in A, and A scales by factor²: the volume does (up to rounding, and
        // the quadrature's 1e-12, whose subdivision the scaling leaves alone).
        kept.volume = kept.volume.map(|volume| volume * (factor * factor));
        kept.scaled += 1;
        for (kept, key) in kept.keys.iter_mut().zip(keys) {
            kept.radii.copy_from_slice(&key.radii);
        }
    }
}

/// Whether `a` and `b` have the same centers and rotations, bit for bit (so that a rebuilt
/// sweep would be bit for bit the kept one).
fn same_frames(a: &[Key], b: &[Key]) -> bool {
    let bits = |key: &Key| {
        let [x, y, z] = key.center.to_array();
        let [qx, qy, qz, qw] = key.rotation.to_array();
        [x, y, z, qx, qy, qz, qw].map(f64::to_bits)
    };
    a.len() == b.len() && a.iter().zip(b).all(|(a, b)| bits(a) == bits(b))
}

/// Whether `a` and `b` have the same radii, bit for bit.
fn same_radii(a: &[Key], b: &[Key]) -> bool {
    let same = |a: &[f64], b: &[f64]| a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
    a.len() == b.len() && a.iter().zip(b).all(|(a, b)| same(&a.radii, &b.radii))
}

/// The memos of every sweep of a rig.
pub type Shapes = Vec<Shape>;
