//! Vertex normals of the deformed mesh: for each vertex, the sum of the cross products of the
//! edges of its incident triangles (each cross product is twice the triangle's area times its
//! normal, so the sum is area-weighted), normalized. Polygons count as their fan triangles.
//!
//! Data flow: rig → sweep → sweep coefficients → bind → deform → **normals** → output.
//!
//! The adjacency is built once per mesh; every vertex then gathers its own sum, so no atomics
//! (and no float atomics) are needed on the GPU. The f32 twin of the GPU kernel is
//! [`crate::cpu::normals`].

use glam::DVec3;
use rayon::prelude::*;

use crate::mesh::Faces;

/// For each vertex i, the other two corners (j, k) of every triangle (i, j, k) incident to it,
/// in the triangle's winding order, so that (p_j − p_i) × (p_k − p_i) is the triangle's
/// area-weighted normal. Compressed rows: vertex i's corners are
/// `corners[offsets[i]..offsets[i + 1]]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NormalAdjacency {
    /// `vertex count + 1` row starts into `corners`.
    pub offsets: Vec<u32>,
    /// Corner pairs, row by row.
    pub corners: Vec<[u32; 2]>,
}

impl NormalAdjacency {
    /// Builds the adjacency of the fan triangulation of `faces` over `vertex_count` vertices.
    pub fn new(faces: &Faces, vertex_count: usize) -> NormalAdjacency {
        let mut counts = vec![0u32; vertex_count + 1];
        for [a, b, c] in faces.triangles() {
            for v in [a, b, c] {
                counts[v as usize + 1] += 1;
            }
        }
        for i in 0..vertex_count {
            counts[i + 1] += counts[i];
        }
        let offsets = counts;
        let mut cursor = offsets.clone();
        let mut corners = vec![[0u32; 2]; offsets[vertex_count] as usize];
        for [a, b, c] in faces.triangles() {
            for (v, pair) in [(a, [b, c]), (b, [c, a]), (c, [a, b])] {
                corners[cursor[v as usize] as usize] = pair;
                cursor[v as usize] += 1;
            }
        }
        NormalAdjacency { offsets, corners }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The corner pairs of vertex `i`.
    pub fn incident(&self, i: usize) -> &[[u32; 2]] {
        &self.corners[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}

/// Area-weighted unit normals of every vertex (f64 reference). A vertex with no incident
/// triangle, or whose triangles cancel or have no area, gets the zero vector.
pub fn vertex_normals(positions: &[DVec3], adjacency: &NormalAdjacency) -> Vec<DVec3> {
    (0..adjacency.vertex_count())
        .into_par_iter()
        .map(|i| {
            let p = positions[i];
            let sum: DVec3 = adjacency
                .incident(i)
                .iter()
                .map(|&[j, k]| (positions[j as usize] - p).cross(positions[k as usize] - p))
                .sum();
            sum.normalize_or_zero()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube of outward quads.
    fn cube() -> (Vec<DVec3>, Faces) {
        let positions: Vec<DVec3> =
            (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64)).collect();
        let mut faces = Faces::new();
        for quad in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
            faces.push(&quad);
        }
        (positions, faces)
    }

    /// A regular octahedron, outward triangles: by symmetry each vertex normal is its axis.
    fn octahedron() -> (Vec<DVec3>, Faces) {
        let positions = vec![DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z];
        let mut faces = Faces::new();
        for [a, b, c] in [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]] {
            faces.push(&[a, b, c]);
        }
        (positions, faces)
    }

    #[test]
    fn octahedron_vertex_normals_are_its_axes() {
        let (positions, faces) = octahedron();
        let normals = vertex_normals(&positions, &NormalAdjacency::new(&faces, positions.len()));
        for (p, n) in positions.iter().zip(&normals) {
            assert!((*n - *p).length() < 1e-15, "{p}: {n}");
        }
    }

    #[test]
    fn cube_corner_normals_point_outward() {
        let (positions, faces) = cube();
        let normals = vertex_normals(&positions, &NormalAdjacency::new(&faces, positions.len()));
        for (p, n) in positions.iter().zip(&normals) {
            let diagonal = (*p - DVec3::splat(0.5)).normalize();
            // Fan-triangulated quads weight a corner's faces 1 or ½: within 0.35 rad of the diagonal.
            assert!(n.angle_between(diagonal) < 0.35, "{p}: {n}");
            assert!((n.length() - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn every_triangle_corner_appears_once() {
        let (positions, faces) = cube();
        let adjacency = NormalAdjacency::new(&faces, positions.len());
        assert_eq!(adjacency.corners.len(), 3 * faces.triangles().count());
        for i in 0..positions.len() as u32 {
            let containing = faces.triangles().filter(|t| t.contains(&i)).count();
            assert_eq!(adjacency.incident(i as usize).len(), containing, "vertex {i}");
            for &[j, k] in adjacency.incident(i as usize) {
                assert!(faces.triangles().any(|t| t == [i, j, k] || t == [k, i, j] || t == [j, k, i]));
            }
        }
    }

    #[test]
    fn isolated_vertex_has_zero_normal() {
        let (mut positions, faces) = cube();
        positions.push(DVec3::splat(9.0));
        let normals = vertex_normals(&positions, &NormalAdjacency::new(&faces, positions.len()));
        assert_eq!(normals[8], DVec3::ZERO);
    }
}
