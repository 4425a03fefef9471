//! A mesh's mirror symmetry, so that autorig finds mirror twins alike (`super::protrusions`):
//! a character's left and right legs, modelled as mirror images, are searched from tips whose
//! persistences differ (one tip is the elder where the merge tree joins them), so their level
//! sets, and the vertices each limb search keeps, may differ by a ring's vertex (wuson's hind
//! legs: 116 and 117 vertices, fitted at 10.0% and 1.6% RMS |d|).
//!
//! A mirror plane of a point set is a plane of symmetry of its covariance, so its normal is an
//! eigenvector of it, and the plane passes through the centroid. Each of the three is tried
//! (the largest eigenvalue first); the plane is the mesh's where every searched vertex's mirror
//! image lies within [`TOLERANCE`] of the bounds' diagonal of a searched vertex, and the map
//! sends each vertex to the nearest one (ties to the lower index). Everything is measured from
//! the vertices, so a rigidly moved mesh gets the same map.

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use glam::{DMat3, DVec3, IVec3};

use crate::mesh::weld::PositionHasher;

/// A vertex's mirror image lies within this fraction of the bounds' diagonal of its twin: an
/// approximate symmetry (wuson's is within 8.7·10⁻⁴, the half-built AT-AT's 11% of its vertices
/// are not).
pub const TOLERANCE: f64 = 2e-3;

/// Marks a vertex with no twin in the map of [`mirror_map`] (one not searched).
pub const NO_TWIN: u32 = u32::MAX;

/// Per vertex of `positions`, its mirror twin across the plane of symmetry of `vertices` (the
/// searched vertices, increasing; [`NO_TWIN`] for the others); `None` where they have none.
pub fn mirror_map(positions: &[DVec3], vertices: &[u32]) -> Option<Vec<u32>> {
    let points: Vec<DVec3> = vertices.iter().map(|&v| positions[v as usize]).collect();
    if points.len() < 4 {
        return None;
    }
    let (lo, hi) = points.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let reach = TOLERANCE * (hi - lo).length();
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
    symmetric_eigenvectors(covariance).into_iter().find_map(|normal| {
        let mut map = vec![NO_TWIN; positions.len()];
        for (&v, &p) in vertices.iter().zip(&points) {
            let image = p - 2.0 * (p - centroid).dot(normal) * normal;
            map[v as usize] = vertices[grid.nearest(&points, image)?];
        }
        Some(map)
    })
}

/// Points bucketed in cubes twice as wide as the reach of a search, so that a search looks in
/// at most two cubes along each axis.
struct Grid {
    reach: f64,
    cells: HashMap<IVec3, Vec<usize>, BuildHasherDefault<PositionHasher>>,
}

impl Grid {
    fn new(points: &[DVec3], reach: f64) -> Grid {
        let mut cells: HashMap<IVec3, Vec<usize>, BuildHasherDefault<PositionHasher>> = HashMap::default();
        for (i, &p) in points.iter().enumerate() {
            cells.entry(Grid::cell(p, reach)).or_default().push(i);
        }
        Grid { reach, cells }
    }

    fn cell(p: DVec3, reach: f64) -> IVec3 {
        (p / (2.0 * reach)).floor().as_ivec3()
    }

    /// The index of the point of `points` nearest `q` within the reach (the lower index of
    /// two as near); `None` where none is.
    fn nearest(&self, points: &[DVec3], q: DVec3) -> Option<usize> {
        let (lo, hi) = (Grid::cell(q - DVec3::splat(self.reach), self.reach), Grid::cell(q + DVec3::splat(self.reach), self.reach));
        let mut best: Option<(f64, usize)> = None;
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    let Some(bucket) = self.cells.get(&IVec3::new(x, y, z)) else { continue };
                    for &i in bucket {
                        let d = points[i].distance(q);
                        if d <= self.reach && best.is_none_or(|(bd, bi)| d < bd || (d == bd && i < bi)) {
                            best = Some((d, i));
                        }
                    }
                }
            }
        }
        best.map(|(_, i)| i)
    }
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
    use glam::DQuat;

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
        let map = mirror_map(&moved, &vertices).expect("the cloud's mirror plane");
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
        let map = mirror_map(&nudged, &vertices).expect("within the tolerance");
        assert!((0..half).all(|i| map[i] as usize == i + half));
    }

    #[test]
    fn a_cloud_with_no_mirror_plane_has_no_map() {
        let (mut points, half) = mirrored_cloud();
        // One image moved off by ten times the tolerance: no plane maps every point.
        let (lo, hi) = points.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
        points[half + 17].y += 10.0 * TOLERANCE * (hi - lo).length();
        let vertices: Vec<u32> = (0..points.len() as u32).collect();
        assert!(mirror_map(&points, &vertices).is_none());
        // Unsearched vertices take no part: without that one, the rest is symmetric but for its
        // twin, which is left out too.
        let searched: Vec<u32> = vertices.iter().copied().filter(|&v| v != 17 && v != (half + 17) as u32).collect();
        let map = mirror_map(&points, &searched).expect("the rest is symmetric");
        assert_eq!((map[17], map[half + 17]), (NO_TWIN, NO_TWIN));
    }
}
