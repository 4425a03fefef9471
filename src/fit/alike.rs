//! Shape twins keyed alike, for [`super::autorig`]: a character's left and right limbs that
//! are not rigged as each other's mirror images ([`super::twins`] does that for exact ones),
//! because the model is posed lopsided, was never modelled symmetric, or its near twins'
//! images fit looser, are still the same kind of limb, and a user expects them keyed alike:
//! as many keys on each. Each limb's fit inserts keys where its own fit is loose and stops
//! where a round of keys no longer tightens it, so such twins took different counts: the public
//! cartoon man's legs 11 and 13, the bunny's ears 15 and 11.
//!
//! Two rigged limbs are **shape twins** ([`shape_twins`]) where their chains have the same
//! shape (as many links, each hanging from the matching link; a hand's fingers matched in
//! whichever order is likest) and their first links are alike ([`alike`]: attached at the same
//! ends, within [`LIKE_COUNTS`] of each other in vertex count, mean radius and straightness,
//! [`LIKE_LENGTHS`] in length: a teapot's spout and handle are not). Each limb is in
//! at most one pair, the likest pairs first. Each pair of matched links alike but keyed
//! differently is then keyed alike ([`rigged_alike`]): each link is fitted again with exactly
//! its twin's key count (`super::refine::KeyCount::Exactly`), and of the two refits the one whose
//! pair's looser link fits better is kept. A refit is a candidate only where the caller accepts
//! it (within its target, or no looser than the fit it replaces), its keys stay on course
//! ([`KEY_PATH`]) and its chain still binds: its first key on its parent's sweep, its
//! children's first keys on it.

use std::time::Instant;

use super::Fit;
use super::chain::{FittedLink, binds};
use crate::sweep::{Key, chord_length};

/// Matched links differ in vertex count by at most this factor…
pub const LIKE_COUNTS: f64 = 1.25;

/// …and in length, the chord of their key centers, by at most this one: a fit's extra keys
/// lengthen its key path where they step aside (the dino's mirror twin toes, 120 vertices each,
/// ran 0.63 with 24 keys and 0.47 with 10; keyed alike, 0.59 and 0.47).
pub const LIKE_LENGTHS: f64 = 1.4;

/// A refit whose key centers run more than this many times as far as those of the fit it
/// would replace has keys off the link's axis: keys forced in past where the fit's own
/// insertion stopped may step aside, and the public cartoon man's leg, fitted with 13 keys
/// where its own fit stopped at 11, ran its centers 1.25 times as far (0.317 against 0.255).
pub const KEY_PATH: f64 = 1.1;

/// Chains of more links than this beyond the first are matched only in their own order (every
/// order of 6 links is 720 to try).
const MATCHED_IN_ANY_ORDER: usize = 6;

/// Two rigged limbs that are shape twins, and their matched links.
#[derive(Clone, Debug, PartialEq)]
pub struct TwinLimbs {
    /// The first limb (an index into the limbs).
    pub first: usize,
    /// The second limb.
    pub second: usize,
    /// Per link of the first limb, the second's link it matches.
    pub links: Vec<usize>,
}

/// The shape twins among `limbs` (each a rigged limb's links, or `None`), the likest pairs
/// first, each limb in at most one (see the module docs).
pub fn shape_twins(limbs: &[Option<&[FittedLink]>]) -> Vec<TwinLimbs> {
    let mut candidates: Vec<(f64, TwinLimbs)> = Vec::new();
    for (first, a) in limbs.iter().enumerate() {
        for (second, b) in limbs.iter().enumerate().skip(first + 1) {
            if let (Some(a), Some(b)) = (a, b)
                && let Some((unlikeness, links)) = matched_links(a, b)
            {
                candidates.push((unlikeness, TwinLimbs { first, second, links }));
            }
        }
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then((a.1.first, a.1.second).cmp(&(b.1.first, b.1.second))));
    let mut paired = vec![false; limbs.len()];
    let mut pairs = Vec::new();
    for (_, pair) in candidates {
        if !paired[pair.first] && !paired[pair.second] {
            paired[pair.first] = true;
            paired[pair.second] = true;
            pairs.push(pair);
        }
    }
    pairs
}

/// How unlike links `a` and `b` are: the sum of the logarithms of the ratios of their vertex
/// counts, lengths, mean radii and straightness (0 for the same).
fn unlikeness(a: &FittedLink, b: &FittedLink) -> f64 {
    log_ratios(a, b).into_iter().sum()
}

/// The logarithms of the ratios of `a`'s and `b`'s vertex counts, lengths, mean radii and
/// straightness ([`straightness`]), each at least 0.
fn log_ratios(a: &FittedLink, b: &FittedLink) -> [f64; 4] {
    let ratio = |x: f64, y: f64| (x / y).ln().abs();
    [
        ratio(a.vertices.len() as f64, b.vertices.len().max(1) as f64),
        ratio(chord_length(&a.fit.keys), chord_length(&b.fit.keys)),
        ratio(a.fit.quality.mean_radius, b.fit.quality.mean_radius),
        ratio(straightness(&a.fit.keys), straightness(&b.fit.keys)),
    ]
}

/// How straight `keys` run: the distance between the first and last centers over the chord of
/// all of them (1 for a straight sweep; the Newell teapot's handle 0.51, its spout 0.93).
fn straightness(keys: &[Key]) -> f64 {
    keys[0].center.distance(keys[keys.len() - 1].center) / chord_length(keys)
}

/// Whether links `a` and `b` are alike: attached at the same ends (a whole component at
/// neither), within [`LIKE_COUNTS`] of each other in vertex count, mean radius and
/// straightness, and [`LIKE_LENGTHS`] in length.
pub fn alike(a: &FittedLink, b: &FittedLink) -> bool {
    let [counts, lengths, radii, straight] = log_ratios(a, b);
    let attached = |link: &FittedLink| link.fit.rim.map(|rim| rim > 0.0);
    attached(a) == attached(b)
        && counts <= LIKE_COUNTS.ln()
        && lengths <= LIKE_LENGTHS.ln()
        && radii <= LIKE_COUNTS.ln()
        && straight <= LIKE_COUNTS.ln()
}

/// The order of `b`'s links that matches `a`'s, link 0 to link 0 and each link's parent to
/// its match's parent, the likest of such orders (the least summed [`unlikeness`]), and that
/// sum; `None` where the chains differ in shape or their first links are not [`alike`]. Other
/// matched links may be unlike (a hand's fingers, splayed otherwise): they are not keyed
/// alike.
fn matched_links(a: &[FittedLink], b: &[FittedLink]) -> Option<(f64, Vec<usize>)> {
    if a.len() != b.len() || a.is_empty() || !alike(&a[0], &b[0]) {
        return None;
    }
    let matches = |order: &[usize]| {
        let parents = (0..a.len()).all(|k| b[order[k]].parent == a[k].parent.map(|p| order[p]));
        parents.then(|| (0..a.len()).map(|k| unlikeness(&a[k], &b[order[k]])).sum::<f64>())
    };
    let mut order: Vec<usize> = (0..a.len()).collect();
    if a.len() - 1 > MATCHED_IN_ANY_ORDER {
        return matches(&order).map(|unlike| (unlike, order));
    }
    let mut best: Option<(f64, Vec<usize>)> = None;
    loop {
        if let Some(unlike) = matches(&order)
            && best.as_ref().is_none_or(|(least, _)| unlike < *least)
        {
            best = Some((unlike, order.clone()));
        }
        if !next_order(&mut order[1..]) {
            return best;
        }
    }
}

/// Steps `order` to the next in lexicographic order; `false` (leaving it the first) after the
/// last.
fn next_order(order: &mut [usize]) -> bool {
    let Some(i) = (1..order.len()).rev().find(|&i| order[i - 1] < order[i]) else {
        order.reverse();
        return false;
    };
    let j = (i..order.len()).rev().find(|&j| order[j] > order[i - 1]).unwrap_or(i);
    order.swap(i - 1, j);
    order[i..].reverse();
    true
}

/// How [`rigged_alike`] fits a link again and judges the result.
pub trait Refitter: Sync {
    /// The link `link` of the limb `links` fitted again with exactly `keys` keys, key 0 at the
    /// same end; `None` where the fit refuses it.
    fn refit(&self, links: &[FittedLink], link: usize, keys: usize) -> Option<Fit>;
    /// Whether `refit` may replace `old`, the link's fit.
    fn accepts(&self, refit: &Fit, old: &Fit) -> bool;
    /// How loosely `fit` follows its link, as a share of its target.
    fn looseness(&self, fit: &Fit) -> f64;
}

/// The limbs `first` and `second` (shape twins matched by `links`, [`TwinLimbs::links`]) with
/// each matched pair of links keyed differently fitted alike (see the module docs); a link
/// neither refit is accepted for stays as it was.
pub fn rigged_alike(
    mut first: Vec<FittedLink>,
    mut second: Vec<FittedLink>,
    links: &[usize],
    refitter: &impl Refitter,
) -> (Vec<FittedLink>, Vec<FittedLink>) {
    // Parents before children, so that a child is checked against its parent's new sweep.
    for (a, &b) in links.iter().enumerate() {
        if first[a].fit.keys.len() == second[b].fit.keys.len() || !alike(&first[a], &second[b]) {
            continue;
        }
        // Each link's seconds count its refit, kept or not.
        let timed = |links: &[FittedLink], link: usize, twin: &Fit| {
            let started = Instant::now();
            (keyed_like(links, link, twin, refitter), started.elapsed().as_secs_f64())
        };
        let ((refit_first, first_seconds), (refit_second, second_seconds)) =
            crate::parallel::join(|| timed(&first, a, &second[b].fit), || timed(&second, b, &first[a].fit));
        first[a].seconds += first_seconds;
        second[b].seconds += second_seconds;
        // Of the two, the pair whose looser link fits better.
        let pair = |one: &Fit, other: &Fit| refitter.looseness(one).max(refitter.looseness(other));
        let with_first = refit_first.map(|fit| (pair(&fit, &second[b].fit), fit));
        let with_second = refit_second.map(|fit| (pair(&first[a].fit, &fit), fit));
        match (with_first, with_second) {
            (Some((one, fit)), Some((other, _))) if one <= other => first[a].fit = fit,
            (Some((_, fit)), None) => first[a].fit = fit,
            (_, Some((_, fit))) => second[b].fit = fit,
            (None, None) => {}
        }
    }
    (first, second)
}

/// Link `link` of `links` fitted again with as many keys as `twin`, where `refitter` accepts
/// it, its keys stay on course ([`KEY_PATH`]) and the chain still binds; else `None`.
fn keyed_like(links: &[FittedLink], link: usize, twin: &Fit, refitter: &impl Refitter) -> Option<Fit> {
    let old = &links[link].fit;
    let fit = refitter.refit(links, link, twin.keys.len()).filter(|fit| fit.keys.len() == twin.keys.len())?;
    let on_course = chord_length(&fit.keys) <= KEY_PATH * chord_length(&old.keys);
    let parent_binds = links[link].parent.is_none_or(|parent| binds(&links[parent].fit, &fit).is_some());
    let children_bind =
        links.iter().filter(|child| child.parent == Some(link)).all(|child| binds(&fit, &child.fit).is_some());
    (on_course && parent_binds && children_bind && refitter.accepts(&fit, old)).then_some(fit)
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};

    use super::*;
    use crate::fit::FitQuality;

    /// A fit of `keys` keys evenly along x over `length`, fitting within `rms_d`.
    fn fit(keys: usize, length: f64, rms_d: f64) -> Fit {
        let keys: Vec<Key> = (0..keys)
            .map(|k| {
                let x = length * k as f64 / (keys - 1) as f64;
                Key::circle(DVec3::new(x, 0.0, 0.0), DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2), 1.0, 8)
            })
            .collect();
        let quality = FitQuality { vertices: 10, without_root: 0, mean_radius: 1.0, max_d: rms_d, rms_d };
        Fit { keys, quality, sections: Vec::new(), steps: Vec::new(), rim: [1.0, 0.0], falloff: 0.0 }
    }

    /// A link of `vertices` vertices hanging from `parent`, its fit [`fit`].
    fn link(vertices: u32, keys: usize, length: f64, parent: Option<usize>) -> FittedLink {
        let vertices: Vec<u32> = (0..vertices).collect();
        FittedLink { fitted: vertices.clone(), vertices, fit: fit(keys, length, 0.05), seconds: 0.0, parent }
    }

    #[test]
    fn every_order_is_stepped_through_once() {
        let mut order = vec![0, 1, 2];
        let mut seen = vec![order.clone()];
        while next_order(&mut order) {
            seen.push(order.clone());
        }
        assert_eq!(seen, [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]]);
        assert_eq!(order, [0, 1, 2], "back to the first");
    }

    #[test]
    fn limbs_alike_in_shape_pair_up_the_likest_first() {
        // Two arms, each a stem with a thumb and a finger (listed in another order on the
        // second), and a leg as long as an arm but of one link.
        let arm = [link(100, 10, 5.0, None), link(20, 6, 1.0, Some(0)), link(30, 6, 2.0, Some(0))];
        let other_arm = [link(105, 12, 5.2, None), link(31, 7, 2.1, Some(0)), link(19, 6, 1.0, Some(0))];
        let leg = [link(100, 10, 5.0, None)];
        let shorter_leg = [link(95, 8, 4.5, None)];
        let long_leg = [link(100, 8, 9.0, None)];
        let limbs = [Some(&arm[..]), Some(&leg[..]), None, Some(&other_arm[..]), Some(&long_leg[..]), Some(&shorter_leg[..])];
        let pairs = shape_twins(&limbs);
        // The legs are liker than the arms (one link against three), and the long leg is
        // like neither.
        assert_eq!(
            pairs,
            [
                TwinLimbs { first: 1, second: 5, links: vec![0] },
                TwinLimbs { first: 0, second: 3, links: vec![0, 2, 1] }
            ]
        );
        // A handle as long, as thick and of as many vertices as a leg, but bent in a half circle
        // or attached at both ends, is no leg's twin.
        let mut handle = [link(100, 10, 5.0, None)];
        for (k, key) in handle[0].fit.keys.iter_mut().enumerate() {
            let angle = std::f64::consts::PI * k as f64 / 9.0;
            key.center = DVec3::new(angle.cos(), angle.sin(), 0.0) * (5.0 / std::f64::consts::PI);
        }
        assert_eq!(shape_twins(&[Some(&leg[..]), Some(&handle[..])]), []);
        let mut attached_at_both_ends = [link(100, 10, 5.0, None)];
        attached_at_both_ends[0].fit.rim = [1.0, 1.0];
        assert_eq!(shape_twins(&[Some(&leg[..]), Some(&attached_at_both_ends[..])]), []);
        assert_eq!(shape_twins(&[Some(&leg[..]), Some(&shorter_leg[..])]).len(), 1);
        // Chains of different shapes are no twins.
        let forked_once = [link(100, 10, 5.0, None), link(20, 6, 1.0, Some(0)), link(30, 6, 2.0, Some(1))];
        assert_eq!(shape_twins(&[Some(&arm[..]), Some(&forked_once[..])]), []);
    }

    /// Refits a link with the keys asked for, as loose as `loose` says for that count.
    struct Counting {
        loose: fn(usize) -> f64,
    }

    impl Refitter for Counting {
        fn refit(&self, links: &[FittedLink], link: usize, keys: usize) -> Option<Fit> {
            Some(fit(keys, chord_length(&links[link].fit.keys), (self.loose)(keys)))
        }

        fn accepts(&self, refit: &Fit, old: &Fit) -> bool {
            refit.quality.rms_d <= 0.1 || refit.quality.rms_d <= old.quality.rms_d
        }

        fn looseness(&self, fit: &Fit) -> f64 {
            fit.quality.rms_d / 0.1
        }
    }

    #[test]
    fn twins_keyed_differently_take_the_count_whose_pair_fits_better() {
        let first = vec![link(100, 10, 5.0, None)];
        let second = vec![link(100, 14, 5.0, None)];
        // More keys fit closer: the first takes 14.
        let closer_with_more = Counting { loose: |keys| if keys >= 14 { 0.02 } else { 0.05 } };
        let (a, b) = rigged_alike(first.clone(), second.clone(), &[0], &closer_with_more);
        assert_eq!((a[0].fit.keys.len(), b[0].fit.keys.len()), (14, 14));
        assert_eq!(b[0].fit, second[0].fit, "the twin refitted is the one whose pair fits better");
        // A refit accepted for neither leaves both as they were.
        let too_loose = Counting { loose: |_| 0.5 };
        let (a, b) = rigged_alike(first.clone(), second.clone(), &[0], &too_loose);
        assert_eq!((a[0].fit.keys.len(), b[0].fit.keys.len()), (10, 14));
        // Fewer keys fit closer: the second takes 10.
        let closer_with_fewer = Counting { loose: |keys| if keys <= 10 { 0.01 } else { 0.08 } };
        let (a, b) = rigged_alike(first, second, &[0], &closer_with_fewer);
        assert_eq!((a[0].fit.keys.len(), b[0].fit.keys.len()), (10, 10));
    }

    #[test]
    fn a_refit_whose_keys_wander_off_the_axis_is_not_kept() {
        struct Wandering;
        impl Refitter for Wandering {
            fn refit(&self, links: &[FittedLink], link: usize, keys: usize) -> Option<Fit> {
                let mut fit = fit(keys, chord_length(&links[link].fit.keys), 0.01);
                fit.keys[1].center.y += 0.5 * chord_length(&links[link].fit.keys);
                Some(fit)
            }
            fn accepts(&self, _: &Fit, _: &Fit) -> bool {
                true
            }
            fn looseness(&self, fit: &Fit) -> f64 {
                fit.quality.rms_d / 0.1
            }
        }
        let (a, b) = rigged_alike(vec![link(100, 10, 5.0, None)], vec![link(100, 14, 5.0, None)], &[0], &Wandering);
        assert_eq!((a[0].fit.keys.len(), b[0].fit.keys.len()), (10, 14));
    }
}
