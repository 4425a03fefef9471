//! Bending a sweep smoothly over a stretch of its axis: the turn of one key (§4, Fig. 7b)
//! shared among the keys of a span, as §4 propagates a control to k keys, with shares that
//! grow smoothly from zero at the span's start to the whole turn at its end.
//!
//! A key's turn bends R(t) and C(t) only within the knot intervals beside it, so a fitted limb
//! of 20 keys turned at one key bends over a tenth of its length, and its outer side stretches
//! as 1 + r·κ. Spread over a span of the axis, the same turn bends at a curvature that many
//! times smaller.

use glam::{DQuat, DVec3};

use super::keys::{KeyMode, move_key};
use crate::sweep::Key;

/// The share of each end of a span over which the rate of turning rises from zero (and falls
/// back to zero) as a raised cosine: a Tukey window, flat between. The peak rate is
/// 1 / (1 − TAPER) = 1.11 times the mean, against 1.5 for a smoothstep and 2 for a raised
/// cosine over the whole span: the outer side of a bend stretches as 1 + w·κ (w its distance
/// from the axis in the bend's plane, κ the spine's curvature), so the bend's largest stretch
/// is nearly the least that turning by the angle within the span allows.
pub const TAPER: f64 = 0.1;

/// The share of a bend's turn done at `x` across its span (0 at its start, 1 at its end):
/// the integral of the Tukey window of [`TAPER`], normalised; 0 before the span, 1 past it.
/// C¹ in x, so the bend's curvature rises and falls without a jump.
pub fn bend_share(x: f64) -> f64 {
    let rising = |x: f64| 0.5 * x - TAPER / (2.0 * std::f64::consts::PI) * (std::f64::consts::PI * x / TAPER).sin();
    let total = 1.0 - TAPER;
    let turned = if x <= 0.0 {
        0.0
    } else if x < TAPER {
        rising(x)
    } else if x <= 1.0 - TAPER {
        0.5 * TAPER + (x - TAPER)
    } else if x < 1.0 {
        total - rising(1.0 - x)
    } else {
        total
    };
    turned / total
}

/// Turns the keys (at `knots`) by `angle` radians about the world direction `axis` (unit)
/// spread over the span of width `span` centred on `t`: each key turns, with the keys after it
/// (as a `local` key move), by the share of the turn [`bend_share`] gives between its knot and
/// the previous key's. What lies before the first knot is turned at the first key (the whole
/// sweep about its first center) and what lies past the last knot at the last key, so the
/// last key has always turned by `angle`, and the sweep past the span has turned rigidly.
pub fn bend(keys: &mut [Key], knots: &[f64], t: f64, span: f64, axis: DVec3, angle: f64) {
    let start = t - 0.5 * span;
    let last = keys.len().saturating_sub(1);
    let mut done = 0.0;
    for (i, &knot) in knots.iter().enumerate().take(keys.len()) {
        let share = if i == last { 1.0 } else { bend_share((knot - start) / span) };
        let step = share - done;
        if step != 0.0 {
            move_key(keys, i, DVec3::ZERO, DQuat::from_axis_angle(axis, angle * step), KeyMode::Local);
        }
        done = share;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(count: usize) -> (Vec<Key>, Vec<f64>) {
        let keys = (0..count).map(|i| Key::circle(DVec3::new(0.0, 0.0, i as f64), DQuat::IDENTITY, 0.1, 8)).collect();
        let knots = (0..count).map(|i| i as f64 / (count - 1) as f64).collect();
        (keys, knots)
    }

    #[test]
    fn the_share_rises_smoothly_from_nothing_to_everything() {
        assert_eq!(bend_share(-0.5), 0.0);
        assert_eq!(bend_share(0.0), 0.0);
        assert_eq!(bend_share(1.0), 1.0);
        assert_eq!(bend_share(2.0), 1.0);
        assert!((bend_share(0.5) - 0.5).abs() < 1e-15, "symmetric about the middle");
        // The rate (a finite difference) starts and ends at 0, is continuous, and peaks at
        // 1 / (1 − TAPER) between the tapers.
        let rate = |x: f64| (bend_share(x + 1e-7) - bend_share(x - 1e-7)) / 2e-7;
        assert!(rate(1e-6) < 1e-3 && rate(1.0 - 1e-6) < 1e-3, "{} {}", rate(1e-6), rate(1.0 - 1e-6));
        for x in [TAPER, 0.5, 1.0 - TAPER] {
            assert!((rate(x) - 1.0 / (1.0 - TAPER)).abs() < 1e-6, "rate at {x}: {}", rate(x));
        }
        let mut previous = 0.0;
        for k in 1..=1000 {
            let x = k as f64 / 1000.0;
            assert!(bend_share(x) >= previous, "increasing");
            assert!((rate(x.min(1.0 - 1e-6)) - rate((x - 1e-3).max(1e-6))).abs() < 0.03, "continuous near {x}");
            previous = bend_share(x);
        }
    }

    /// A straight column of 21 keys bent 90° over its middle fifth: the keys before the span
    /// stay, those past it turned rigidly by exactly 90°, and the turn between neighbouring
    /// keys never exceeds the mean over the span times the window's peak.
    #[test]
    fn a_bend_turns_the_sweep_past_its_span_rigidly_and_spreads_the_turn_within() {
        let (mut keys, knots) = column(21);
        let rest = keys.clone();
        let angle = std::f64::consts::FRAC_PI_2;
        bend(&mut keys, &knots, 0.5, 0.2, DVec3::X, angle);
        for i in 0..=8 {
            assert_eq!(keys[i], rest[i], "key {i} lies before the span [0.4, 0.6]");
        }
        let turned = DQuat::from_rotation_x(angle);
        for i in 12..21 {
            assert!(keys[i].rotation.angle_between(turned) < 1e-12, "key {i}");
            // Past the span the column runs straight along the turned axis.
            let along = (keys[i].center - keys[12].center).dot(turned * DVec3::Z);
            assert!((along - (i - 12) as f64).abs() < 1e-12, "key {i}: {along}");
        }
        let mean = angle / 4.0;
        for i in 1..21 {
            let step = keys[i].rotation.angle_between(keys[i - 1].rotation);
            assert!(step <= mean / (1.0 - TAPER) + 1e-12, "keys {} and {i}: {step}", i - 1);
        }
        // Chords between keys keep their lengths: the keys turn about their own centers.
        for i in 1..21 {
            assert!((keys[i].center.distance(keys[i - 1].center) - 1.0).abs() < 1e-12);
        }
    }

    /// A span reaching past either end: the share before the first knot turns the whole sweep
    /// at key 0, and the last key has turned by the whole angle.
    #[test]
    fn a_span_past_the_ends_still_turns_the_last_key_by_the_angle() {
        let (mut keys, knots) = column(6);
        let angle = 1.0;
        bend(&mut keys, &knots, 0.0, 3.0, DVec3::Y, angle);
        let first = keys[0].rotation.to_axis_angle().1;
        assert!(first > 0.0 && first < angle, "key 0 takes the share before t = 0: {first}");
        assert!(keys[5].rotation.angle_between(DQuat::from_rotation_y(angle)) < 1e-12);
    }
}
