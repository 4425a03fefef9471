//! A mesh's mirror symmetry, so that autorig finds mirror twins alike (`super::protrusions`):
//! a character's left and right legs, modelled as mirror images, are searched from tips whose
//! persistences differ (one tip is the elder where the merge tree joins them), so their level
//! sets, and the vertices each limb search keeps, may differ by a ring's vertex (wuson's hind
//! legs: 116 and 117 vertices, fitted at 10.0% and 1.6% RMS |d|).
//!
//! A mirror plane of a point set is a plane of symmetry of its covariance, so its normal is an
//! eigenvector of it, and the plane passes through the centroid. Each of the three is tried
//! (the largest eigenvalue first); the plane is the mesh's where the mirror image of every
//! searched vertex but at most [`UNMATCHED`] of them lies within [`TOLERANCE`] of the bounds'
//! diagonal of a searched vertex (a character symmetric but for a buckle or a scar: the public
//! ogre's 0.3% of its vertices), and the map sends each such vertex to the nearest one (ties
//! to the lower index), the others to no twin. Everything is measured from the vertices, so a
//! rigidly moved mesh gets the same map. A mesh with no such plane may have a near one
//! ([`near_mirror_map`]: within [`NEAR_TOLERANCE`]), a model made lopsided after it was
//! modelled symmetric.

use glam::{DMat3, DQuat, DVec3};

use crate::sweep::Key;

use super::grid::Grid;

/// A vertex's mirror image lies within this fraction of the bounds' diagonal of its twin: an
/// approximate symmetry (wuson's is within 8.7·10⁻⁴, the half-built AT-AT's 11% of its vertices
/// are not).
pub const TOLERANCE: f64 = 2e-3;

/// At most this share of the searched vertices may have no mirror image within [`TOLERANCE`]
/// (the ogre's 0.3%; the half-built AT-AT's 11% are too many).
pub const UNMATCHED: f64 = 0.01;

/// A near mirror plane ([`near_mirror_map`]): a vertex's image lies within this fraction of the
/// bounds' diagonal of its twin. A mesh modelled symmetric and then made lopsided (the dino:
/// 31% of its vertices have an image within [`TOLERANCE`], 99.1% within this) has limbs that
/// are nearly each other's images: they are made alike (`super::protrusions`), and rigged
/// alike where that fits them no worse (`super::autorig`). The faerie, posed lopsided, has
/// none (13% of its vertices within this).
pub const NEAR_TOLERANCE: f64 = 1e-2;

/// Marks a vertex with no twin in the map of [`mirror_map`] (one not searched).
pub const NO_TWIN: u32 = u32::MAX;

/// A mirror plane of a mesh and the twin of each vertex across it.
#[derive(Clone, Debug, PartialEq)]
pub struct Mirror {
    /// A point of the plane: the mean of its twin pairs' midpoints (the searched vertices'
    /// centroid where the plane through them maps too few).
    pub point: DVec3,
    /// Its unit normal.
    pub normal: DVec3,
    /// Per vertex, its twin ([`NO_TWIN`] for one not searched or with no image).
    pub map: Vec<u32>,
    /// Whether the images lie only within [`NEAR_TOLERANCE`] of their twins, not within
    /// [`TOLERANCE`] ([`near_mirror_map`]).
    pub near: bool,
}

impl Mirror {
    /// The mirror image of `p`.
    pub fn reflect(&self, p: DVec3) -> DVec3 {
        p - 2.0 * (p - self.point).dot(self.normal) * self.normal
    }

    /// The key whose cross-section is the mirror image of `key`'s: its center reflected, its
    /// frame reflected with its y axis turned back, so that it is a rotation again, and its
    /// radii read the other way round (the ray at θ of the image is the image of the ray at
    /// −θ). A sweep through the reflected keys is the mirror image of the sweep through them:
    /// the centers' spline and the rotations' interpolation (each a linear map of the
    /// quaternions, normalized) commute with the reflection.
    pub fn reflect_key(&self, key: &Key) -> Key {
        let frame = DMat3::from_quat(key.rotation.normalize());
        let h = |v: DVec3| v - 2.0 * v.dot(self.normal) * self.normal;
        let reflected = DMat3::from_cols(h(frame.x_axis), -h(frame.y_axis), h(frame.z_axis));
        let m = key.radii.len();
        Key {
            center: self.reflect(key.center),
            rotation: DQuat::from_mat3(&reflected).normalize(),
            radii: (0..m).map(|j| key.radii[(m - j) % m]).collect(),
        }
    }
}

/// Per vertex of `positions`, its mirror twin across the plane of symmetry of `vertices` (the
/// searched vertices, increasing; [`NO_TWIN`] for the others and for the few, at most
/// [`UNMATCHED`] of them, whose image has no twin); `None` where they have no such plane.
pub fn mirror_map(positions: &[DVec3], vertices: &[u32]) -> Option<Mirror> {
    mirror_map_within(positions, vertices, TOLERANCE)
}

/// [`mirror_map`] with the images within [`NEAR_TOLERANCE`] of their twins.
pub fn near_mirror_map(positions: &[DVec3], vertices: &[u32]) -> Option<Mirror> {
    mirror_map_within(positions, vertices, NEAR_TOLERANCE)
}

/// [`mirror_map`] with the images within `tolerance` of the bounds' diagonal of their twins.
fn mirror_map_within(positions: &[DVec3], vertices: &[u32], tolerance: f64) -> Option<Mirror> {
    let points: Vec<DVec3> = vertices.iter().map(|&v| positions[v as usize]).collect();
    if points.len() < 4 {
        return None;
    }
    let (lo, hi) = points.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let reach = tolerance * (hi - lo).length();
    if !(reach > 0.0 && reach.is_finite()) {
        return None;
    }
    let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let mut covariance = DMat3::ZERO;
    for &p in &points {
        let d = p - centroid;
        covariance += DMat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    let grid = Grid::new(&points, reach);
    let most_unmatched = (UNMATCHED * points.len() as f64).floor() as usize;
    // Per point, the index of its twin by the plane through `point` normal to `normal`, where
    // at most `most_unmatched` have none.
    let twins_by = |point: DVec3, normal: DVec3| -> Option<Vec<Option<usize>>> {
        let mut unmatched = 0;
        let mut twins = Vec::with_capacity(points.len());
        for &p in &points {
            let twin = grid.nearest(&points, p - 2.0 * (p - point).dot(normal) * normal);
            if twin.is_none() {
                unmatched += 1;
                if unmatched > most_unmatched {
                    return None;
                }
            }
            twins.push(twin);
        }
        Some(twins)
    };
    let (point, normal, twins) = symmetric_eigenvectors(covariance)
        .into_iter()
        .find_map(|normal| Some((centroid, normal, twins_by(centroid, normal)?)))?;
    // The plane through the pairs' midpoints, normal to their mean difference: the centroid is
    // off the plane by whatever has no twin (an ogre's lopsided grin moves it 10⁻⁴ of the
    // diagonal, which moved its reflected fingers' keys by a few percent of their radius).
    let (mut midpoints, mut across, mut pairs) = (DVec3::ZERO, DVec3::ZERO, 0);
    for (i, twin) in twins.iter().enumerate() {
        let Some(k) = *twin else { continue };
        let difference = points[i] - points[k];
        midpoints += (points[i] + points[k]) * 0.5;
        across += if difference.dot(normal) < 0.0 { -difference } else { difference };
        pairs += 1;
    }
    let refined = across.try_normalize().map(|across| (midpoints / pairs as f64, across));
    let (point, normal, twins) = refined
        .and_then(|(point, normal)| Some((point, normal, twins_by(point, normal)?)))
        .unwrap_or((point, normal, twins));
    let mut map = vec![NO_TWIN; positions.len()];
    for (&v, twin) in vertices.iter().zip(twins) {
        if let Some(k) = twin {
            map[v as usize] = vertices[k];
        }
    }
    Some(Mirror { point, normal, map, near: tolerance > TOLERANCE })
}

/// The unit eigenvectors of the symmetric matrix `m`, largest eigenvalue first (cyclic Jacobi
/// rotations).
pub fn symmetric_eigenvectors(m: DMat3) -> [DVec3; 3] {
    let mut a = m.to_cols_array_2d();
    let mut v = DMat3::IDENTITY.to_cols_array_2d();
    for _ in 0..50 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        if off <= 1e-30 * (a[0][0].powi(2) + a[1][1].powi(2) + a[2][2].powi(2)) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let (c, s) = (1.0 / (t * t + 1.0).sqrt(), t / (t * t + 1.0).sqrt());
            // A ← Jᵀ·A·J and V ← V·J, J the rotation by (c, s) in the plane of p and q.
            let turn = |row: &mut [f64; 3]| {
                let (xp, xq) = (row[p], row[q]);
                row[p] = c * xp - s * xq;
                row[q] = s * xp + c * xq;
            };
            a.iter_mut().for_each(turn);
            let (ap, aq) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| c * ap[k] - s * aq[k]);
            a[q] = std::array::from_fn(|k| s * ap[k] + c * aq[k]);
            v.iter_mut().for_each(turn);
        }
    }
    // The eigenvector of a[k][k] is v's k-th entry of every row: v = J₁·J₂·… applied on the
    // right.
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]));
    order.map(|k| DVec3::new(v[0][k], v[1][k], v[2][k]).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points of a lopsided cloud on one side of the plane x = 0, and their mirror images.
    fn mirrored_cloud() -> (Vec<DVec3>, usize) {
        let half: Vec<DVec3> = (0..200)
            .map(|i| {
                let f = i as f64;
                DVec3::new(0.3 + (f * 0.37).sin().abs() * 2.0, (f * 0.71).cos() * 3.0, (f * 0.13).sin() * 1.5 + f * 0.01)
            })
            .collect();
        let mut points = half.clone();
        points.extend(half.iter().map(|p| DVec3::new(-p.x, p.y, p.z)));
        (points, half.len())
    }

    #[test]
    fn the_eigenvectors_of_a_turned_diagonal_matrix_are_its_turned_axes() {
        let turn = DQuat::from_euler(glam::EulerRot::XYZ, 0.4, -1.1, 0.7);
        let r = DMat3::from_quat(turn);
        let m = r * DMat3::from_diagonal(DVec3::new(1.0, 5.0, 3.0)) * r.transpose();
        let [first, second, third] = symmetric_eigenvectors(m);
        for (found, axis) in [(first, DVec3::Y), (second, DVec3::Z), (third, DVec3::X)] {
            assert!(found.dot(turn * axis).abs() > 1.0 - 1e-12, "{found} against {}", turn * axis);
        }
    }

    #[test]
    fn a_mirrored_cloud_moved_anywhere_maps_each_point_to_its_image() {
        let (points, half) = mirrored_cloud();
        let turn = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, 0.9, -0.5);
        let shift = DVec3::new(5.0, -2.0, 7.5);
        let moved: Vec<DVec3> = points.iter().map(|&p| turn * p + shift).collect();
        let vertices: Vec<u32> = (0..moved.len() as u32).collect();
        let map = mirror_map(&moved, &vertices).expect("the cloud's mirror plane").map;
        for i in 0..half {
            assert_eq!(map[i] as usize, i + half, "point {i}");
            assert_eq!(map[i + half] as usize, i, "point {}", i + half);
        }
        // Within the tolerance: each image moved by a tenth of it still maps.
        let reach = TOLERANCE * {
            let (lo, hi) = moved.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
            (hi - lo).length()
        };
        let mut nudged = moved.clone();
        for p in &mut nudged[half..] {
            *p += turn * DVec3::new(0.1 * reach, 0.0, 0.0);
        }
        let map = mirror_map(&nudged, &vertices).expect("within the tolerance").map;
        assert!((0..half).all(|i| map[i] as usize == i + half));
    }

    /// A mirrored cloud whose one half is nudged by twice the tolerance, each point its own way
    /// (a lopsided model), has no mirror plane but a near one, which maps each point to its
    /// image and says it is near; nudged by twice the near tolerance it has neither. The exact
    /// cloud's plane is not near.
    #[test]
    fn a_lopsided_cloud_has_a_near_mirror_plane_only() {
        let (points, half) = mirrored_cloud();
        let vertices: Vec<u32> = (0..points.len() as u32).collect();
        assert!(!mirror_map(&points, &vertices).expect("the cloud's mirror plane").near);
        let diagonal = diagonal(&points);
        let lopsided = |by: f64| {
            let mut moved = points.clone();
            for (i, p) in moved[half..].iter_mut().enumerate() {
                let f = i as f64;
                let direction = DVec3::new((f * 1.3).sin(), (f * 2.9).cos(), (f * 0.7).sin()).normalize();
                *p += direction * (by * diagonal);
            }
            moved
        };
        let moved = lopsided(2.0 * TOLERANCE);
        assert!(mirror_map(&moved, &vertices).is_none());
        let near = near_mirror_map(&moved, &vertices).expect("a near mirror plane");
        assert!(near.near);
        assert!((0..half).all(|i| near.map[i] as usize == i + half && near.map[i + half] as usize == i));
        assert!(near_mirror_map(&lopsided(2.0 * NEAR_TOLERANCE), &vertices).is_none());
    }

    /// The diagonal of the bounds of `points`.
    fn diagonal(points: &[DVec3]) -> f64 {
        let (lo, hi) = points.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
        (hi - lo).length()
    }

    /// `points` with each image `half + i` of `moved` moved off by ten times the tolerance.
    fn with_images_moved(mut points: Vec<DVec3>, half: usize, moved: impl Iterator<Item = usize>) -> Vec<DVec3> {
        let off = 10.0 * TOLERANCE * diagonal(&points);
        for i in moved {
            points[half + i].y += off;
        }
        points
    }

    #[test]
    fn a_cloud_with_no_mirror_plane_has_no_map() {
        let (points, half) = mirrored_cloud();
        let vertices: Vec<u32> = (0..points.len() as u32).collect();
        // Six images of 400 points moved off by ten times the tolerance (1.5%, over
        // [`UNMATCHED`]): no plane.
        let points = with_images_moved(points, half, (17..23).map(|i| i * 7 % half));
        assert!(mirror_map(&points, &vertices).is_none());
        // Unsearched vertices take no part: without those, the rest is symmetric.
        let off: Vec<u32> = (17..23).map(|i| i * 7 % half).flat_map(|i| [i as u32, (half + i) as u32]).collect();
        let searched: Vec<u32> = vertices.iter().copied().filter(|v| !off.contains(v)).collect();
        let map = mirror_map(&points, &searched).expect("the rest is symmetric").map;
        assert!(off.iter().all(|&v| map[v as usize] == NO_TWIN));
        assert!((0..half).filter(|i| !off.contains(&(*i as u32))).all(|i| map[i] as usize == i + half));
    }

    #[test]
    fn a_cloud_symmetric_but_for_a_few_points_maps_the_rest() {
        let (points, half) = mirrored_cloud();
        let vertices: Vec<u32> = (0..points.len() as u32).collect();
        // Two images of 400 points moved off: they and their originals, 1% of the points (within
        // [`UNMATCHED`]), have no twin; the rest keep theirs.
        let moved = [50, 120];
        let points = with_images_moved(points, half, moved.into_iter());
        let map = mirror_map(&points, &vertices).expect("symmetric but for four points").map;
        // Three moved, six points without a twin (1.5%), are too many.
        let three = with_images_moved(points.clone(), half, [199].into_iter());
        assert!(mirror_map(&three, &vertices).is_none());
        for i in 0..half {
            if moved.contains(&i) {
                assert_eq!((map[i], map[half + i]), (NO_TWIN, NO_TWIN), "point {i}");
            } else {
                assert_eq!((map[i] as usize, map[half + i] as usize), (half + i, i), "point {i}");
            }
        }
    }

    /// A sweep through reflected keys is the mirror image of the sweep: every surface point
    /// S(θ, t) reflected is the reflected sweep's S(−θ, t), on a curved, twisted sweep with
    /// uneven radii, across an oblique plane.
    #[test]
    fn a_sweep_through_reflected_keys_is_the_mirror_image_of_the_sweep() {
        use crate::sweep::Sweep;
        let keys: Vec<Key> = (0..5)
            .map(|i| {
                let f = i as f64;
                let rotation = DQuat::from_euler(glam::EulerRot::XYZ, 0.2 * f, 0.3 - 0.1 * f, 0.25 * f);
                let radii = (0..12).map(|j| 0.5 + 0.1 * f + 0.2 * ((j as f64) * 0.9 + f).sin().abs()).collect();
                Key { center: DVec3::new(f, (0.7 * f).sin(), 0.2 * f * f), rotation, radii }
            })
            .collect();
        let mirror = Mirror {
            point: DVec3::new(0.3, -1.0, 2.0),
            normal: DVec3::new(0.6, 0.0, 0.8),
            map: Vec::new(),
            near: false,
        };
        let reflected: Vec<Key> = keys.iter().map(|key| mirror.reflect_key(key)).collect();
        assert!(reflected.iter().all(|key| (DMat3::from_quat(key.rotation).determinant() - 1.0).abs() < 1e-12));
        let (sweep, image) = (Sweep::try_new(&keys, None).unwrap(), Sweep::try_new(&reflected, None).unwrap());
        let mut worst: f64 = 0.0;
        for i in 0..=20 {
            for j in 0..24 {
                let (t, theta) = (i as f64 / 20.0, std::f64::consts::TAU * j as f64 / 24.0 + 0.1);
                let expected = mirror.reflect(sweep.surface_point(theta, t));
                worst = worst.max(image.surface_point(-theta, t).distance(expected));
            }
        }
        assert!(worst < 1e-9, "the reflected sweep misses the image by {worst}");
    }
}
