//! What is under the pointer: the nearest mesh triangle along the pointer's ray (Möller–Trumbore
//! over every triangle, in parallel; run on a press, never per frame) and the key ring drawn
//! nearest to the pointer on screen.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// A triangle hit by a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray.
    pub distance: f32,
    /// The triangle's corners (vertex indices).
    pub corners: [u32; 3],
    /// Index of the triangle.
    pub triangle: usize,
    /// The point hit.
    pub point: Vec3,
}

impl Hit {
    /// The corner nearest to the point hit.
    pub fn nearest_corner(&self, positions: &[Vec3]) -> u32 {
        let distance = |v: u32| positions[v as usize].distance_squared(self.point);
        self.corners.into_iter().min_by(|&a, &b| distance(a).total_cmp(&distance(b))).expect("three corners")
    }
}

/// The first triangle the ray (`origin`, unit `direction`) meets, both sides counting.
pub fn pick_triangle(positions: &[Vec3], triangles: &[[u32; 3]], origin: Vec3, direction: Vec3) -> Option<Hit> {
    triangles
        .par_iter()
        .enumerate()
        .filter_map(|(triangle, &corners)| {
            let [a, b, c] = corners.map(|v| positions[v as usize]);
            let distance = intersect(origin, direction, a, b, c)?;
            Some(Hit { distance, corners, triangle, point: origin + distance * direction })
        })
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
}

/// Möller–Trumbore: the distance along the ray to triangle (a, b, c), if it is hit in front.
fn intersect(origin: Vec3, direction: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<f32> {
    let (ab, ac) = (b - a, c - a);
    let p = direction.cross(ac);
    let determinant = ab.dot(p);
    if determinant.abs() < 1e-12 {
        return None;
    }
    let inverse = 1.0 / determinant;
    let to_origin = origin - a;
    let u = to_origin.dot(p) * inverse;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = to_origin.cross(ab);
    let v = direction.dot(q) * inverse;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let distance = ac.dot(q) * inverse;
    (distance > 0.0).then_some(distance)
}

/// A key cross-section as drawn: its sweep, its key and points around its ring in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct RingOnScreen {
    /// Index of the sweep.
    pub sweep: usize,
    /// Index of the key.
    pub key: usize,
    /// Ring points projected into the window (points behind the eye left out).
    pub pixels: Vec<Vec2>,
}

/// The ring with a point nearest to `pixel`, if within `reach` pixels.
pub fn pick_ring(rings: &[RingOnScreen], pixel: Vec2, reach: f32) -> Option<(usize, usize)> {
    rings
        .iter()
        .filter_map(|ring| {
            let nearest = ring.pixels.iter().map(|p| p.distance(pixel)).fold(f32::INFINITY, f32::min);
            (nearest <= reach).then_some((nearest, ring.sweep, ring.key))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, sweep, key)| (sweep, key))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_of_two_stacked_triangles_is_hit() {
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(1.0, 0.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0),
        ];
        let triangles = [[0, 1, 2], [3, 4, 5]];
        let origin = Vec3::new(0.2, 0.2, 5.0);
        let hit = pick_triangle(&positions, &triangles, origin, -Vec3::Z).unwrap();
        assert_eq!(hit.triangle, 1);
        assert!((hit.distance - 3.0).abs() < 1e-6 && hit.point.distance(Vec3::new(0.2, 0.2, 2.0)) < 1e-6);
        assert_eq!(hit.nearest_corner(&positions), 3);
        assert_eq!(pick_triangle(&positions, &triangles, origin, Vec3::Z), None, "behind the ray");
        assert_eq!(pick_triangle(&positions, &triangles, Vec3::new(0.9, 0.9, 5.0), -Vec3::Z), None, "outside");
    }

    #[test]
    fn ring_within_reach_is_picked() {
        let ring = |sweep, key, x: f32| RingOnScreen {
            sweep,
            key,
            pixels: (0..8).map(|i| Vec2::new(x, 10.0 * i as f32)).collect(),
        };
        let rings = [ring(0, 0, 100.0), ring(1, 3, 120.0)];
        assert_eq!(pick_ring(&rings, Vec2::new(114.0, 35.0), 8.0), Some((1, 3)));
        assert_eq!(pick_ring(&rings, Vec2::new(300.0, 35.0), 8.0), None);
    }
}
