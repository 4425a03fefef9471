//! What an edit changed in a pose's keys, so that a failing edit can be undone: the frames of
//! every key, and the radii of the keys whose radii it changed.
//!
//! An edit moves keys of many sweeps (the hierarchy carries children, §5) but changes radii
//! rarely: a `scale_radii` edit changes one key's, and a volume rule (§5) multiplies whole
//! sweeps only once it has converged and the pose has been checked. So instead of copying the
//! whole pose before an edit (every radius of every sweep), the edit works on the pose in place
//! and the journal records seven numbers per key plus the radii it is told are about to change.
//! Its storage is kept from edit to edit.

use glam::{DQuat, DVec3};

use crate::sweep::Key;

/// The state of a pose before an edit, as much as the edit may change.
#[derive(Clone, Debug, Default)]
pub struct Journal {
    /// The centers and rotations of every key of every sweep.
    frames: Vec<Vec<(DVec3, DQuat)>>,
    /// (sweep, key, radii before), in the order they were saved.
    radii: Vec<(usize, usize, Vec<f64>)>,
}

impl Journal {
    /// Starts a journal of `keys`: records every frame, and forgets the radii saved before.
    pub fn begin(&mut self, keys: &[Vec<Key>]) {
        self.frames.resize_with(keys.len(), Vec::new);
        for (frames, keys) in self.frames.iter_mut().zip(keys) {
            frames.clear();
            frames.extend(keys.iter().map(|key| (key.center, key.rotation)));
        }
        self.radii.clear();
    }

    /// Records the radii of key `key` of sweep `sweep` before they change.
    pub fn save_key_radii(&mut self, keys: &[Vec<Key>], sweep: usize, key: usize) {
        self.radii.push((sweep, key, keys[sweep][key].radii.clone()));
    }

    /// Records the radii of every key of sweep `sweep` before they change.
    pub fn save_sweep_radii(&mut self, keys: &[Vec<Key>], sweep: usize) {
        for key in 0..keys[sweep].len() {
            self.save_key_radii(keys, sweep, key);
        }
    }

    /// Puts `keys` back as they were at [`Journal::begin`], given that only the radii saved
    /// since have changed.
    pub fn restore(&mut self, keys: &mut [Vec<Key>]) {
        for (sweep, key, radii) in self.radii.drain(..).rev() {
            keys[sweep][key].radii = radii;
        }
        for (frames, keys) in self.frames.iter().zip(keys.iter_mut()) {
            for (&(center, rotation), key) in frames.iter().zip(keys.iter_mut()) {
                (key.center, key.rotation) = (center, rotation);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(x: f64, r: f64) -> Key {
        Key { center: DVec3::new(x, 0.0, 0.0), rotation: DQuat::IDENTITY, radii: vec![r; 3] }
    }

    #[test]
    fn restore_undoes_frames_and_the_saved_radii() {
        let before = vec![vec![key(0.0, 1.0), key(1.0, 2.0)], vec![key(5.0, 3.0), key(6.0, 3.0)]];
        let mut keys = before.clone();
        let mut journal = Journal::default();
        journal.begin(&keys);
        journal.save_key_radii(&keys, 0, 1);
        keys[0][1].radii[2] = 9.0;
        journal.save_sweep_radii(&keys, 1);
        keys[1].iter_mut().for_each(|key| key.radii.iter_mut().for_each(|r| *r *= 0.5));
        keys[1][0].center.y = 4.0;
        keys[0][0].rotation = DQuat::from_rotation_z(1.0);
        journal.restore(&mut keys);
        assert_eq!(keys, before);
    }

    #[test]
    fn a_key_saved_twice_gets_its_first_radii_back() {
        let before = vec![vec![key(0.0, 1.0), key(1.0, 1.0)]];
        let mut keys = before.clone();
        let mut journal = Journal::default();
        journal.begin(&keys);
        journal.save_key_radii(&keys, 0, 0);
        keys[0][0].radii[0] = 2.0;
        journal.save_key_radii(&keys, 0, 0);
        keys[0][0].radii[0] = 3.0;
        journal.restore(&mut keys);
        assert_eq!(keys, before);
    }
}
