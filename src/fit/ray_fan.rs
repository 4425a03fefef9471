//! A fan of rays from one center in a section's plane, at θ_j = 2πj/M (the angles at which a
//! key's radii are sampled, §3), and where each crosses the section's boundary.
//!
//! Each segment is tested only against the rays within one ray's step of the angles it spans
//! as seen from the center, so a fan over S segments costs about S + M tests, not
//! M·S. A segment seen from (nearly) on its own line, or from (nearly) one of its ends, spans
//! up to π and is tested against every ray. The tests themselves are the single ray's
//! (`ray_hit`), so the fan's crossings are the ones each ray finds alone, to the bit: which
//! rays a segment is tested against only has to include every ray it may meet. Angles are
//! compared as pseudo-angles (`pseudo_angle`, increasing with the angle, no arctangent), and
//! the rays a segment spans are counted from a table of the rays below each of 4M equal steps
//! of pseudo-angle (a ray or so per step), as a search among the rays' own would count them.

use std::f64::consts::TAU;

use glam::DVec2;

use super::section::Contour;

/// A segment whose angle seen from the center comes within about this (radians) of π is tested
/// against every ray: the tangent of its angle's difference from π is at most this.
const NEARLY_STRAIGHT: f64 = 0.01;
/// A segment whose nearer end lies within this fraction of its length from the center is
/// tested against every ray (the single ray's end slack then spans a wide angle).
const NEAR_END: f64 = 1e-6;

/// `count` rays and the crossings each found on the last [`RayFan::cast`].
pub struct RayFan {
    directions: Vec<DVec2>,
    /// The rays' pseudo-angles, increasing from 0 (ray 0).
    ray_angles: Vec<f64>,
    /// For each of `count` equal steps of pseudo-angle per unit (4·`count` in all, and one
    /// for 4 itself), how many rays lie below the step before it: where a count of the rays
    /// below a pseudo-angle in that step may start ([`RayFan::rays_below`]).
    rays_before_step: Vec<usize>,
    crossings: Vec<Vec<f64>>,
    /// The pseudo-angles of a contour's points seen from the center, one contour at a time.
    angles: Vec<f64>,
}

impl RayFan {
    /// A fan of `count` rays, ray j at θ_j = 2πj/count.
    pub fn new(count: usize) -> Self {
        let directions: Vec<DVec2> = (0..count)
            .map(|j| {
                let angle = TAU * j as f64 / count as f64;
                DVec2::new(angle.cos(), angle.sin())
            })
            .collect();
        let ray_angles: Vec<f64> = directions.iter().map(|&d| pseudo_angle(d)).collect();
        let rays_before_step = (0..=4 * count)
            .map(|step| ray_angles.partition_point(|&r| r < (step as f64 - 1.0) / count as f64))
            .collect();
        RayFan { directions, ray_angles, rays_before_step, crossings: vec![Vec::new(); count], angles: Vec::new() }
    }

    /// How many rays lie at pseudo-angles below `angle`, or also at it where `or_at`: the
    /// count a search among the rays' angles gives, from the first ray of its step on.
    fn rays_below(&self, angle: f64, or_at: bool) -> usize {
        let count = self.ray_angles.len();
        let step = ((angle * count as f64) as usize).min(4 * count);
        let mut below = self.rays_before_step[step];
        while below < count && (self.ray_angles[below] < angle || (or_at && self.ray_angles[below] == angle)) {
            below += 1;
        }
        below
    }

    /// Casts the fan from `center` (in-plane coordinates) onto the contours.
    pub fn cast(&mut self, contours: &[&Contour], center: DVec2) {
        for crossings in &mut self.crossings {
            crossings.clear();
        }
        let count = self.directions.len();
        for contour in contours {
            self.angles.clear();
            self.angles.extend(contour.points.iter().map(|p| pseudo_angle(*p - center)));
            let n = contour.points.len();
            for (i, (a, b)) in contour.segments().enumerate() {
                let next = if i + 1 == n { 0 } else { i + 1 };
                let (first, rays) =
                    self.spanned(a - center, b - center, self.angles[i], self.angles[next]).unwrap_or((0, count));
                for k in 0..rays {
                    let j = if first + k >= count { first + k - count } else { first + k };
                    if let Some(distance) = ray_hit(center, self.directions[j], a, b) {
                        self.crossings[j].push(distance);
                    }
                }
            }
        }
        for crossings in &mut self.crossings {
            merge_shared_points(crossings);
        }
    }

    /// The distances along ray `j` to each of its crossings on the last cast, increasing.
    pub fn crossings(&self, j: usize) -> &[f64] {
        &self.crossings[j]
    }

    /// The rays a segment from `a` to `b` (relative to the center, at pseudo-angles `angle_a`
    /// and `angle_b`) may meet: the first and how many, around the fan; `None` when it may meet
    /// any. Those are the rays whose angle lies on the arc the segment spans, and one more on
    /// either side for rounding.
    fn spanned(&self, a: DVec2, b: DVec2, angle_a: f64, angle_b: f64) -> Option<(usize, usize)> {
        let count = self.directions.len();
        let near_squared = NEAR_END * NEAR_END * a.distance_squared(b);
        if a.length_squared() <= near_squared || b.length_squared() <= near_squared {
            return None;
        }
        let (cross, dot) = (a.perp_dot(b), a.dot(b));
        if dot < 0.0 && cross.abs() <= NEARLY_STRAIGHT * -dot {
            return None;
        }
        // Counter-clockwise from `from` to `to`: the arc of less than π.
        let (from, to) = if cross >= 0.0 { (angle_a, angle_b) } else { (angle_b, angle_a) };
        let first = self.rays_below(from, false) as i64 - 1;
        let last = self.rays_below(to, true) as i64;
        let last = if to < from { last + count as i64 } else { last };
        let rays = (last - first + 1) as usize;
        (rays < count).then(|| (first.rem_euclid(count as i64) as usize, rays))
    }
}

/// An angle-like measure of the direction of `d`, in [0, 4] (4 only where rounding meets a
/// direction just below the x axis): increasing with its angle from the x axis
/// counter-clockwise, as the arctangent's is, and cheaper; 0 for the zero vector.
fn pseudo_angle(d: DVec2) -> f64 {
    let sum = d.x.abs() + d.y.abs();
    if sum == 0.0 {
        return 0.0;
    }
    let (x, y) = (d.x / sum, d.y / sum);
    match (y >= 0.0, x >= 0.0) {
        (true, true) => y,
        (true, false) => 1.0 - x,
        (false, false) => 2.0 - y,
        (false, true) => 3.0 + x,
    }
}

/// Fans kept for reuse on a thread, at most this many.
const KEPT_FANS: usize = 4;

thread_local! {
    /// Fans this thread has cast and may cast again: a fit samples thousands of sections with
    /// fans of the same few sizes, and a new fan computes its directions and allocates its
    /// rays' lists.
    static KEPT: std::cell::RefCell<Vec<RayFan>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Calls `cast_with` with a fan of `count` rays, one this thread used before where it has one.
pub fn with_fan<R>(count: usize, cast_with: impl FnOnce(&mut RayFan) -> R) -> R {
    let kept = KEPT.with_borrow_mut(|kept| {
        let index = kept.iter().position(|fan| fan.directions.len() == count)?;
        Some(kept.swap_remove(index))
    });
    let mut fan = kept.unwrap_or_else(|| RayFan::new(count));
    let result = cast_with(&mut fan);
    KEPT.with_borrow_mut(|kept| {
        if kept.len() < KEPT_FANS {
            kept.push(fan);
        }
    });
    result
}

/// The distances along the single ray from `center` at `angle` to each crossing of the
/// contours, increasing: what one ray of a [`RayFan`] finds, by testing every segment.
#[cfg(test)]
pub fn ray_hits(contours: &[&Contour], center: DVec2, angle: f64) -> Vec<f64> {
    let direction = DVec2::new(angle.cos(), angle.sin());
    let mut hits: Vec<f64> =
        contours.iter().flat_map(|c| c.segments()).filter_map(|(a, b)| ray_hit(center, direction, a, b)).collect();
    merge_shared_points(&mut hits);
    hits
}

/// Sorts a ray's crossings and counts a crossing through a shared point of two segments, which
/// the ray meets on both, once.
fn merge_shared_points(hits: &mut Vec<f64>) {
    hits.sort_by(f64::total_cmp);
    hits.dedup_by(|b, a| *b - *a <= 1e-9 * a.abs().max(f64::MIN_POSITIVE));
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A star-ish closed contour of `n` points with a wobbling radius, and a crescent-like
    /// dent so that some rays cross it more than twice.
    fn wobbly(n: usize, seed: f64) -> Contour {
        let points = (0..n)
            .map(|k| {
                let a = TAU * k as f64 / n as f64;
                let r = 2.0 + 0.6 * (3.0 * a + seed).sin() + 0.4 * (7.0 * a - seed).cos();
                DVec2::new(a.cos(), a.sin()) * r + DVec2::new(0.3, -0.2)
            })
            .collect();
        Contour { points, closed: true }
    }

    #[test]
    fn the_fan_finds_what_each_ray_finds_alone() {
        let shapes = [wobbly(40, 0.3), wobbly(97, 1.7), wobbly(12, 2.9)];
        let mut compared = 0;
        for count in [4, 16, 48, 64] {
            let mut fan = RayFan::new(count);
            for shape in &shapes {
                let contours = [shape];
                // Centers inside, outside, on a vertex, on an edge's midpoint and near a vertex.
                let p = shape.points[5];
                let mid = 0.5 * (shape.points[7] + shape.points[8]);
                // And a grid over the shape and around it.
                let grid = (0..49).map(|k| DVec2::new((k % 7) as f64 - 3.0, (k / 7) as f64 - 3.0) * 0.9);
                let special = [DVec2::ZERO, DVec2::new(3.5, 1.0), p, mid, p + DVec2::splat(1e-9), DVec2::new(1.2, 0.4)];
                for center in special.into_iter().chain(grid) {
                    fan.cast(&contours, center);
                    for j in 0..count {
                        let alone = ray_hits(&contours, center, TAU * j as f64 / count as f64);
                        assert_eq!(fan.crossings(j), alone.as_slice(), "ray {j} of {count} from {center}");
                        compared += alone.len();
                    }
                }
            }
        }
        assert!(compared > 1000, "only {compared} crossings compared");
    }

    #[test]
    fn a_segment_is_tested_against_the_rays_within_a_step_of_its_angles() {
        let fan = RayFan::new(8);
        // From the origin, (1, 0.1) to (0.1, 1) spans θ from 0.0997 to 1.4711 rad, which holds
        // ray 1 (π/4); within a step (π/4) of it lie rays 0 and 2 as well, not 7 or 3.
        let spanned = |a: DVec2, b: DVec2| fan.spanned(a, b, pseudo_angle(a), pseudo_angle(b));
        assert_eq!(spanned(DVec2::new(1.0, 0.1), DVec2::new(0.1, 1.0)), Some((0, 3)));
        assert_eq!(spanned(DVec2::new(0.1, 1.0), DVec2::new(1.0, 0.1)), Some((0, 3)));
        // Across θ = 0: from -0.5 to 0.5 rad, rays 7, 0 and 1.
        assert_eq!(spanned(DVec2::from_angle(-0.5), DVec2::from_angle(0.5)), Some((7, 3)));
        // Across θ = π: from 3 to -3 rad (3.28), rays 3 (3π/4), 4 (π) and 5 (5π/4).
        assert_eq!(spanned(DVec2::from_angle(3.0), DVec2::from_angle(-3.0)), Some((3, 3)));
        // Seen from on its own line, a segment may meet any ray.
        assert_eq!(spanned(DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0)), None);
        assert_eq!(spanned(DVec2::ZERO, DVec2::new(1.0, 0.0)), None);
    }

    #[test]
    fn the_rays_below_an_angle_are_those_a_search_among_them_finds() {
        for count in [1, 3, 4, 7, 32, 48] {
            let fan = RayFan::new(count);
            let mut angles: Vec<f64> = (0..=4000).map(|k| k as f64 / 1000.0).collect();
            angles.extend(fan.ray_angles.iter().flat_map(|&r| [r, r.next_down(), r.next_up()]));
            angles.extend([-0.5, 4.5, f64::NAN]);
            for angle in angles {
                let below = fan.ray_angles.partition_point(|&r| r < angle);
                let at_or_below = fan.ray_angles.partition_point(|&r| r <= angle);
                assert_eq!(fan.rays_below(angle, false), below, "{count} rays, below {angle}");
                assert_eq!(fan.rays_below(angle, true), at_or_below, "{count} rays, at or below {angle}");
            }
        }
    }

    #[test]
    fn the_pseudo_angle_increases_with_the_angle() {
        let angles: Vec<f64> = (0..10_000).map(|k| TAU * k as f64 / 10_000.0).collect();
        let pseudo: Vec<f64> = angles.iter().map(|&a| pseudo_angle(DVec2::from_angle(a) * 3.7)).collect();
        assert!(pseudo.windows(2).all(|pair| pair[0] < pair[1]), "not increasing");
        assert!(pseudo[0] == 0.0 && pseudo[9_999] < 4.0);
        assert_eq!(pseudo_angle(DVec2::new(0.0, 2.0)), 1.0);
        assert_eq!(pseudo_angle(DVec2::new(-2.0, 0.0)), 2.0);
        assert_eq!(pseudo_angle(DVec2::new(0.0, -2.0)), 3.0);
    }
}
