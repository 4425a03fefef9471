//! Sampled radii of a key (§3, Fig. 3b): from the section's center along M rays to the
//! section's boundary; where a ray crosses it more than once, the mean distance of the
//! boundary around the ray ([`super::hidden`]).

use glam::DVec2;

use super::hidden::mean_radii;
use super::ray_fan::{RayFan, with_fan};
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
    with_fan(count, |fan| sample_with(fan, contours, center, count))
}

/// [`sample`] with `fan` of `count` rays.
fn sample_with(fan: &mut RayFan, contours: &[&Contour], center: DVec2, count: usize) -> Option<SampledRadii> {
    fan.cast(contours, center);
    let mut several = Vec::new();
    let mut found: Vec<Option<f64>> = (0..count)
        .map(|j| {
            let crossings = fan.crossings(j);
            if crossings.len() > 1 {
                several.push(j);
            }
            crossings.last().copied()
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
