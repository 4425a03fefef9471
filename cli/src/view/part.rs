//! Choosing a part of the mesh to fit a sweep to (§3) with one click: the face group under the
//! pointer, or the connected region of the surface within a radius of the point clicked.

use sweepffd::fit::connected_to;
use sweepffd::mesh::Mesh;
use sweepffd::rig::VertexSelection;

/// How a click selects a part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PartRule {
    /// The face group of the face clicked.
    Group,
    /// Vertices within this fraction of the mesh's bounding-box diagonal of the vertex clicked,
    /// edge-connected to it through such vertices.
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
            let members = mesh.face_group_vertices(group);
            let vertices: Vec<u32> = members.iter().copied().filter(free).collect();
            let selection = if vertices.len() == members.len() {
                VertexSelection::Groups(vec![group.name.clone()])
            } else {
                VertexSelection::Indices(vertices.clone())
            };
            Part { name: group.name.clone(), selection, vertices }
        }
        PartRule::Radius(fraction) => {
            let (centre, radius) = (mesh.positions[seed as usize], fraction * mesh.diagonal());
            let region = connected_to(mesh, seed, |p| p.distance(centre) <= radius);
            let vertices: Vec<u32> = region.into_iter().filter(free).collect();
            Part { name: format!("part-{seed}"), selection: VertexSelection::Indices(vertices.clone()), vertices }
        }
    };
    (!part.vertices.is_empty()).then_some(part)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use sweepffd::mesh::{FaceGroup, Faces};

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
