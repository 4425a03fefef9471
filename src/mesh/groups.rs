//! Vertices of named face groups.

use super::{FaceGroup, Mesh};

impl Mesh {
    /// The vertices used by the faces of the group `name`, increasing and deduplicated;
    /// `None` if no group has that name (the first one counts if several do).
    pub fn group_vertices(&self, name: &str) -> Option<Vec<u32>> {
        let group = self.groups.iter().find(|g| g.name == name)?;
        Some(self.face_group_vertices(group))
    }

    /// The vertices used by the faces of `group` (one of [`Mesh::groups`]), increasing and
    /// deduplicated.
    pub fn face_group_vertices(&self, group: &FaceGroup) -> Vec<u32> {
        let mut vertices: Vec<u32> = group
            .faces
            .iter()
            .filter(|&&f| (f as usize) < self.faces.len())
            .flat_map(|&f| self.faces.face(f as usize).iter().copied())
            .collect();
        vertices.sort_unstable();
        vertices.dedup();
        vertices
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::mesh::{FaceGroup, Faces, Mesh};

    #[test]
    fn group_vertices_are_sorted_and_unique() {
        let positions = vec![DVec3::ZERO; 6];
        let mut faces = Faces::new();
        faces.push(&[5, 1, 2]);
        faces.push(&[0, 1, 2, 3]);
        faces.push(&[2, 4, 5]);
        let groups =
            vec![FaceGroup { name: "a".into(), faces: vec![0, 2] }, FaceGroup { name: "b".into(), faces: vec![1] }];
        let mesh = Mesh::from_parts(positions, faces, groups).unwrap();
        assert_eq!(mesh.group_vertices("a"), Some(vec![1, 2, 4, 5]));
        assert_eq!(mesh.group_vertices("b"), Some(vec![0, 1, 2, 3]));
        assert_eq!(mesh.group_vertices("c"), None);
    }
}
