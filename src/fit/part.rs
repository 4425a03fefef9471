//! The part of a mesh a sweep is fitted to: the selected vertices and the triangles among them.

use glam::DVec3;

use crate::mesh::Mesh;

/// The selected vertices of a mesh and every (fan-triangulated) face whose vertices are all
/// selected. Indices in [`Part::triangles`] are local: they index [`Part::positions`].
#[derive(Clone, Debug)]
pub struct Part {
    /// The selected vertices' indices in the mesh, increasing and unique.
    pub vertices: Vec<u32>,
    /// Their positions, in the same order.
    pub positions: Vec<DVec3>,
    /// Triangles of faces lying wholly in the part, in local indices.
    pub triangles: Vec<[u32; 3]>,
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
        Part { vertices, positions, triangles }
    }

    /// The centroid of the part's vertices.
    pub fn centroid(&self) -> DVec3 {
        self.positions.iter().copied().sum::<DVec3>() / self.positions.len() as f64
    }
}
