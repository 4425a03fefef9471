//! Midpoint subdivision, to make large meshes of real shapes for throughput measurements (a
//! 35k-vertex bunny becomes 140k, 560k, 2.2M vertices): every face is fan-triangulated and each
//! triangle split into four at its edge midpoints. The shape does not change; only the vertex
//! count grows. Old vertices keep their indices; each new vertex is the midpoint of an edge,
//! appended in order of first use, so a rig's vertex selection carries over
//! ([`Subdivision::carry`]).

use std::collections::HashMap;

use super::{FaceGroup, Faces, Mesh, MeshError};

/// A subdivided mesh and where its new vertices come from.
#[derive(Clone, Debug)]
pub struct Subdivision {
    /// The subdivided mesh: the old vertices first, then one per edge.
    pub mesh: Mesh,
    /// The edge each new vertex halves: vertex `old_count + k` is the midpoint of `parents[k]`.
    pub parents: Vec<[u32; 2]>,
}

impl Mesh {
    /// One level of midpoint subdivision; face groups keep their faces' four children each.
    pub fn subdivided(&self) -> Result<Subdivision, MeshError> {
        let old_count = self.positions.len() as u32;
        let mut positions = self.positions.clone();
        let mut parents: Vec<[u32; 2]> = Vec::new();
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32| -> u32 {
            let edge = (a.min(b), a.max(b));
            *midpoints.entry(edge).or_insert_with(|| {
                positions.push(0.5 * (positions[a as usize] + positions[b as usize]));
                parents.push([edge.0, edge.1]);
                old_count + parents.len() as u32 - 1
            })
        };
        let mut faces = Faces::new();
        // The children of each old face, for the groups.
        let mut children: Vec<std::ops::Range<u32>> = Vec::with_capacity(self.faces.len());
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
        let groups = self
            .groups
            .iter()
            .map(|group| FaceGroup {
                name: group.name.clone(),
                faces: group.faces.iter().flat_map(|&f| children[f as usize].clone()).collect(),
            })
            .collect();
        let mesh = Mesh::from_parts(positions, faces, groups)?;
        Ok(Subdivision { mesh, parents })
    }

    /// `levels` levels of [`Mesh::subdivided`]: the final mesh and each level's step (to
    /// [`carry`](Subdivision::carry) vertex selections through).
    pub fn subdivided_times(&self, levels: usize) -> Result<(Mesh, Vec<Subdivision>), MeshError> {
        let mut mesh = self.clone();
        let mut steps = Vec::with_capacity(levels);
        for _ in 0..levels {
            let step = mesh.subdivided()?;
            mesh = step.mesh.clone();
            steps.push(step);
        }
        Ok((mesh, steps))
    }
}

impl Subdivision {
    /// A sorted vertex selection of the mesh before subdivision carried to the mesh after: the
    /// old vertices, and each new vertex whose edge has both ends selected.
    pub fn carry(&self, indices: &[u32]) -> Vec<u32> {
        let old_count = (self.mesh.positions.len() - self.parents.len()) as u32;
        let selected = |v: u32| indices.binary_search(&v).is_ok();
        let mut carried = indices.to_vec();
        carried.extend(
            self.parents
                .iter()
                .enumerate()
                .filter(|(_, [a, b])| selected(*a) && selected(*b))
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
        let step = mesh.subdivided().unwrap();
        assert_eq!(step.mesh.positions.len(), mesh.positions.len() + edges.len());
        assert_eq!(step.mesh.faces.len(), 4 * triangles);
        assert_eq!(&step.mesh.positions[..mesh.positions.len()], &mesh.positions[..]);
        for (k, [a, b]) in step.parents.iter().enumerate() {
            let expected = 0.5 * (mesh.positions[*a as usize] + mesh.positions[*b as usize]);
            assert_eq!(step.mesh.positions[mesh.positions.len() + k], expected);
        }
        // A closed tube stays closed, with the same enclosed volume (midpoints lie on the
        // original flat faces).
        let before = mesh.enclosed_volume(&mesh.positions);
        let after = step.mesh.enclosed_volume(&step.mesh.positions);
        assert!((before - after).abs() < 1e-12 * before.abs(), "{before} vs {after}");
    }

    #[test]
    fn selection_carries_to_midpoints_inside_it() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2]);
        faces.push(&[1, 3, 2]);
        let groups = vec![FaceGroup { name: "second".into(), faces: vec![1] }];
        let step = Mesh::from_parts(positions, faces, groups).unwrap().subdivided().unwrap();
        assert_eq!(step.mesh.groups[0].faces, vec![4, 5, 6, 7]);
        let carried = step.carry(&[1, 2, 3]);
        // Edges 1–3, 3–2 and 1–2 are inside the selection; 0–1 and 2–0 are not.
        let inside: Vec<[u32; 2]> = carried[3..].iter().map(|&v| step.parents[v as usize - 4]).collect();
        assert_eq!(inside.len(), 3);
        assert!(inside.iter().all(|&[a, b]| a != 0 && b != 0), "{inside:?}");
    }
}
