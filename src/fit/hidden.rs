//! The radius of a ray that crosses a section's boundary more than once (a section that is not
//! star-shaped around its center: a cupped ear's crescent, the separate contours of toes or
//! fingers).
//!
//! No radius r_j describes such a ray's boundary: the sweep's cross-section r(θ) is one curve
//! per angle. The outermost crossing encloses everything but leaves each wall the ray meets
//! inside it at a depth |d| up to the section's width there. The fit is judged by the RMS of
//! the vertices' d (§3, Fig. 4, [`super::quality`]), and the vertices lie on the boundary with
//! a density that follows its length, so for such a ray the radius that minimises
//! Σ (|v − C| − r_j)² over the boundary near θ_j is taken: the length-weighted mean distance
//! of the boundary around θ_j,
//!
//! r_j = ∫ B_j(θ(s)) ρ(s) ds / ∫ B_j(θ(s)) ds,
//!
//! with B_j the hat function of width 2·2π/M centred on θ_j (the weight of θ_j in the linear
//! interpolation between neighbouring samples) and ρ(s), θ(s) the distance and angle from the
//! section's center of the boundary point at arc length s. The integral is taken by splitting
//! each boundary segment into pieces spanning at most a quarter of the angular spacing. A ray
//! that crosses once keeps its crossing, so a star-shaped section keeps its radii.

use std::f64::consts::{PI, TAU};

use glam::DVec2;

use super::section::Contour;

/// Each boundary segment is split into pieces spanning at most this fraction of the angular
/// spacing 2π/M seen from the center.
const PIECE: f64 = 0.25;

/// The length-weighted mean distance from `center` of the boundary of `contours` within one
/// angular spacing of θ_j = 2πj/`count` (see the module docs), for each `j` in `rays`;
/// `None` for a ray with no boundary in its window.
pub fn mean_radii(contours: &[&Contour], center: DVec2, count: usize, rays: &[usize]) -> Vec<Option<f64>> {
    let spacing = TAU / count as f64;
    // No ray crosses more than once (a star-shaped section): nothing to weigh.
    if rays.is_empty() {
        return Vec::new();
    }
    let mut sums = vec![(0.0, 0.0); rays.len()];
    for (a, b) in contours.iter().flat_map(|c| c.segments()) {
        let (pa, pb) = (a - center, b - center);
        let swept = angle_between(pa, pb);
        let pieces = ((swept / (PIECE * spacing)).ceil() as usize).clamp(1, 4 * count);
        for k in 0..pieces {
            let (p, q) =
                (pa + (pb - pa) * (k as f64 / pieces as f64), pa + (pb - pa) * ((k + 1) as f64 / pieces as f64));
            let m = 0.5 * (p + q);
            let length = p.distance(q);
            if length == 0.0 || m == DVec2::ZERO {
                continue;
            }
            let theta = m.y.atan2(m.x);
            for (sum, &j) in sums.iter_mut().zip(rays) {
                let offset = angle_difference(theta, spacing * j as f64);
                let weight = 1.0 - offset / spacing;
                if weight > 0.0 {
                    sum.0 += weight * length * m.length();
                    sum.1 += weight * length;
                }
            }
        }
    }
    sums.into_iter().map(|(moment, weight)| (weight > 0.0).then(|| moment / weight)).collect()
}

/// The unsigned angle between two directions, in [0, π].
fn angle_between(a: DVec2, b: DVec2) -> f64 {
    a.perp_dot(b).atan2(a.dot(b)).abs()
}

/// The unsigned difference of two angles around the circle, in [0, π].
fn angle_difference(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    if d > PI { TAU - d } else { d }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(center: DVec2, radius: f64, n: usize) -> Contour {
        let points = (0..n).map(|k| center + DVec2::from_angle(TAU * k as f64 / n as f64) * radius).collect();
        Contour { points, closed: true }
    }

    #[test]
    fn a_circle_around_the_center_gives_its_radius() {
        let c = circle(DVec2::ZERO, 2.0, 400);
        for r in mean_radii(&[&c], DVec2::ZERO, 16, &[0, 3, 15]) {
            assert!((r.unwrap() - 2.0).abs() < 1e-4, "{r:?}");
        }
    }

    #[test]
    fn a_ray_through_a_ring_takes_the_mean_of_its_two_walls() {
        // An annulus of radii 1 and 3: the outer wall is three times as long, so the mean
        // distance is (1·1 + 3·3)/(1 + 3) = 2.5, between the walls where the outermost
        // crossing would take 3.
        let (outer, inner) = (circle(DVec2::ZERO, 3.0, 600), circle(DVec2::ZERO, 1.0, 200));
        let r = mean_radii(&[&outer, &inner], DVec2::ZERO, 8, &[2])[0].unwrap();
        assert!((r - 2.5).abs() < 1e-3, "{r}");
    }

    #[test]
    fn no_rays_to_weigh_give_no_radii() {
        assert!(mean_radii(&[&circle(DVec2::ZERO, 2.0, 40)], DVec2::ZERO, 8, &[]).is_empty());
    }

    #[test]
    fn a_window_with_no_boundary_gives_none() {
        let far = circle(DVec2::new(10.0, 0.0), 1.0, 50);
        assert_eq!(mean_radii(&[&far], DVec2::ZERO, 8, &[4]), vec![None]);
    }
}
