//! Editing key cross-sections (§4, Fig. 7): moving or rotating a key relative to the previous
//! one (the keys after it follow) or on its own, and scaling its radii.

use std::f64::consts::TAU;

use glam::{DQuat, DVec3};
#[cfg(feature = "json")]
use serde::{Deserialize, Serialize};

use super::rigid::Motion;
use crate::sweep::Key;

/// How a key move affects the keys after it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(rename_all = "lowercase"))]
pub enum KeyMode {
    /// Edits the key's local transform T_{i−1,i}: keys i+1..n keep theirs, so they move with it
    /// (their T_{0,k} change).
    #[default]
    Local,
    /// Moves the key alone.
    Independent,
}

/// Rotates key `index` by `rotation` about its own center and then translates it by
/// `translation` (both in world coordinates); in [`KeyMode::Local`] the keys after it undergo
/// the same rigid motion.
pub fn move_key(keys: &mut [Key], index: usize, translation: DVec3, rotation: DQuat, mode: KeyMode) {
    let motion = Motion::about(keys[index].center, rotation, translation);
    let end = match mode {
        KeyMode::Local => keys.len(),
        KeyMode::Independent => index + 1,
    };
    for key in &mut keys[index..end] {
        motion.apply(key);
    }
}

/// Scales the radii of `key` by `factor`: all of them, or with `theta_range = Some((a, b))` (in
/// radians, counter-clockwise from a to b, wrapping through 2π if b < a) a smooth bump that is
/// `factor` in the middle of the range and falls off as a raised cosine to 1 at its ends, for a
/// local deformation (Fig. 7c, Fig. 15).
pub fn scale_radii(key: &mut Key, factor: f64, theta_range: Option<(f64, f64)>) {
    let m = key.radii.len();
    for (j, radius) in key.radii.iter_mut().enumerate() {
        let weight = match theta_range {
            None => 1.0,
            Some((a, b)) => {
                let width = (b - a).rem_euclid(TAU);
                let offset = (TAU * j as f64 / m as f64 - a).rem_euclid(TAU);
                if width == 0.0 || offset > width { 0.0 } else { 0.5 - 0.5 * (TAU * offset / width).cos() }
            }
        };
        *radius *= 1.0 + (factor - 1.0) * weight;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column() -> Vec<Key> {
        (0..4).map(|i| Key::circle(DVec3::new(0.0, 0.0, i as f64), DQuat::IDENTITY, 1.0, 8)).collect()
    }

    #[test]
    fn local_move_carries_the_later_keys_rigidly() {
        let mut keys = column();
        move_key(&mut keys, 1, DVec3::X, DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2), KeyMode::Local);
        assert_eq!(keys[0], column()[0]);
        assert!(keys[1].center.distance(DVec3::new(1.0, 0.0, 1.0)) < 1e-15);
        // Key 3 was 2 above key 1; turned a quarter about y it now lies 2 along +x.
        assert!(keys[3].center.distance(DVec3::new(3.0, 0.0, 1.0)) < 1e-14, "{}", keys[3].center);
        assert!((keys[3].rotation * DVec3::Z - DVec3::X).length() < 1e-15);
    }

    #[test]
    fn independent_move_leaves_the_others() {
        let mut keys = column();
        move_key(&mut keys, 2, DVec3::Y, DQuat::IDENTITY, KeyMode::Independent);
        assert_eq!(keys[3], column()[3]);
        assert_eq!(keys[2].center, DVec3::new(0.0, 1.0, 2.0));
    }

    #[test]
    fn ranged_scaling_peaks_in_the_middle_and_leaves_the_rest() {
        let mut key = Key::circle(DVec3::ZERO, DQuat::IDENTITY, 1.0, 8);
        scale_radii(&mut key, 2.0, Some((0.0, std::f64::consts::PI)));
        assert_eq!(key.radii[2], 2.0, "θ = π/2 is the middle of the range");
        assert!(key.radii[1] > 1.0 && key.radii[1] < 2.0);
        assert_eq!(key.radii[0], 1.0);
        assert!(key.radii[5..].iter().all(|&r| r == 1.0));
    }

    #[test]
    fn range_may_wrap_through_zero() {
        let mut key = Key::circle(DVec3::ZERO, DQuat::IDENTITY, 1.0, 8);
        scale_radii(&mut key, 0.5, Some((1.5 * std::f64::consts::PI, 0.5 * std::f64::consts::PI)));
        assert_eq!(key.radii[0], 0.5, "θ = 0 is the middle of the wrapped range");
        assert_eq!(key.radii[4], 1.0);
    }
}
