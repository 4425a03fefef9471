//! A center from which a section looks star-shaped, so that radii sampled from it describe
//! the whole boundary (a sweep's cross-section is a star-shaped curve r(θ) around C(t)).
//!
//! The area centroid serves when every ray from it crosses the boundary once. Otherwise (a
//! crescent, such as the cupped section of a bunny's ear, whose centroid may even lie outside
//! it), points inside the section are tried on a grid and then a finer grid around the best
//! one. Each is scored by how much boundary its rays cannot see: for each probe ray, the
//! depth between its first and its outermost crossing (the |d| a vertex on a hidden wall
//! gets), relative to the mean outermost distance, with a ray that meets nothing counting
//! as fully hidden. The best point wins, ties going to the point nearest the centroid; so once
//! a point sees the whole boundary, only points nearer the centroid are scored (on the beast,
//! a public mesh, that skips nearly half the points its fits would score).

use glam::DVec2;

use super::ray_fan::{RayFan, with_fan};
use super::section::Contour;

/// Probe rays per candidate center.
const PROBES: usize = 48;
/// Grid points per side of the coarse search.
const GRID: usize = 9;

/// The center of the section made of `contours`, starting from its area centroid.
pub fn star_center(contours: &[&Contour], centroid: DVec2) -> DVec2 {
    if contours.iter().any(|c| !c.closed) {
        return centroid;
    }
    with_fan(PROBES, |fan| search_from(fan, contours, centroid))
}

/// [`star_center`] with `fan` of [`PROBES`] rays.
fn search_from(fan: &mut RayFan, contours: &[&Contour], centroid: DVec2) -> DVec2 {
    let mut best = (hidden_depth(fan, contours, centroid), 0.0, centroid);
    if best.0 == 0.0 {
        return centroid;
    }
    let (lo, hi) = bounds(contours);
    let mut step = (hi - lo) / (GRID - 1) as f64;
    let mut search = |origin: DVec2, step: DVec2, best: &mut (f64, f64, DVec2)| {
        for i in 0..GRID {
            for j in 0..GRID {
                let q = origin + DVec2::new(i as f64 * step.x, j as f64 * step.y);
                let distance = q.distance(centroid);
                // Once a point sees the whole boundary, only a nearer one can win.
                if best.0 == 0.0 && distance >= best.1 {
                    continue;
                }
                if !contours.iter().any(|c| c.encloses(q)) {
                    continue;
                }
                let candidate = (hidden_depth(fan, contours, q), distance, q);
                if (candidate.0, candidate.1) < (best.0, best.1) {
                    *best = candidate;
                }
            }
        }
    };
    search(lo, step, &mut best);
    step /= (GRID - 1) as f64 / 2.0;
    let around = best.2 - step * ((GRID - 1) as f64 / 2.0);
    search(around, step, &mut best);
    best.2
}

/// How much of the boundary the rays from `q` cannot see (see the module docs); 0 when the
/// section is star-shaped around `q`. `fan` has [`PROBES`] rays.
fn hidden_depth(fan: &mut RayFan, contours: &[&Contour], q: DVec2) -> f64 {
    fan.cast(contours, q);
    let (mut hidden, mut reach, mut missed) = (0.0, 0.0, 0usize);
    for j in 0..PROBES {
        let hits = fan.crossings(j);
        match (hits.first(), hits.last()) {
            (Some(first), Some(last)) => {
                hidden += last - first;
                reach += last;
            }
            _ => missed += 1,
        }
    }
    if reach == 0.0 {
        return f64::INFINITY;
    }
    hidden / reach + missed as f64 / PROBES as f64
}

fn bounds(contours: &[&Contour]) -> (DVec2, DVec2) {
    contours
        .iter()
        .flat_map(|c| c.points.iter())
        .fold((DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use super::*;

    #[test]
    fn a_crescent_gets_a_center_that_sees_all_of_it() {
        // A thick C shape: its centroid lies in the bay, from where rays cross twice.
        let mut points = Vec::new();
        for k in 0..=24 {
            let a = 0.6 + (TAU - 1.2) * k as f64 / 24.0;
            points.push(DVec2::new(a.cos(), a.sin()) * 2.0);
        }
        for k in (0..=24).rev() {
            let a = 0.6 + (TAU - 1.2) * k as f64 / 24.0;
            points.push(DVec2::new(a.cos(), a.sin()) * 1.2 + DVec2::new(0.9, 0.0));
        }
        let c = Contour { points, closed: true };
        let contours = [&c];
        let centroid = crate::fit::section::center(&contours);
        let chosen = star_center(&contours, centroid);
        let mut fan = RayFan::new(PROBES);
        assert!(hidden_depth(&mut fan, &contours, chosen) < hidden_depth(&mut fan, &contours, centroid));
        assert!(c.encloses(chosen));
    }

    #[test]
    fn points_no_nearer_than_one_that_sees_everything_are_passed_over_with_the_same_result() {
        // The search scoring every point inside the section, as it first did.
        let every_point = |contours: &[&Contour], centroid: DVec2| -> DVec2 {
            let mut fan = RayFan::new(PROBES);
            let mut best = (hidden_depth(&mut fan, contours, centroid), 0.0, centroid);
            if best.0 == 0.0 {
                return centroid;
            }
            let (lo, hi) = bounds(contours);
            let mut step = (hi - lo) / (GRID - 1) as f64;
            let mut search = |origin: DVec2, step: DVec2, best: &mut (f64, f64, DVec2)| {
                for i in 0..GRID {
                    for j in 0..GRID {
                        let q = origin + DVec2::new(i as f64 * step.x, j as f64 * step.y);
                        if contours.iter().any(|c| c.encloses(q)) {
                            let candidate = (hidden_depth(&mut fan, contours, q), q.distance(centroid), q);
                            if (candidate.0, candidate.1) < (best.0, best.1) {
                                *best = candidate;
                            }
                        }
                    }
                }
            };
            search(lo, step, &mut best);
            step /= (GRID - 1) as f64 / 2.0;
            search(best.2 - step * ((GRID - 1) as f64 / 2.0), step, &mut best);
            best.2
        };
        // Crescents of several thicknesses and openings, and a crescent with a separate blob,
        // searched from their centroids and from points off them.
        let (mut sections, mut seen_whole) = (0, 0);
        for (k, (inner, shift, opening)) in [(1.2, 0.9, 0.6), (1.5, 0.4, 0.3), (0.8, 1.1, 1.0), (1.7, 0.2, 0.9)].into_iter().enumerate() {
            let mut points = Vec::new();
            for s in 0..=30 {
                let a = opening + (TAU - 2.0 * opening) * s as f64 / 30.0;
                points.push(DVec2::from_angle(a) * 2.0);
            }
            for s in (0..=30).rev() {
                let a = opening + (TAU - 2.0 * opening) * s as f64 / 30.0;
                points.push(DVec2::from_angle(a) * inner + DVec2::new(shift, 0.0));
            }
            let crescent = Contour { points, closed: true };
            let blob = Contour {
                points: (0..12).map(|s| DVec2::from_angle(TAU * s as f64 / 12.0) * 0.3 + DVec2::new(3.0, k as f64 * 0.2)).collect(),
                closed: true,
            };
            for contours in [vec![&crescent], vec![&crescent, &blob]] {
                let centroid = crate::fit::section::center(&contours);
                for from in [centroid, centroid + DVec2::new(0.3, -0.2), DVec2::new(-1.6, 0.1)] {
                    let chosen = star_center(&contours, from);
                    assert_eq!(chosen, every_point(&contours, from), "section {k} from {from}");
                    sections += 1;
                    seen_whole += usize::from(hidden_depth(&mut RayFan::new(PROBES), &contours, chosen) == 0.0);
                }
            }
        }
        assert_eq!(sections, 24);
        // Where a point sees the whole boundary, the points after it were passed over.
        assert!(seen_whole >= 3, "{seen_whole} sections seen whole from their center");
    }

    #[test]
    fn a_convex_section_keeps_its_centroid() {
        let c = Contour {
            points: vec![DVec2::new(-1.0, -1.0), DVec2::new(2.0, -1.0), DVec2::new(2.0, 1.0), DVec2::new(-1.0, 1.0)],
            closed: true,
        };
        assert_eq!(star_center(&[&c], DVec2::new(0.5, 0.0)), DVec2::new(0.5, 0.0));
    }
}
