//! Keeping a sweep's length through an edit, as Maya's Keep Length and Blender's non-stretching
//! curve deform do: after the edit, the keys are moved along the new spine so that each chord
//! between neighbouring key centers has its rest length, and with them the spine's chord
//! length Σ |c_{i+1} − c_i|. Stretching, the paper's behaviour, stays the default.

use glam::DVec3;

use crate::sweep::Key;

/// Moves `keys` so that every chord |c_{i+1} − c_i| is `rest`'s (the same number of keys): key 0
/// stays where it is (the end where a limb is attached), and from key 1 on each key is put at
/// its rest distance from the one before along the direction between them after the edit, the
/// keys after it translated with it, so the frames and the directions of the chords are the
/// edit's. Where the edit brought two centers together, the chord runs along the earlier key's
/// normal.
pub fn keep_chord_lengths(keys: &mut [Key], rest: &[Key]) {
    for i in 1..keys.len().min(rest.len()) {
        let length = rest[i].center.distance(rest[i - 1].center);
        let chord = keys[i].center - keys[i - 1].center;
        let direction = chord.try_normalize().unwrap_or_else(|| keys[i - 1].rotation.normalize() * DVec3::Z);
        let shift = direction * length - chord;
        for key in &mut keys[i..] {
            key.center += shift;
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DQuat;

    use super::*;
    use crate::edit::keys::{KeyMode, move_key};
    use crate::sweep::chord_length;

    fn column() -> Vec<Key> {
        (0..5).map(|i| Key::circle(DVec3::new(0.0, 0.0, i as f64 * 0.5), DQuat::IDENTITY, 0.1, 8)).collect()
    }

    #[test]
    fn a_stretched_sweep_gets_its_length_back_along_its_new_direction() {
        let rest = column();
        let mut keys = rest.clone();
        move_key(&mut keys, 4, DVec3::new(1.0, 0.0, 1.0), DQuat::IDENTITY, KeyMode::Independent);
        let before = keys.clone();
        keep_chord_lengths(&mut keys, &rest);
        assert_eq!(keys[0], rest[0], "key 0 stays");
        for i in 1..5 {
            let length = keys[i].center.distance(keys[i - 1].center);
            assert!((length - 0.5).abs() < 1e-15, "chord {i}: {length}");
            assert_eq!(keys[i].rotation, before[i].rotation, "frames are the edit's");
        }
        // The last chord keeps the edit's direction, towards the dragged key.
        let (edited, kept) = (before[4].center - before[3].center, keys[4].center - keys[3].center);
        assert!(edited.normalize().dot(kept.normalize()) > 1.0 - 1e-15);
        assert!((chord_length(&keys) - chord_length(&rest)).abs() < 1e-15);
        // Without it the edit stretched the spine.
        assert!(chord_length(&before) > 1.2 * chord_length(&rest));
    }

    #[test]
    fn coincident_centers_part_along_the_earlier_normal() {
        let rest = column();
        let mut keys = rest.clone();
        keys[2].center = keys[1].center;
        keep_chord_lengths(&mut keys, &rest);
        assert!(keys[2].center.distance(DVec3::new(0.0, 0.0, 1.0)) < 1e-15, "{}", keys[2].center);
    }
}
