//! Chord-length knots u_i of a sweep's rest keys (§3): u_0 = 0,
//! u_i = u_{i−1} + |p_i − p_{i−1}| / L, u_n = 1, with L the total chord length.
//!
//! The knots belong to the rest rig and stay fixed while the sweep is posed, so a vertex bound
//! between keys i and i+1 stays between them.

use glam::DVec3;

use super::error::SweepError;
use crate::limits::MIN_KNOT_SPACING;

/// Normalized chord-length knots of `centers`. Fails if two consecutive centers coincide (the
/// knot would not increase), lie closer than [`MIN_KNOT_SPACING`] of the chord length, or a
/// distance is not finite.
pub fn chord_length_knots(centers: &[DVec3]) -> Result<Vec<f64>, SweepError> {
    let mut knots = Vec::with_capacity(centers.len());
    knots.push(0.0);
    let mut total = 0.0;
    for (i, pair) in centers.windows(2).enumerate() {
        let chord = pair[0].distance(pair[1]);
        if !chord.is_finite() {
            return Err(SweepError::ChordOverflow { key: i + 1, previous: i });
        }
        if chord == 0.0 {
            return Err(SweepError::CoincidentCenters { key: i + 1, previous: i });
        }
        total += chord;
        knots.push(total);
    }
    if !total.is_finite() {
        return Err(SweepError::ChordOverflow { key: centers.len() - 1, previous: centers.len() - 2 });
    }
    for knot in &mut knots {
        *knot /= total;
    }
    // Pin the last knot to 1 exactly, whatever the rounding of the division.
    if let Some(last) = knots.last_mut() {
        *last = 1.0;
    }
    if let Some(i) = knots.windows(2).position(|pair| pair[1] - pair[0] < MIN_KNOT_SPACING) {
        let fraction = centers[i].distance(centers[i + 1]) / total;
        return Err(SweepError::CentersTooClose { key: i + 1, previous: i, fraction });
    }
    Ok(knots)
}

/// Checks explicit knots: one per key, finite, from exactly 0 to exactly 1, increasing by at
/// least [`MIN_KNOT_SPACING`] from one to the next.
pub fn validate_knots(knots: &[f64], keys: usize) -> Result<(), SweepError> {
    if knots.len() != keys {
        return Err(SweepError::KnotCount { keys, found: knots.len() });
    }
    if let Some(index) = knots.iter().position(|u| !u.is_finite()) {
        return Err(SweepError::NonFiniteKnot { index });
    }
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    if first != 0.0 || last != 1.0 {
        return Err(SweepError::KnotRange { first, last });
    }
    for (index, pair) in knots.windows(2).enumerate() {
        if pair[1] <= pair[0] {
            return Err(SweepError::KnotsNotIncreasing { index: index + 1, previous: pair[0], value: pair[1] });
        }
        if pair[1] - pair[0] < MIN_KNOT_SPACING {
            return Err(SweepError::KnotsTooClose { index: index + 1, previous: pair[0], value: pair[1] });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knots_follow_chord_length() {
        let centers = [DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 3.0, 0.0)];
        assert_eq!(chord_length_knots(&centers).unwrap(), vec![0.0, 0.25, 1.0]);
    }

    #[test]
    fn coincident_consecutive_centers_are_rejected() {
        let centers = [DVec3::ZERO, DVec3::X, DVec3::X];
        assert_eq!(chord_length_knots(&centers), Err(SweepError::CoincidentCenters { key: 2, previous: 1 }));
    }

    #[test]
    fn explicit_knots_must_increase_from_zero_to_one() {
        assert!(validate_knots(&[0.0, 0.5, 1.0], 3).is_ok());
        assert!(matches!(validate_knots(&[0.0, 1.0], 3), Err(SweepError::KnotCount { .. })));
        assert!(matches!(validate_knots(&[0.1, 0.5, 1.0], 3), Err(SweepError::KnotRange { .. })));
        assert!(matches!(
            validate_knots(&[0.0, 0.5, 0.5, 1.0], 4),
            Err(SweepError::KnotsNotIncreasing { index: 2, .. })
        ));
        assert!(matches!(validate_knots(&[0.0, f64::NAN, 1.0], 3), Err(SweepError::NonFiniteKnot { index: 1 })));
    }

    #[test]
    fn knots_closer_than_the_minimum_spacing_are_rejected() {
        assert_eq!(
            validate_knots(&[0.0, 1e-300, 1.0], 3),
            Err(SweepError::KnotsTooClose { index: 1, previous: 0.0, value: 1e-300 })
        );
        assert!(validate_knots(&[0.0, 2.0 * MIN_KNOT_SPACING, 1.0], 3).is_ok());
        assert!(validate_knots(&[0.0, 1.0 - 0.5 * MIN_KNOT_SPACING, 1.0], 3).is_err());
    }

    #[test]
    fn centers_closer_than_the_minimum_spacing_are_rejected() {
        let centers = [DVec3::ZERO, DVec3::new(0.0, 0.0, 1e-9), DVec3::Z];
        assert!(matches!(
            chord_length_knots(&centers),
            Err(SweepError::CentersTooClose { key: 1, previous: 0, fraction }) if fraction < 1e-8
        ));
    }

    #[test]
    fn a_chord_length_that_overflows_is_rejected() {
        let centers = [DVec3::splat(-1e308), DVec3::ZERO, DVec3::splat(1e308)];
        assert!(matches!(chord_length_knots(&centers), Err(SweepError::ChordOverflow { .. })));
    }
}
