//! The first guess at a part's axis: a polyline given by the user, or the part's principal
//! axis (the direction of largest variance of its vertices) through its centroid.

use glam::{DMat3, DVec3};

/// A polyline parametrized by arc length.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    points: Vec<DVec3>,
    /// Arc length at each point, from 0.
    lengths: Vec<f64>,
}

impl Polyline {
    /// The polyline through `points`, dropping repeated points and points so near the previous
    /// one that the arc length does not grow in floating point (a segment of zero span would
    /// make [`point`](Polyline::point) divide by zero); `None` when fewer than two distinct
    /// points remain or a point is not finite.
    pub fn new(points: &[DVec3]) -> Option<Polyline> {
        if points.iter().any(|p| !p.is_finite()) {
            return None;
        }
        let mut kept: Vec<DVec3> = Vec::with_capacity(points.len());
        let mut lengths: Vec<f64> = Vec::with_capacity(points.len());
        for &p in points {
            match (kept.last(), lengths.last()) {
                (Some(&last), Some(&length)) => {
                    let grown = length + last.distance(p);
                    if grown > length {
                        kept.push(p);
                        lengths.push(grown);
                    }
                }
                _ => {
                    kept.push(p);
                    lengths.push(0.0);
                }
            }
        }
        (kept.len() >= 2).then_some(Polyline { points: kept, lengths })
    }

    /// The polyline's length.
    pub fn length(&self) -> f64 {
        self.lengths.last().copied().unwrap_or(0.0)
    }

    /// The point at arc length `s`, extrapolated along the end segments beyond `[0, length]`.
    pub fn point(&self, s: f64) -> DVec3 {
        let i = self.segment_at(s);
        let (a, b) = (self.points[i], self.points[i + 1]);
        let span = self.lengths[i + 1] - self.lengths[i];
        a + (b - a) * ((s - self.lengths[i]) / span)
    }

    /// The unit tangent at arc length `s`: at a corner, the mean of the two segments' directions.
    pub fn tangent(&self, s: f64) -> DVec3 {
        let i = self.segment_at(s);
        let direction = |k: usize| (self.points[k + 1] - self.points[k]).normalize();
        let here = direction(i);
        let at_corner = |k: usize| (self.lengths[k] - s).abs() <= 1e-12 * self.length();
        if i > 0 && at_corner(i) {
            (direction(i - 1) + here).try_normalize().unwrap_or(here)
        } else if i + 2 < self.points.len() && at_corner(i + 1) {
            (direction(i + 1) + here).try_normalize().unwrap_or(here)
        } else {
            here
        }
    }

    /// The direction of the chord from arc length s − h to s + h, both clamped to
    /// [0, length]: a tangent that does not follow the polyline's small kinks; the end
    /// segment's direction where the clamped chord vanishes.
    pub fn chord_tangent(&self, s: f64, h: f64) -> DVec3 {
        let length = self.length();
        let (a, b) = ((s - h).clamp(0.0, length), (s + h).clamp(0.0, length));
        (self.point(b) - self.point(a)).try_normalize().unwrap_or_else(|| self.tangent(s))
    }

    /// The arc length of the point of the polyline (extended along its end segments) nearest
    /// to `p`.
    pub fn project(&self, p: DVec3) -> f64 {
        let last = self.points.len() - 2;
        let mut best = (f64::INFINITY, 0.0);
        for (i, pair) in self.points.windows(2).enumerate() {
            let (a, b) = (pair[0], pair[1]);
            let span = self.lengths[i + 1] - self.lengths[i];
            let mut u = (p - a).dot(b - a) / (span * span);
            if i > 0 {
                u = u.max(0.0);
            }
            if i < last {
                u = u.min(1.0);
            }
            let distance = p.distance_squared(a + (b - a) * u);
            if distance < best.0 {
                best = (distance, self.lengths[i] + u * span);
            }
        }
        best.1
    }

    /// The segment holding arc length `s` (the first or last one beyond the ends).
    fn segment_at(&self, s: f64) -> usize {
        let inner = &self.lengths[1..self.lengths.len() - 1];
        inner.partition_point(|&l| l <= s)
    }
}

/// The centroid of `points` and their principal axis (unit; the eigenvector of the largest
/// eigenvalue of the covariance matrix, by power iteration from its largest column).
pub fn principal_axis(points: &[DVec3]) -> (DVec3, DVec3) {
    let centroid = points.iter().copied().sum::<DVec3>() / points.len().max(1) as f64;
    let mut covariance = DMat3::ZERO;
    for p in points {
        let d = *p - centroid;
        covariance += DMat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    let columns = [covariance.x_axis, covariance.y_axis, covariance.z_axis];
    let start = columns.into_iter().max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()));
    let mut axis = start.and_then(DVec3::try_normalize).unwrap_or(DVec3::X);
    for _ in 0..100 {
        let next = (covariance * axis).try_normalize().unwrap_or(axis);
        let converged = next.dot(axis) > 1.0 - 1e-15;
        axis = next;
        if converged {
            break;
        }
    }
    (centroid, axis)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_too_near_to_grow_the_arc_length_is_dropped() {
        // 1e-17 from its neighbour, 2 units along: the arc length stays 2.0 in f64. Kept, its
        // segment's span would be zero and the point at the end infinite.
        let near = DVec3::new(1e-17, 0.0, 2.0);
        assert_eq!(2.0 + near.distance(2.0 * DVec3::Z), 2.0);
        let line = Polyline::new(&[DVec3::ZERO, 2.0 * DVec3::Z, near]).unwrap();
        assert_eq!(line.length(), 2.0);
        for s in [0.0, 1.0, 2.0, 2.5] {
            assert!(line.point(s).is_finite() && line.tangent(s).is_finite(), "at {s}");
        }
        assert_eq!(line.point(2.0), 2.0 * DVec3::Z);
    }

    #[test]
    fn polyline_points_tangents_and_projection() {
        let line = Polyline::new(&[DVec3::ZERO, DVec3::X, DVec3::X, DVec3::new(1.0, 2.0, 0.0)]).unwrap();
        assert_eq!(line.length(), 3.0);
        assert_eq!(line.point(0.5), DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(line.point(2.0), DVec3::new(1.0, 1.0, 0.0));
        assert_eq!(line.point(-1.0), DVec3::new(-1.0, 0.0, 0.0));
        assert_eq!(line.point(4.0), DVec3::new(1.0, 3.0, 0.0));
        assert_eq!(line.tangent(0.5), DVec3::X);
        assert!((line.tangent(1.0) - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
        assert_eq!(line.project(DVec3::new(0.25, -1.0, 0.0)), 0.25);
        assert_eq!(line.project(DVec3::new(-2.0, 0.1, 0.0)), -2.0);
        assert_eq!(line.project(DVec3::new(1.5, 2.5, 0.0)), 3.5);
        assert!(Polyline::new(&[DVec3::ONE, DVec3::ONE]).is_none());
    }

    #[test]
    fn principal_axis_of_a_stretched_cloud() {
        let direction = DVec3::new(1.0, 2.0, -0.5).normalize();
        let side = direction.any_orthonormal_vector();
        let points: Vec<DVec3> =
            (0..100).map(|i| direction * (i as f64 - 49.5) + side * ((i % 7) as f64 - 3.0) * 0.3).collect();
        let (centroid, axis) = principal_axis(&points);
        assert!(axis.dot(direction).abs() > 1.0 - 1e-6, "{axis}");
        assert!((centroid - side * points.iter().map(|p| p.dot(side)).sum::<f64>() / 100.0).length() < 1e-9);
    }
}
