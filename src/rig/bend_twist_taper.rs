//! Bending, twisting and tapering a sweep by editing its keys (§4, Fig. 7): the demo's pose, the
//! tests' standard deformation and the pose the engine probes the Jacobian normals' reach with
//! ([`crate::normals::jacobian_reach`]).

use glam::{DQuat, DVec3};

use super::Rig;
use crate::sweep::Key;

/// A pose of a whole rig that bends, twists and tapers every sweep along its knots.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BendTwistTaper {
    /// Total bend angle in radians, spread over the sweep in proportion to the knots, about the
    /// first key's local x axis.
    pub bend: f64,
    /// Total twist angle in radians about the sweep's own axis, growing linearly with t.
    pub twist: f64,
    /// Radius scale at the last key (1 = none), growing linearly with t from 1 at the first.
    pub taper: f64,
}

impl BendTwistTaper {
    /// The posed keys of `rig`'s sweeps, each key transformed relative to the previous one
    /// (bend), about its own normal (twist) and in its radii (taper).
    pub fn keys(&self, rig: &Rig) -> Vec<Vec<Key>> {
        rig.sweeps().iter().zip(rig.rest()).map(|(sweep, rest)| self.sweep_keys(&sweep.keys, rest.knots())).collect()
    }

    /// The posed keys of one sweep's `keys` at its `knots`, as [`BendTwistTaper::keys`] poses
    /// each sweep of a rig.
    pub fn sweep_keys(&self, keys: &[Key], knots: &[f64]) -> Vec<Key> {
        let axis = keys[0].rotation.normalize() * DVec3::X;
        let mut posed: Vec<Key> = Vec::with_capacity(keys.len());
        for (i, (key, &u)) in keys.iter().zip(knots).enumerate() {
            let bend = DQuat::from_axis_angle(axis, self.bend * u);
            let center = match i {
                0 => key.center,
                _ => {
                    // The chord from the previous key, turned by the bend at the chord's middle.
                    let middle = DQuat::from_axis_angle(axis, self.bend * 0.5 * (u + knots[i - 1]));
                    posed[i - 1].center + middle * (key.center - keys[i - 1].center)
                }
            };
            let rotation = bend * key.rotation.normalize() * DQuat::from_rotation_z(self.twist * u);
            let scale = 1.0 + (self.taper - 1.0) * u;
            posed.push(Key { center, rotation, radii: key.radii.iter().map(|r| r * scale).collect() });
        }
        posed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::{Tube, tube_rig};

    #[test]
    fn identity_parameters_reproduce_the_rest_keys() {
        let rig = tube_rig(&Tube { rings: 3, around: 8, length: 2.0, radius: 0.3 }, 5, 8);
        let keys = BendTwistTaper { bend: 0.0, twist: 0.0, taper: 1.0 }.keys(&rig);
        assert_eq!(keys[0], rig.sweeps()[0].keys);
    }

    #[test]
    fn quarter_bend_turns_the_last_key_a_quarter() {
        let rig = tube_rig(&Tube { rings: 3, around: 8, length: 2.0, radius: 0.3 }, 9, 8);
        let keys = BendTwistTaper { bend: std::f64::consts::FRAC_PI_2, twist: 0.0, taper: 0.5 }.keys(&rig);
        let last = &keys[0][8];
        let normal = last.rotation * DVec3::Z;
        assert!((normal - DVec3::new(0.0, -1.0, 0.0)).length() < 1e-12, "{normal}");
        assert!((last.radii[0] - 0.15).abs() < 1e-15);
    }
}
