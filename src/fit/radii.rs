//! Sampled radii of a key (§3, Fig. 3b): from the section's center along M rays to the
//! section's boundary; where a ray crosses it more than once, the mean distance of the
//! boundary around the ray ([`super::hidden`]).

use std::f64::consts::TAU;

use glam::DVec2;

use super::hidden::mean_radii;
use super::section::Contour;

/// The radii of one key and how the section met the rays.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledRadii {
    /// ρ_j at θ_j = 2πj/M.
    pub radii: Vec<f64>,
    /// Rays that crossed the boundary more than once (the section is not star-shaped around
    /// its center there); each took the mean distance of the boundary around it
    /// ([`mean_radii`]), or its outermost crossing where that has none.
    pub several_crossings: usize,
    /// Rays that met no boundary (an open section); each took the value interpolated between
    /// its nearest neighbours that did.
    pub missed: usize,
}

/// Samples `count` radii of the section made of `contours` around `center` (all in in-plane
/// coordinates); `None` when no ray meets the boundary.
pub fn sample(contours: &[&Contour], center: DVec2, count: usize) -> Option<SampledRadii> {
    let mut several = Vec::new();
    let mut found: Vec<Option<f64>> = (0..count)
        .map(|j| {
            let (crossings, outermost) = ray_crossings(contours, center, TAU * j as f64 / count as f64);
            if crossings > 1 {
                several.push(j);
            }
            outermost
        })
        .collect();
    for (&j, mean) in several.iter().zip(mean_radii(contours, center, count, &several)) {
        if let Some(mean) = mean {
            found[j] = Some(mean);
        }
    }
    let several_crossings = several.len();
    let missed = found.iter().filter(|r| r.is_none()).count();
    let radii = fill_periodic_gaps(&found)?;
    Some(SampledRadii { radii, several_crossings, missed })
}

/// How many times the ray from `center` at `angle` crosses the contours, and the distance to
/// its outermost crossing.
pub fn ray_crossings(contours: &[&Contour], center: DVec2, angle: f64) -> (usize, Option<f64>) {
    let hits = ray_hits(contours, center, angle);
    (hits.len(), hits.last().copied())
}

/// The distances along the ray from `center` at `angle` to each crossing of the contours,
/// increasing.
pub fn ray_hits(contours: &[&Contour], center: DVec2, angle: f64) -> Vec<f64> {
    let direction = DVec2::new(angle.cos(), angle.sin());
    let mut hits: Vec<f64> =
        contours.iter().flat_map(|c| c.segments()).filter_map(|(a, b)| ray_hit(center, direction, a, b)).collect();
    hits.sort_by(f64::total_cmp);
    // A ray through a shared point of two segments meets both: count it once.
    hits.dedup_by(|b, a| *b - *a <= 1e-9 * a.abs().max(f64::MIN_POSITIVE));
    hits
}

/// The distance along the ray from `origin` in unit `direction` to the segment `a`–`b`, if
/// they meet (the ends included, with a little slack so that a ray through a shared point of
/// two segments cannot slip between them).
fn ray_hit(origin: DVec2, direction: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let edge = b - a;
    let denominator = direction.perp_dot(edge);
    if denominator == 0.0 {
        return None;
    }
    let to_a = a - origin;
    let distance = to_a.perp_dot(edge) / denominator;
    let u = to_a.perp_dot(direction) / denominator;
    const SLACK: f64 = 1e-9;
    (distance >= 0.0 && (-SLACK..=1.0 + SLACK).contains(&u)).then_some(distance)
}

/// Fills each missing value by linear interpolation between the nearest present values on
/// either side, around the circle; `None` if every value is missing.
fn fill_periodic_gaps(values: &[Option<f64>]) -> Option<Vec<f64>> {
    let n = values.len();
    let present: Vec<usize> = (0..n).filter(|&j| values[j].is_some()).collect();
    let &first = present.first()?;
    let mut filled: Vec<f64> = values.iter().map(|v| v.unwrap_or(0.0)).collect();
    for (k, &from) in present.iter().enumerate() {
        let to = present.get(k + 1).copied().unwrap_or(first + n);
        let (a, b) = (filled[from], filled[to % n]);
        for j in from + 1..to {
            let u = (j - from) as f64 / (to - from) as f64;
            filled[j % n] = a + (b - a) * u;
        }
    }
    Some(filled)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon(points: &[(f64, f64)]) -> Contour {
        Contour { points: points.iter().map(|&(x, y)| DVec2::new(x, y)).collect(), closed: true }
    }

    #[test]
    fn a_square_gives_its_radii() {
        let square = polygon(&[(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]);
        let sampled = sample(&[&square], DVec2::ZERO, 8).unwrap();
        let diagonal = 2f64.sqrt();
        let expected = [1.0, diagonal, 1.0, diagonal, 1.0, diagonal, 1.0, diagonal];
        for (r, e) in sampled.radii.iter().zip(expected) {
            assert!((r - e).abs() < 1e-12, "{:?}", sampled.radii);
        }
        assert_eq!((sampled.several_crossings, sampled.missed), (0, 0));
    }

    #[test]
    fn a_non_star_section_takes_the_mean_of_the_walls_it_crosses_and_says_so() {
        // A C shape whose slot opens to +x around the center: the rays at θ = π/2, π and 3π/2
        // cross the inner wall, then the outer; the ray at θ = 0 leaves through the slot.
        let c = polygon(&[
            (-2.0, -2.0),
            (2.0, -2.0),
            (2.0, -1.0),
            (-1.0, -1.0),
            (-1.0, 1.0),
            (2.0, 1.0),
            (2.0, 2.0),
            (-2.0, 2.0),
        ]);
        let sampled = sample(&[&c], DVec2::ZERO, 4).unwrap();
        assert_eq!((sampled.several_crossings, sampled.missed), (3, 1));
        // Between the inner wall (1 away) and the outer (2 away), where the outermost crossing
        // would take 2 and leave the inner wall 1 inside.
        for r in &sampled.radii[1..] {
            assert!(*r > 1.0 && *r < 2.0, "{:?}", sampled.radii);
        }
    }

    #[test]
    fn gaps_are_filled_around_the_circle() {
        let filled = fill_periodic_gaps(&[Some(1.0), None, Some(3.0), None, None, None]).unwrap();
        assert_eq!(filled, vec![1.0, 2.0, 3.0, 2.5, 2.0, 1.5]);
        assert!(fill_periodic_gaps(&[None, None]).is_none());
    }
}
