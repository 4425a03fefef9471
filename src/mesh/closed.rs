//! Whether a mesh is closed: every edge shared by exactly two faces, as an enclosed volume
//! needs.

use std::collections::HashMap;

use super::Mesh;

/// An edge that keeps a mesh from being closed: its two vertices and how many faces it
/// borders (1 on a hole's rim, 3 or more where sheets meet).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OpenEdge {
    /// The edge's vertices, the smaller first.
    pub vertices: [u32; 2],
    /// The faces it borders.
    pub faces: usize,
}

impl Mesh {
    /// The first edge (in face order) not shared by exactly two faces, or `None` when the mesh
    /// is closed.
    pub fn open_edge(&self) -> Option<OpenEdge> {
        let edges = || {
            (0..self.faces.len()).flat_map(|f| {
                let face = self.faces.face(f);
                (0..face.len()).map(move |k| {
                    let (a, b) = (face[k], face[(k + 1) % face.len()]);
                    [a.min(b), a.max(b)]
                })
            })
        };
        let mut count: HashMap<[u32; 2], usize> = HashMap::new();
        for edge in edges() {
            *count.entry(edge).or_default() += 1;
        }
        edges().find(|edge| count[edge] != 2).map(|vertices| OpenEdge { vertices, faces: count[&vertices] })
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::mesh::Faces;

    fn tetrahedron(faces: &[[u32; 3]]) -> Mesh {
        let mut all = Faces::new();
        faces.iter().for_each(|f| all.push(f));
        Mesh::from_parts(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], all, Vec::new()).unwrap()
    }

    #[test]
    fn a_tetrahedron_is_closed_and_loses_that_with_a_face() {
        let faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert_eq!(tetrahedron(&faces).open_edge(), None);
        assert_eq!(tetrahedron(&faces[1..]).open_edge(), Some(OpenEdge { vertices: [0, 1], faces: 1 }));
    }
}
