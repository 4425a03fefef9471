//! The posed sweeps of the keys being edited, kept between the rebuilds of an edit: a memo, so
//! that its results are exactly those of building every sweep afresh.
//!
//! The controls (§4), the hierarchy (§5) and the volume rules rebuild a sweep after every step,
//! and most steps move keys rigidly. A kept sweep whose keys still have the radii it was built
//! from is rebuilt by [`Sweep::try_with_axis`] (C(t) and R(t) only, linear in the keys), and
//! its volume (Eq. 1) reuses the area polynomials A(t), so such a step costs time independent
//! of the number of radii, beyond comparing them.

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
}

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
            let areas = if same_radii { self.kept.take().and_then(|kept| kept.areas) } else { None };
            self.kept = Some(Kept { keys: keys.to_vec(), sweep: rebuilt, areas, volume: None });
        }
        Ok(self.kept.as_mut().expect("kept above"))
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
