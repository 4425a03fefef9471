//! How a fit's key centers run through its part: along it, or back and forth inside it. A
//! coarse part's fit may take either path from different starts (`super::refine`), and a fit
//! whose keys fold back or zigzag is no limb (`super::autorig`), however closely its radii
//! follow the vertices.

use glam::DVec3;

use crate::sweep::Key;

/// Whether `keys`' centers zigzag through the part rather than run along it: the path from
/// center to center turns back (a step against the one before it) at more than half of its
/// keys, and is over [`ZIGZAG_PATH`] times as long as the farthest two centers are apart. A
/// coarse part's fit may do so from one start and not from another (one of the AT-AT's four
/// upper legs, whose three mirror images ran down their legs, turned back 13 times in 22 keys
/// over 3.3 times its reach; the faerie's 12-vertex hand 11 times in 20 over 4.6).
pub fn zigzags(keys: &[Key]) -> bool {
    let steps: Vec<DVec3> = keys.windows(2).map(|pair| pair[1].center - pair[0].center).collect();
    let turns = steps.windows(2).filter(|pair| pair[0].dot(pair[1]) < 0.0).count();
    let path: f64 = steps.iter().map(|step| step.length()).sum();
    let reach = keys.iter().flat_map(|a| keys.iter().map(move |b| a.center.distance(b.center))).fold(0.0, f64::max);
    2 * turns > steps.len().saturating_sub(1) && path > ZIGZAG_PATH * reach
}

/// See [`zigzags`].
pub const ZIGZAG_PATH: f64 = 2.0;

/// How a fitted sweep's keys fold back: the knot intervals whose end key's center lies behind
/// the plane of their start key (the sweep runs backwards there), of all its intervals.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Folds {
    /// Intervals that step backwards.
    pub backwards: usize,
    /// Intervals.
    pub intervals: usize,
}

/// `keys`' folds where they fold the sweep: at least a third of the intervals step backwards
/// and the centers travel back at least [`FOLDED`] of the way they travel forward (along each
/// key's normal). A ball's fit may key back and forth around its middle (the faerie's head,
/// fitted from the start its keys zigzag from: 9 of 22 intervals, 39%); a coarse limb's fit
/// may step back now and then (wuson's front leg: 4 of 17, 36%; spot's: 4 of 14, 8%) and
/// still follow it.
pub fn folds(keys: &[Key]) -> Option<Folds> {
    let (mut forward, mut back, mut backwards) = (0.0, 0.0, 0);
    for pair in keys.windows(2) {
        let step = (pair[1].center - pair[0].center).dot(pair[0].rotation.normalize() * DVec3::Z);
        if step >= 0.0 {
            forward += step;
        } else {
            back -= step;
            backwards += 1;
        }
    }
    let intervals = keys.len().saturating_sub(1);
    (3 * backwards >= intervals && intervals > 0 && back >= FOLDED * forward).then_some(Folds { backwards, intervals })
}

/// A fit folds where its centers travel back at least this share of the way they travel forward
/// (with a third of its knot intervals or more running backwards).
pub const FOLDED: f64 = 0.3;

/// Whether `keys` run astray of their part: they fold back ([`folds`]) or zigzag
/// ([`zigzags`]).
pub fn astray(keys: &[Key]) -> bool {
    folds(keys).is_some() || zigzags(keys)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn keys_through(points: &[[f64; 3]]) -> Vec<Key> {
        points.iter().map(|&p| Key::circle(DVec3::from(p), DQuat::IDENTITY, 1.0, 8)).collect()
    }

    /// Keys along +z, their planes normal to it, at `zs`.
    fn keys_at(zs: &[f64]) -> Vec<Key> {
        zs.iter().map(|&z| Key::circle(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY, 1.0, 8)).collect()
    }

    /// A path that turns back at most of its keys and travels far more than it reaches
    /// zigzags. A straight one does not; nor does a handle's arc over 1.6π, which travels 2.5
    /// times as far as it reaches but never turns back; nor a coarse leg's wobble, which turns
    /// back at every key but by a tenth of a step.
    #[test]
    fn keys_that_turn_back_at_most_keys_zigzag_and_others_do_not() {
        let straight: Vec<[f64; 3]> = (0..8).map(|k| [0.0, 0.0, k as f64]).collect();
        assert!(!zigzags(&keys_through(&straight)));
        let zigzag: Vec<[f64; 3]> =
            (0..12).map(|k| [0.0, 0.0, if k % 2 == 0 { 0.1 * k as f64 } else { 3.0 }]).collect();
        assert!(zigzags(&keys_through(&zigzag)));
        let handle: Vec<[f64; 3]> = (0..=10)
            .map(|k| {
                let a = std::f64::consts::PI * k as f64 / 10.0 * 1.6;
                [a.cos(), a.sin(), 0.0]
            })
            .collect();
        assert!(!zigzags(&keys_through(&handle)));
        let wobble =
            [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.9], [0.0, 0.0, 2.0], [0.0, 0.0, 1.9], [0.0, 0.0, 3.0]];
        assert!(!zigzags(&keys_through(&wobble)));
    }

    /// Keys that march on do not fold, nor do they with one small step back; keys that go back
    /// and forth do, and run astray.
    #[test]
    fn keys_that_march_on_do_not_fold_and_keys_that_turn_back_do() {
        assert_eq!(folds(&keys_at(&[0.0, 1.0, 2.0, 3.0, 4.0])), None);
        // One small step back in eight: a coarse fit's wobble.
        assert_eq!(folds(&keys_at(&[0.0, 1.0, 2.0, 1.9, 3.0, 4.0, 5.0, 6.0, 7.0])), None);
        // Back and forth around the middle: 3 of 6 intervals, back 2.5 for 4.5 forward.
        let zigzag = keys_at(&[0.0, 2.0, 1.0, 2.0, 1.0, 2.5, 2.0]);
        assert_eq!(folds(&zigzag), Some(Folds { backwards: 3, intervals: 6 }));
        assert!(astray(&zigzag));
        assert!(!astray(&keys_at(&[0.0, 1.0, 2.0, 3.0, 4.0])));
    }
}
