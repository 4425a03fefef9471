//! [`Faces::from_triangles`]: an engine's `u32` triangle list as [`Faces`].

use super::{Faces, MeshDataError};

impl Faces {
    /// The faces of a flat triangle list, three vertex indices a triangle (the index buffer
    /// of a `TriangleList` draw): triangle f is `indices[3f..3f + 3]`.
    ///
    /// Fails with [`MeshDataError::MalformedFaces`] if the length is not a multiple of 3 or
    /// exceeds `u32::MAX` (the offsets are 32-bit). The indices are not checked against a
    /// vertex count here; [`Mesh::from_parts`](super::Mesh::from_parts) and the GPU deformer
    /// check them where the faces meet their positions.
    pub fn from_triangles(indices: &[u32]) -> Result<Faces, MeshDataError> {
        let malformed = |reason| Err(MeshDataError::MalformedFaces { reason });
        if !indices.len().is_multiple_of(3) {
            return malformed("the triangle list's length is not a multiple of 3");
        }
        if u32::try_from(indices.len()).is_err() {
            return malformed("the triangle list has more than u32::MAX indices");
        }
        let offsets = (0..=indices.len() as u32).step_by(3).collect();
        Ok(Faces { offsets, indices: indices.to_vec() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_triangles_gives_one_face_per_triple() {
        let faces = Faces::from_triangles(&[0, 1, 2, 2, 1, 3]).unwrap();
        assert_eq!(faces.offsets, vec![0, 3, 6]);
        assert_eq!(faces.face(1), &[2, 1, 3]);
        assert_eq!(faces.triangles().collect::<Vec<_>>(), vec![[0, 1, 2], [2, 1, 3]]);
        assert_eq!(faces.check_offsets(), Ok(()));
    }

    #[test]
    fn from_triangles_of_nothing_is_no_face() {
        assert_eq!(Faces::from_triangles(&[]).unwrap(), Faces::new());
    }

    #[test]
    fn from_triangles_rejects_a_length_not_a_multiple_of_3() {
        let error = Faces::from_triangles(&[0, 1, 2, 3]).unwrap_err();
        assert_eq!(error.to_string(), "malformed faces: the triangle list's length is not a multiple of 3");
    }
}
