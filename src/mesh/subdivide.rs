//! Subdivision that keeps the shape, to make large meshes of real shapes for throughput
//! measurements: midpoint subdivision (every face fan-triangulated and each triangle split into
//! four at its edge midpoints: a 35k-vertex bunny becomes 140k, 557k, 2.2M vertices) and, to
//! reach an exact vertex count in between, centroid splits of faces spread evenly over the
//! mesh (each adds one vertex and leaves the edges alone, so no crack opens). Old vertices keep
//! their indices; new ones are appended, each the mean of its parents, so a rig's vertex
//! selection carries over ([`Subdivision::carry`]).
//!
//! The size of the result is predicted before anything is allocated, and a subdivision that
//! would pass [`MAX_VERTICES`] or [`MAX_FACES`] is refused ([`SubdivisionError`]): a level
//! adds one vertex per distinct edge E of the fan triangles and makes four triangles of each
//! of the T, so after a level V′ = V + E, T′ = 4T and E′ = 2E + 3T (exact unless a triangle
//! repeats a corner, where it overestimates).

use std::collections::HashMap;
use std::ops::Range;

use thiserror::Error;

use super::{FaceGroup, Faces, Mesh, MeshDataError};
use crate::limits::{MAX_FACES, MAX_VERTICES};

/// Why a mesh cannot be subdivided as asked.
#[derive(Debug, Error)]
pub enum SubdivisionError {
    /// A step would make a mesh past the limits.
    #[error(
        "{step} would make {vertices} vertices and {faces} faces, over the limits of {MAX_VERTICES} vertices \
         and {MAX_FACES} faces"
    )]
    TooLarge {
        /// Which step: "midpoint subdivision level 7 (of 30)", "centroid splits".
        step: String,
        /// The vertices it would make (saturated at `usize::MAX`).
        vertices: usize,
        /// The faces it would make (saturated at `usize::MAX`).
        faces: usize,
    },
    /// A vertex count to subdivide to past [`MAX_VERTICES`].
    #[error("a target of {vertices} vertices is over the limit of {MAX_VERTICES} vertices")]
    TargetTooLarge {
        /// The target asked for.
        vertices: usize,
    },
    /// The subdivided data do not form a mesh.
    #[error(transparent)]
    Mesh(#[from] MeshDataError),
}

/// The size of a mesh as subdivision changes it: vertices, fan triangles and their distinct
/// edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Size {
    vertices: usize,
    triangles: usize,
    edges: usize,
}

impl Size {
    /// The size after one midpoint level (saturating).
    fn midpoint_level(self) -> Size {
        Size {
            vertices: self.vertices.saturating_add(self.edges),
            triangles: self.triangles.saturating_mul(4),
            edges: self.edges.saturating_mul(2).saturating_add(self.triangles.saturating_mul(3)),
        }
    }

    /// Whether a mesh of this size (one face per triangle) fits the limits.
    fn fits(self) -> bool {
        self.vertices <= MAX_VERTICES && self.triangles <= MAX_FACES
    }

    /// The error for `step` making a mesh of this size.
    fn too_large(self, step: String) -> SubdivisionError {
        SubdivisionError::TooLarge { step, vertices: self.vertices, faces: self.triangles }
    }
}

/// The old vertices a new vertex is the mean of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parents {
    /// The midpoint of an edge.
    Edge([u32; 2]),
    /// The centroid of a triangle.
    Triangle([u32; 3]),
}

impl Parents {
    fn all(&self) -> &[u32] {
        match self {
            Parents::Edge(ends) => ends,
            Parents::Triangle(corners) => corners,
        }
    }
}

/// Where the new vertices of a subdivided mesh come from: its old vertices come first, then
/// the new ones.
#[derive(Clone, Debug)]
pub struct Subdivision {
    /// Vertices before the subdivision.
    pub old_count: u32,
    /// Vertex `old_count + k` is the mean of `parents[k]`.
    pub parents: Vec<Parents>,
}

impl Mesh {
    /// One level of midpoint subdivision; face groups keep their faces' four children each.
    ///
    /// # Errors
    ///
    /// [`SubdivisionError::TooLarge`] when the result would pass the limits (checked before
    /// allocating).
    pub fn subdivided(&self) -> Result<(Mesh, Subdivision), SubdivisionError> {
        let next = self.size().midpoint_level();
        if !next.fits() {
            return Err(next.too_large("one level of midpoint subdivision".to_string()));
        }
        let old_count = self.positions.len() as u32;
        let mut positions = self.positions.clone();
        let mut parents: Vec<Parents> = Vec::new();
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32| -> u32 {
            let edge = (a.min(b), a.max(b));
            *midpoints.entry(edge).or_insert_with(|| {
                positions.push(0.5 * (positions[a as usize] + positions[b as usize]));
                parents.push(Parents::Edge([edge.0, edge.1]));
                old_count + parents.len() as u32 - 1
            })
        };
        let mut faces = Faces::new();
        // The children of each old face, for the groups.
        let mut children: Vec<Range<u32>> = Vec::with_capacity(self.faces.len());
        for face in self.faces.iter() {
            let first = faces.len() as u32;
            let corner = face.first().copied().unwrap_or(0);
            for pair in face.windows(2).skip(1) {
                let [a, b, c] = [corner, pair[0], pair[1]];
                let (ab, bc, ca) = (midpoint(a, b), midpoint(b, c), midpoint(c, a));
                for triangle in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
                    faces.push(&triangle);
                }
            }
            children.push(first..faces.len() as u32);
        }
        let mesh = Mesh::from_parts(positions, faces, self.groups_of_children(&children))?;
        Ok((mesh, Subdivision { old_count, parents }))
    }

    /// Splits `count` triangles (of the fan triangulation), spread evenly over the mesh, at
    /// their centroids into three; the other triangles stay. A `count` over the number of
    /// triangles splits them all.
    ///
    /// # Errors
    ///
    /// [`SubdivisionError::TooLarge`] when the result would pass the limits (checked before
    /// allocating).
    pub fn split_at_centroids(&self, count: usize) -> Result<(Mesh, Subdivision), SubdivisionError> {
        let triangles = self.faces.triangles().count();
        let count = count.min(triangles);
        let after = Size {
            vertices: self.positions.len().saturating_add(count),
            triangles: triangles.saturating_add(count.saturating_mul(2)),
            edges: 0,
        };
        if !after.fits() {
            return Err(after.too_large(format!("splitting {count} triangles at their centroids")));
        }
        let old_count = self.positions.len() as u32;
        let total = triangles.max(1);
        let mut positions = self.positions.clone();
        let mut parents = Vec::new();
        let mut faces = Faces::new();
        let mut children: Vec<Range<u32>> = Vec::with_capacity(self.faces.len());
        let mut triangle = 0;
        for face in self.faces.iter() {
            let first = faces.len() as u32;
            let corner = face.first().copied().unwrap_or(0);
            for pair in face.windows(2).skip(1) {
                let [a, b, c] = [corner, pair[0], pair[1]];
                // Bresenham: triangle i is split when ⌊(i + 1)·count / total⌋ steps up.
                let split = (triangle + 1) * count / total > triangle * count / total;
                triangle += 1;
                if split {
                    let centre = old_count + parents.len() as u32;
                    positions.push((positions[a as usize] + positions[b as usize] + positions[c as usize]) / 3.0);
                    parents.push(Parents::Triangle([a, b, c]));
                    for t in [[a, b, centre], [b, c, centre], [c, a, centre]] {
                        faces.push(&t);
                    }
                } else {
                    faces.push(&[a, b, c]);
                }
            }
            children.push(first..faces.len() as u32);
        }
        let mesh = Mesh::from_parts(positions, faces, self.groups_of_children(&children))?;
        Ok((mesh, Subdivision { old_count, parents }))
    }

    /// Midpoint subdivisions while the count stays at most `vertices`, then centroid splits
    /// up to exactly `vertices` (or as near as one round of splits gets): the final mesh and
    /// each step.
    ///
    /// # Errors
    ///
    /// [`SubdivisionError::TargetTooLarge`] for a target over [`MAX_VERTICES`], checked first;
    /// [`SubdivisionError::TooLarge`] when a step would make more than [`MAX_FACES`] faces.
    pub fn subdivided_to(&self, vertices: usize) -> Result<(Mesh, Vec<Subdivision>), SubdivisionError> {
        if vertices > MAX_VERTICES {
            return Err(SubdivisionError::TargetTooLarge { vertices });
        }
        let mut mesh = self.clone();
        let mut steps = Vec::new();
        while mesh.positions.len() < vertices {
            // A midpoint level adds a vertex per edge of the triangles.
            let (next, step) = if mesh.positions.len() + mesh.triangle_edge_count() <= vertices {
                mesh.subdivided()?
            } else {
                let missing = vertices - mesh.positions.len();
                mesh.split_at_centroids(missing.min(mesh.faces.triangles().count()))?
            };
            if step.parents.is_empty() {
                break;
            }
            mesh = next;
            steps.push(step);
        }
        Ok((mesh, steps))
    }

    /// The vertices, fan triangles and distinct triangle edges of the mesh.
    fn size(&self) -> Size {
        Size {
            vertices: self.positions.len(),
            triangles: self.faces.triangles().count(),
            edges: self.triangle_edge_count(),
        }
    }

    /// The number of distinct edges of the fan triangles.
    fn triangle_edge_count(&self) -> usize {
        let mut edges: Vec<(u32, u32)> = self
            .faces
            .triangles()
            .flat_map(|[a, b, c]| [(a, b), (b, c), (c, a)])
            .map(|(p, q)| (p.min(q), p.max(q)))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        edges.len()
    }

    /// The groups after each face `f` became the faces `children[f]`.
    fn groups_of_children(&self, children: &[Range<u32>]) -> Vec<FaceGroup> {
        self.groups
            .iter()
            .map(|group| FaceGroup {
                name: group.name.clone(),
                faces: group.faces.iter().flat_map(|&f| children[f as usize].clone()).collect(),
            })
            .collect()
    }

    /// `levels` levels of [`Mesh::subdivided`]: the final mesh and each level's step (to
    /// [`carry`](Subdivision::carry) vertex selections through).
    ///
    /// # Errors
    ///
    /// [`SubdivisionError::TooLarge`], naming the first level past the limits, when the
    /// predicted size of some level passes them; checked for all levels before the first.
    pub fn subdivided_times(&self, levels: usize) -> Result<(Mesh, Vec<Subdivision>), SubdivisionError> {
        let mut size = self.size();
        if size.triangles == 0 {
            // No face to split: every level would leave the mesh as it is.
            return Ok((self.clone(), Vec::new()));
        }
        // At most ⌈log₄ MAX_FACES⌉ + 1 rounds: the triangles quadruple each level.
        for level in 1..=levels {
            size = size.midpoint_level();
            if !size.fits() {
                return Err(size.too_large(format!("midpoint subdivision level {level} (of {levels})")));
            }
        }
        let mut mesh = self.clone();
        let mut steps = Vec::with_capacity(levels);
        for _ in 0..levels {
            let (next, step) = mesh.subdivided()?;
            mesh = next;
            steps.push(step);
        }
        Ok((mesh, steps))
    }
}

impl Subdivision {
    /// A sorted vertex selection of the mesh before subdivision carried to the mesh after: the
    /// old vertices, and each new vertex whose parents are all selected.
    pub fn carry(&self, indices: &[u32]) -> Vec<u32> {
        let old_count = self.old_count;
        let selected = |v: &u32| indices.binary_search(v).is_ok();
        let mut carried = indices.to_vec();
        carried.extend(
            self.parents
                .iter()
                .enumerate()
                .filter(|(_, parents)| parents.all().iter().all(selected))
                .map(|(k, _)| old_count + k as u32),
        );
        carried
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::synthetic::Tube;

    #[test]
    fn one_level_adds_a_vertex_per_edge_and_quadruples_triangles() {
        let mesh = Tube { rings: 5, around: 12, length: 2.0, radius: 0.5 }.mesh();
        let triangles = mesh.faces.triangles().count();
        let mut edges = std::collections::HashSet::new();
        for [a, b, c] in mesh.faces.triangles() {
            for (p, q) in [(a, b), (b, c), (c, a)] {
                edges.insert((p.min(q), p.max(q)));
            }
        }
        let (fine, step) = mesh.subdivided().unwrap();
        assert_eq!(fine.positions.len(), mesh.positions.len() + edges.len());
        assert_eq!(fine.faces.len(), 4 * triangles);
        assert_eq!(&fine.positions[..mesh.positions.len()], &mesh.positions[..]);
        for (k, parents) in step.parents.iter().enumerate() {
            let Parents::Edge([a, b]) = parents else { panic!("midpoints only") };
            let expected = 0.5 * (mesh.positions[*a as usize] + mesh.positions[*b as usize]);
            assert_eq!(fine.positions[mesh.positions.len() + k], expected);
        }
        // A closed tube stays closed, with the same enclosed volume (midpoints lie on the
        // original flat faces).
        let before = mesh.enclosed_volume(&mesh.positions);
        let after = fine.enclosed_volume(&fine.positions);
        assert!((before - after).abs() < 1e-12 * before.abs(), "{before} vs {after}");
    }

    #[test]
    fn selection_carries_to_midpoints_inside_it() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2]);
        faces.push(&[1, 3, 2]);
        let groups = vec![FaceGroup { name: "second".into(), faces: vec![1] }];
        let (fine, step) = Mesh::from_parts(positions, faces, groups).unwrap().subdivided().unwrap();
        assert_eq!(fine.groups[0].faces, vec![4, 5, 6, 7]);
        let carried = step.carry(&[1, 2, 3]);
        // Edges 1–3, 3–2 and 1–2 are inside the selection; 0–1 and 2–0 are not.
        let inside: Vec<Parents> = carried[3..].iter().map(|&v| step.parents[v as usize - 4]).collect();
        assert_eq!(inside.len(), 3);
        assert!(inside.iter().all(|p| !p.all().contains(&0)), "{inside:?}");
    }

    #[test]
    fn levels_past_the_vertex_limit_are_refused_before_any_work() {
        let mesh = Tube { rings: 5, around: 12, length: 2.0, radius: 0.5 }.mesh();
        let err = mesh.subdivided_times(30).unwrap_err();
        // 62 vertices, 120 triangles and 180 edges: level k has 62 + 180·(2^k − 1)·… until
        // level 10 makes 125,829,122 triangles, past 2²⁶.
        assert_eq!(
            err.to_string(),
            "midpoint subdivision level 10 (of 30) would make 62914562 vertices and 125829120 faces, over the \
             limits of 33554432 vertices and 67108864 faces"
        );
        // The prediction is exact: the level before the limit has the predicted size.
        let (fine, _) = mesh.subdivided_times(2).unwrap();
        let mut size = mesh.size();
        for _ in 0..2 {
            size = size.midpoint_level();
        }
        assert_eq!(size, fine.size());
    }

    #[test]
    fn huge_level_counts_and_targets_are_refused_at_once() {
        let mesh = Tube { rings: 5, around: 12, length: 2.0, radius: 0.5 }.mesh();
        let err = mesh.subdivided_times(usize::MAX).unwrap_err();
        assert!(err.to_string().starts_with("midpoint subdivision level 10 (of 18446744073709551615) would make"));
        let err = mesh.subdivided_to(1_000_000_000_000).unwrap_err();
        assert_eq!(err.to_string(), "a target of 1000000000000 vertices is over the limit of 33554432 vertices");
        assert!(mesh.subdivided_to(crate::limits::MAX_VERTICES + 1).is_err());
    }

    #[test]
    fn a_mesh_without_faces_subdivides_to_itself() {
        let mesh = Mesh::from_parts(vec![DVec3::ZERO, DVec3::X], Faces::new(), Vec::new()).unwrap();
        let (same, steps) = mesh.subdivided_times(usize::MAX).unwrap();
        assert_eq!(same.positions, mesh.positions);
        assert!(steps.is_empty());
    }

    #[test]
    fn exact_vertex_count_by_midpoints_then_centroids() {
        let mesh = Tube { rings: 5, around: 12, length: 2.0, radius: 0.5 }.mesh();
        let (big, steps) = mesh.subdivided_to(1000).unwrap();
        assert_eq!(big.positions.len(), 1000);
        assert!(matches!(steps.last().unwrap().parents[0], Parents::Triangle(_)));
        // Still closed, same volume: centroids lie on the faces they split.
        assert!(big.is_closed());
        let (before, after) = (mesh.enclosed_volume(&mesh.positions), big.enclosed_volume(&big.positions));
        assert!((before - after).abs() < 1e-12 * before.abs(), "{before} vs {after}");
        // The whole mesh selected stays the whole mesh.
        let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
        let carried = steps.iter().fold(all, |indices, step| step.carry(&indices));
        assert_eq!(carried.len(), 1000);
    }
}
