//! Which end of a fitted sweep is attached to the rest of the mesh, and the same sweep
//! traversed from its other end, so that key 0 can sit where the part is attached (a leg's
//! hip, an ear's base) and the free end (a foot, an ear's tip) is the last key.
//!
//! The attached end is the one nearer which the part's rim ([`Part::rim`]) is longer: each
//! rim edge counts its length towards the end of the sweep nearer its parameter t, the mean
//! of the t of its two vertices bound to the sweep. A leg cut at hip and ankle is attached at
//! the hip, whose loop is the longer.

use std::f64::consts::PI;

use glam::DQuat;

use super::part::Part;
use super::quality::measure;
use super::refine::Fitted;
use super::{Fit, FitError, FitStep};
use crate::bind::SweepBinder;
use crate::sweep::{Key, Sweep};

/// The total length of the part's rim edges nearer the first key (mean t < ½) and nearer the
/// last key (mean t > ½); an edge at t = ½ exactly counts towards neither. `[0, 0]` for a
/// part with no rim.
pub fn rim_lengths(part: &Part, sweep: &Sweep) -> [f64; 2] {
    let binder = SweepBinder::new(sweep);
    let t = |v: u32| binder.bind(part.positions[v as usize]).t;
    let mut lengths = [0.0, 0.0];
    for &[a, b] in &part.rim {
        let length = part.positions[a as usize].distance(part.positions[b as usize]);
        let middle = 0.5 * (t(a) + t(b));
        if middle < 0.5 {
            lengths[0] += length;
        } else if middle > 0.5 {
            lengths[1] += length;
        }
    }
    lengths
}

/// The keys of the same sweep surface traversed from the other end: key i′ = key n − i, its
/// frame turned by π about its local x axis (q′ = q·R_x(π): x stays, y and the normal N flip,
/// so N still points along increasing t), and its radii re-indexed ρ′_j = ρ_{(M−j) mod M}
/// (the ray at θ′_j = 2πj/M in the turned frame is the ray at −θ_j in the old one).
///
/// Chord-length knots become u′_i = 1 − u_{n−i}. The natural spline of the centers, the
/// radius spline (natural in t, periodic in θ) and the nlerp of the rotations (a common unit
/// factor on the right commutes with nlerp and keeps q_i · q_{i+1}) are all unchanged by the
/// reversal, so the surface is the same: S′(θ, t) = S(−θ, 1 − t), and so is every vertex's
/// |d|.
pub fn reversed(keys: &[Key]) -> Vec<Key> {
    let turn = DQuat::from_rotation_x(PI);
    keys.iter()
        .rev()
        .map(|key| {
            let m = key.radii.len();
            Key {
                center: key.center,
                rotation: key.rotation * turn,
                radii: (0..m).map(|j| key.radii[(m - j) % m]).collect(),
            }
        })
        .collect()
}

/// The fit traversed from its other end ([`reversed`]): keys and sections in reverse order,
/// the part measured again on the turned sweep, and every step's keys reversed as well (their
/// quality stays: each is the same surface).
pub(super) fn turned(part: &Part, fitted: &Fitted, steps: &mut [FitStep]) -> Result<Fitted, FitError> {
    let keys = reversed(&fitted.keys);
    let sweep = Sweep::try_new(&keys, None)?;
    let measured = measure(&sweep, &part.positions);
    let sections = fitted.sections.iter().rev().copied().collect();
    for step in steps {
        step.keys = reversed(&step.keys);
    }
    Ok(Fitted { keys, sections, sweep, measured })
}

impl Fit {
    /// The same fit traversed from its other end ([`reversed`]): keys, sections and every
    /// step's keys in reverse order, the rim lengths swapped. Its quality stays: every vertex's
    /// |d| on the same surface is the same.
    pub(super) fn reversed(&self) -> Fit {
        let steps = self
            .steps
            .iter()
            .map(|step| FitStep { keys: reversed(&step.keys), ..step.clone() })
            .collect();
        Fit {
            keys: reversed(&self.keys),
            quality: self.quality,
            sections: self.sections.iter().rev().copied().collect(),
            steps,
            rim: [self.rim[1], self.rim[0]],
            falloff: self.falloff,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use glam::DVec3;

    use super::*;
    use crate::fit::frames::transported_frames;

    /// A bent sweep of four keys with radii that differ around and along it.
    fn bent_keys() -> Vec<Key> {
        let centers = [DVec3::ZERO, DVec3::new(0.3, 0.1, 1.0), DVec3::new(1.1, 0.2, 1.8), DVec3::new(2.0, 0.0, 2.1)];
        let normals: Vec<DVec3> =
            (0..4).map(|i| (centers[(i + 1).min(3)] - centers[i.saturating_sub(1)]).normalize()).collect();
        transported_frames(&normals, None)
            .into_iter()
            .zip(centers)
            .enumerate()
            .map(|(i, (rotation, center))| {
                let radii = (0..12)
                    .map(|j| 0.3 + 0.05 * i as f64 + 0.1 * (TAU * j as f64 / 12.0 + 0.4).sin().max(0.0))
                    .collect();
                Key { center, rotation, radii }
            })
            .collect()
    }

    #[test]
    fn a_reversed_sweep_is_the_same_surface_traversed_backwards() {
        let keys = bent_keys();
        let sweep = Sweep::try_new(&keys, None).unwrap();
        let turned = Sweep::try_new(&reversed(&keys), None).unwrap();
        let mut worst = 0.0f64;
        for a in 0..24 {
            for b in 0..=20 {
                let (theta, t) = (TAU * a as f64 / 24.0, b as f64 / 20.0);
                let here = sweep.surface_point(theta, t);
                worst = worst.max(here.distance(turned.surface_point(TAU - theta, 1.0 - t)));
            }
        }
        assert!(worst < 1e-12, "surfaces differ by {worst:.3e}");
        for b in 0..=20 {
            let t = b as f64 / 20.0;
            let (n, n_turned) = (sweep.normal(t), turned.normal(1.0 - t));
            assert!((n + n_turned).length() < 1e-12, "t = {t}: N {n} but reversed N {n_turned}");
            assert!(sweep.center_derivative(t).dot(n) > 0.0 && turned.center_derivative(1.0 - t).dot(n_turned) > 0.0);
        }
    }

    #[test]
    fn reversing_twice_gives_the_keys_back() {
        let keys = bent_keys();
        let twice = reversed(&reversed(&keys));
        for (key, back) in keys.iter().zip(&twice) {
            assert_eq!(key.center, back.center);
            assert_eq!(key.radii, back.radii);
            // R_x(2π) = −1: the same rotation.
            assert!(
                (key.rotation * DVec3::new(0.3, -0.7, 0.5) - back.rotation * DVec3::new(0.3, -0.7, 0.5)).length()
                    < 1e-15
            );
        }
        let frames: Vec<DQuat> = reversed(&keys).iter().map(|k| k.rotation).collect();
        assert!(frames.windows(2).all(|w| w[0].dot(w[1]) > 0.0), "neighbouring frames stay sign-aligned");
    }
}
