//! [`Mesh::from_parts`]: a mesh built in code, validated.

use glam::DVec3;

use super::{FaceGroup, Faces, Mesh, MeshDataError};

impl Mesh {
    /// Builds a mesh in code; `groups` may be empty.
    ///
    /// # Errors
    ///
    /// A [`MeshDataError`] when `positions` is empty or has a non-finite coordinate, when
    /// `faces.offsets` does not describe `faces.indices`, when a face has fewer than 3
    /// vertices or an index `>= positions.len()`, or when a group's face list is not strictly
    /// increasing or names a face that does not exist. Numbers in the error are zero-based.
    /// Empty `offsets` (as from `Faces::default()`) are taken as no face.
    pub fn from_parts(positions: Vec<DVec3>, mut faces: Faces, groups: Vec<FaceGroup>) -> Result<Mesh, MeshDataError> {
        check_positions(&positions)?;
        faces.check_offsets()?;
        if faces.offsets.is_empty() {
            faces = Faces::new();
        }
        check_faces(&faces, positions.len())?;
        check_groups(&groups, faces.len())?;
        Ok(Mesh { positions, faces, groups })
    }
}

fn check_positions(positions: &[DVec3]) -> Result<(), MeshDataError> {
    if positions.is_empty() {
        return Err(MeshDataError::NoVertices);
    }
    match positions.iter().position(|p| !p.is_finite()) {
        Some(vertex) => Err(MeshDataError::NonFinite { vertex }),
        None => Ok(()),
    }
}

fn check_faces(faces: &Faces, count: usize) -> Result<(), MeshDataError> {
    for (face, indices) in faces.iter().enumerate() {
        if indices.len() < 3 {
            let count = indices.len();
            return Err(MeshDataError::ShortFace { face, count });
        }
        if let Some(&index) = indices.iter().find(|&&i| i as usize >= count) {
            let index = i64::from(index);
            return Err(MeshDataError::IndexOutOfRange { face, index, count });
        }
    }
    Ok(())
}

fn check_groups(groups: &[FaceGroup], count: usize) -> Result<(), MeshDataError> {
    for group in groups {
        if group.faces.windows(2).any(|w| w[1] <= w[0]) {
            let group = group.name.clone();
            return Err(MeshDataError::GroupNotIncreasing { group });
        }
        if let Some(&face) = group.faces.last().filter(|&&f| f as usize >= count) {
            let group = group.name.clone();
            return Err(MeshDataError::GroupFaceOutOfRange { group, face, count });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle() -> (Vec<DVec3>, Faces) {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2]);
        (positions, faces)
    }

    fn invalid(result: Result<Mesh, MeshDataError>) -> MeshDataError {
        result.expect_err("the parts are invalid")
    }

    #[test]
    fn valid_parts_build_a_mesh() {
        let (positions, faces) = triangle();
        let group = FaceGroup { name: "all".into(), faces: vec![0] };
        let mesh = Mesh::from_parts(positions, faces, vec![group]).unwrap();
        assert_eq!(mesh.faces.len(), 1);
        assert_eq!(mesh.groups[0].name, "all");
    }

    #[test]
    fn default_faces_are_normalized_to_new() {
        let (positions, _) = triangle();
        let mesh = Mesh::from_parts(positions, Faces::default(), Vec::new()).unwrap();
        assert_eq!(mesh.faces, Faces::new());
    }

    #[test]
    fn no_positions_is_an_error() {
        let e = invalid(Mesh::from_parts(Vec::new(), Faces::new(), Vec::new()));
        assert_eq!(e, MeshDataError::NoVertices);
        assert_eq!(e.to_string(), "the mesh has no vertices");
    }

    #[test]
    fn non_finite_position_is_an_error() {
        let (mut positions, faces) = triangle();
        positions[2].z = f64::NAN;
        let e = invalid(Mesh::from_parts(positions, faces, Vec::new()));
        assert_eq!(e.to_string(), "vertex 2 has a non-finite coordinate");
    }

    #[test]
    fn index_out_of_range_is_an_error() {
        let (positions, mut faces) = triangle();
        faces.push(&[0, 2, 3]);
        let e = invalid(Mesh::from_parts(positions, faces, Vec::new()));
        assert_eq!(e.to_string(), "face 1 refers to vertex 3 but the mesh has 3 vertices");
    }

    #[test]
    fn two_vertex_face_is_an_error() {
        let (positions, mut faces) = triangle();
        faces.push(&[0, 1]);
        let e = invalid(Mesh::from_parts(positions, faces, Vec::new()));
        assert_eq!(e, MeshDataError::ShortFace { face: 1, count: 2 });
    }

    #[test]
    fn malformed_offsets_are_an_error() {
        let (positions, _) = triangle();
        let faces = Faces { offsets: vec![0, 4], indices: vec![0, 1, 2] };
        let e = invalid(Mesh::from_parts(positions, faces, Vec::new()));
        assert!(matches!(e, MeshDataError::MalformedFaces { .. }), "{e}");
    }

    #[test]
    fn group_errors() {
        let (positions, faces) = triangle();
        let group = |faces| FaceGroup { name: "g".into(), faces };
        let e = invalid(Mesh::from_parts(positions.clone(), faces.clone(), vec![group(vec![1])]));
        assert_eq!(e.to_string(), "group \"g\" refers to face 1 but the mesh has 1 faces");
        let e = invalid(Mesh::from_parts(positions, faces, vec![group(vec![0, 0])]));
        assert_eq!(e, MeshDataError::GroupNotIncreasing { group: "g".into() });
    }
}
