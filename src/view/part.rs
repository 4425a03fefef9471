//! Choosing a part of the mesh to fit a sweep to (§3) with one click: the face group under the
//! pointer, or the connected region of the surface within a radius of the point clicked.

use std::collections::VecDeque;

use crate::mesh::Mesh;
use crate::rig::VertexSelection;

/// How a click selects a part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PartRule {
    /// The face group of the face clicked.
    Group,
    /// Vertices within this fraction of the mesh's bounding-box diagonal of the vertex clicked,
    /// connected to it through such vertices.
    Radius(f64),
}

/// A part picked for fitting.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// A name for the fitted sweep.
    pub name: String,
    /// The selection as a rig file writes it.
    pub selection: VertexSelection,
    /// The part's vertices, increasing.
    pub vertices: Vec<u32>,
}

/// The part around vertex `seed` of face `face` by `rule`, without the vertices `taken`
/// (owned by a sweep already); `None` if nothing is left or the face has no group.
pub fn select_part(mesh: &Mesh, seed: u32, face: usize, rule: PartRule, taken: &[bool]) -> Option<Part> {
    let free = |v: &u32| !taken.get(*v as usize).copied().unwrap_or(false);
    let part = match rule {
        PartRule::Group => {
            let group = mesh.groups.iter().find(|g| g.faces.binary_search(&(face as u32)).is_ok())?;
            let vertices: Vec<u32> = mesh.group_vertices(&group.name)?.into_iter().filter(free).collect();
            let selection = if vertices.len() == mesh.group_vertices(&group.name)?.len() {
                VertexSelection::Groups(vec![group.name.clone()])
            } else {
                VertexSelection::Indices(vertices.clone())
            };
            Part { name: group.name.clone(), selection, vertices }
        }
        PartRule::Radius(fraction) => {
            let vertices: Vec<u32> = region(mesh, seed, fraction * mesh.diagonal()).into_iter().filter(free).collect();
            Part { name: format!("part-{seed}"), selection: VertexSelection::Indices(vertices.clone()), vertices }
        }
    };
    (!part.vertices.is_empty()).then_some(part)
}

/// Vertices within `radius` of `seed` reachable from it along edges between such vertices,
/// increasing.
fn region(mesh: &Mesh, seed: u32, radius: f64) -> Vec<u32> {
    let centre = mesh.positions[seed as usize];
    let inside = |v: u32| mesh.positions[v as usize].distance(centre) <= radius;
    // Faces around each vertex (only those with a vertex inside matter).
    let mut faces_of: std::collections::HashMap<u32, Vec<usize>> = std::collections::HashMap::new();
    for (f, face) in mesh.faces.iter().enumerate() {
        for &v in face.iter().filter(|&&v| inside(v)) {
            faces_of.entry(v).or_default().push(f);
        }
    }
    let mut seen = vec![false; mesh.positions.len()];
    let mut queue = VecDeque::from([seed]);
    seen[seed as usize] = true;
    let mut found = Vec::new();
    while let Some(v) = queue.pop_front() {
        found.push(v);
        for &f in faces_of.get(&v).map(Vec::as_slice).unwrap_or(&[]) {
            for &w in mesh.faces.face(f) {
                if !seen[w as usize] && inside(w) {
                    seen[w as usize] = true;
                    queue.push_back(w);
                }
            }
        }
    }
    found.sort_unstable();
    found
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::mesh::{FaceGroup, Faces};

    /// Two triangles sharing an edge, and a third far away.
    fn mesh() -> Mesh {
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.2, 0.2, 0.0),
            DVec3::new(0.3, 0.2, 0.0),
            DVec3::new(0.2, 0.3, 0.0),
        ];
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2]);
        faces.push(&[1, 3, 2]);
        faces.push(&[4, 5, 6]);
        let groups = vec![FaceGroup { name: "pair".into(), faces: vec![0, 1] }];
        Mesh::from_parts(positions, faces, groups).unwrap()
    }

    #[test]
    fn group_rule_takes_the_group_of_the_face() {
        let mesh = mesh();
        let part = select_part(&mesh, 0, 1, PartRule::Group, &[]).unwrap();
        assert_eq!(part.vertices, vec![0, 1, 2, 3]);
        assert_eq!(part.selection, VertexSelection::Groups(vec!["pair".into()]));
        assert_eq!(select_part(&mesh, 4, 2, PartRule::Group, &[]), None, "face 2 is in no group");
        let taken = [true, false, false, false];
        let part = select_part(&mesh, 1, 0, PartRule::Group, &taken).unwrap();
        assert_eq!(part.selection, VertexSelection::Indices(vec![1, 2, 3]));
    }

    #[test]
    fn radius_rule_stays_connected() {
        let mesh = mesh();
        // Vertices 4–6 are within reach of vertex 0 but not connected to it.
        let radius = 1.2 / mesh.diagonal();
        let part = select_part(&mesh, 0, 0, PartRule::Radius(radius), &[]).unwrap();
        assert_eq!(part.vertices, vec![0, 1, 2]);
    }
}
