//! The part of a mesh a sweep is fitted to: the selected vertices, the triangles among them and
//! the rim where the part is attached to the rest of the mesh.

use glam::DVec3;

use crate::mesh::Mesh;

/// The selected vertices of a mesh and every triangle of its fan-triangulated faces whose
/// vertices are all selected. Indices in [`Part::triangles`] and [`Part::rim`] are local: they
/// index [`Part::positions`].
#[derive(Clone, Debug)]
pub struct Part {
    /// The selected vertices' indices in the mesh, increasing and unique.
    pub vertices: Vec<u32>,
    /// Their positions, in the same order.
    pub positions: Vec<DVec3>,
    /// The mesh's fan triangles lying wholly in the part, in local indices.
    pub triangles: Vec<[u32; 3]>,
    /// The rim, where the part is attached to the rest of the mesh: every edge of the mesh's
    /// fan triangles between two selected vertices that lies both on a triangle of the part
    /// and on a triangle with a vertex outside it. Each edge once, its smaller index first, in
    /// increasing order. An edge of the mesh's own open boundary (a hole in a scan) lies on no
    /// outside triangle and is not on the rim; a part that is a whole closed mesh has none.
    pub rim: Vec<[u32; 2]>,
}

impl Part {
    /// The part of `mesh` made of `vertices` (any order, duplicates allowed, all in range).
    pub fn new(mesh: &Mesh, vertices: &[u32]) -> Part {
        let mut vertices = vertices.to_vec();
        vertices.sort_unstable();
        vertices.dedup();
        let mut local = vec![u32::MAX; mesh.positions.len()];
        for (i, &v) in vertices.iter().enumerate() {
            local[v as usize] = i as u32;
        }
        let triangles = mesh
            .faces
            .triangles()
            .filter_map(|[a, b, c]| {
                let t = [local[a as usize], local[b as usize], local[c as usize]];
                t.iter().all(|&i| i != u32::MAX).then_some(t)
            })
            .collect();
        let positions = vertices.iter().map(|&v| mesh.positions[v as usize]).collect();
        let rim = rim(mesh, &local);
        Part { vertices, positions, triangles, rim }
    }

    /// Points on the part's surface to fit to: its vertices, and where it has fewer than
    /// `at_least` of them, the midpoints of its triangles' edges too (each edge once), so that
    /// a fit with more unknowns than vertices follows the facets between them rather than the
    /// vertices alone.
    pub fn surface_samples(&self, at_least: usize) -> Vec<DVec3> {
        let mut samples = self.positions.clone();
        if samples.len() >= at_least {
            return samples;
        }
        let mut edges: Vec<[u32; 2]> = self
            .triangles
            .iter()
            .flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]])
            .map(|[a, b]| [a.min(b), a.max(b)])
            .filter(|[a, b]| a != b)
            .collect();
        edges.sort_unstable();
        edges.dedup();
        samples.extend(edges.iter().map(|&[a, b]| (self.positions[a as usize] + self.positions[b as usize]) / 2.0));
        samples
    }

    /// The centroids of the part's triangles.
    pub fn triangle_centroids(&self) -> Vec<DVec3> {
        self.triangles.iter().map(|t| t.iter().map(|&v| self.positions[v as usize]).sum::<DVec3>() / 3.0).collect()
    }

    /// Whether the part's vertices all lie in one plane, to within [`FLAT_WITHIN`] of its
    /// bounding box's diagonal (a sheet, such as a drawing's outline meshed in a plane): the
    /// plane of its largest triangle, which a flat part's every triangle lies in. No sweep's
    /// sections, nor any of its pieces', have area there.
    pub fn lies_in_a_plane(&self) -> bool {
        let corners = |t: &[u32; 3]| t.map(|v| self.positions[v as usize]);
        let largest = self.triangles.iter().map(corners).max_by(|a, b| {
            let area = |[p, q, r]: [DVec3; 3]| (q - p).cross(r - p).length_squared();
            area(*a).total_cmp(&area(*b))
        });
        let Some([p, q, r]) = largest else { return false };
        let Some(normal) = (q - p).cross(r - p).try_normalize() else { return false };
        let (low, high) = self
            .positions
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(low, high), &v| (low.min(v), high.max(v)));
        let within = FLAT_WITHIN * low.distance(high);
        self.positions.iter().all(|&v| (v - p).dot(normal).abs() <= within)
    }

    /// The centroid of the part's vertices.
    pub fn centroid(&self) -> DVec3 {
        self.positions.iter().copied().sum::<DVec3>() / self.positions.len() as f64
    }
}

/// See [`Part::lies_in_a_plane`].
pub const FLAT_WITHIN: f64 = 1e-9;

/// The rim edges of the part whose local index of each mesh vertex is `local` (`u32::MAX`:
/// not selected); see [`Part::rim`].
fn rim(mesh: &Mesh, local: &[u32]) -> Vec<[u32; 2]> {
    // Every side of a triangle between two selected vertices, with whether the triangle is in
    // the part.
    let mut sides: Vec<([u32; 2], bool)> = Vec::new();
    for triangle in mesh.faces.triangles() {
        let t = triangle.map(|v| local[v as usize]);
        let in_part = t.iter().all(|&i| i != u32::MAX);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if a != u32::MAX && b != u32::MAX && a != b {
                sides.push(([a.min(b), a.max(b)], in_part));
            }
        }
    }
    sides.sort_unstable();
    sides.dedup();
    // Sorted, an edge on triangles both inside and outside the part appears as (edge, false)
    // followed by (edge, true).
    sides.windows(2).filter(|w| w[0].0 == w[1].0).map(|w| w[0].0).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Faces;

    /// A strip of `n` unit quads along x: vertices (i, 0, 0) = 2i and (i, 1, 0) = 2i + 1.
    fn strip(n: u32) -> Mesh {
        let positions =
            (0..=n).flat_map(|i| [DVec3::new(i as f64, 0.0, 0.0), DVec3::new(i as f64, 1.0, 0.0)]).collect();
        let mut faces = Faces::new();
        for i in 0..n {
            faces.push(&[2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1]);
        }
        Mesh::from_parts(positions, faces, Vec::new()).unwrap()
    }

    #[test]
    fn the_rim_is_where_the_part_meets_the_rest_of_the_mesh() {
        let mesh = strip(3);
        // The first two quads: attached to the third along the edge x = 2; the strip's open
        // sides and its end x = 0 belong to no other face.
        let part = Part::new(&mesh, &[0, 1, 2, 3, 4, 5]);
        assert_eq!(part.triangles.len(), 4);
        assert_eq!(part.rim, [[4, 5]]);
        // The middle quad: attached at both ends.
        let part = Part::new(&mesh, &[2, 3, 4, 5]);
        assert_eq!(part.rim, [[0, 1], [2, 3]]);
        // The whole mesh: attached nowhere.
        assert!(Part::new(&mesh, &(0..8).collect::<Vec<_>>()).rim.is_empty());
    }

    #[test]
    fn a_strip_in_a_plane_lies_in_it_and_a_bent_one_does_not() {
        let mesh = strip(3);
        assert!(Part::new(&mesh, &(0..8).collect::<Vec<_>>()).lies_in_a_plane());
        let mut bent = mesh.clone();
        bent.positions[7].z = 1e-3;
        assert!(!Part::new(&bent, &(0..8).collect::<Vec<_>>()).lies_in_a_plane());
        // A part with no triangle has no plane.
        assert!(!Part::new(&mesh, &[0, 7]).lies_in_a_plane());
    }

    #[test]
    fn the_rim_of_a_partly_selected_quad_follows_its_fan_triangles() {
        let mesh = strip(2);
        // Three corners of the second quad (2, 4, 5, 3): its fan triangle (2, 5, 3) is in the
        // part; the other, (2, 4, 5), is not, nor is the first quad. The part is attached
        // along the diagonal 2–5 and the side 2–3; the side 3–5 is the mesh's open boundary.
        let part = Part::new(&mesh, &[2, 3, 5]);
        assert_eq!(part.triangles, [[0, 2, 1]]);
        assert_eq!(part.rim, [[0, 1], [0, 2]]);
    }
}
