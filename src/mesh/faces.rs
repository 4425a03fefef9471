//! Access to the flat polygon list [`Faces`]: face by face, or fan-triangulated.

use super::{Faces, LimitError, Limited, MeshDataError};

impl Faces {
    /// An empty face list (`offsets == [0]`).
    pub fn new() -> Faces {
        Faces { offsets: vec![0], indices: Vec::new() }
    }

    /// The number of faces. An `offsets` list left empty (as by `Faces::default()`) counts as
    /// no face.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Whether there is no face.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The vertex indices of face `f`, in order.
    ///
    /// # Panics
    ///
    /// If `f >= self.len()`, like slice indexing.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.indices[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    /// The faces in order, each as its vertex indices.
    pub fn iter(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.offsets.windows(2).map(|w| &self.indices[w[0] as usize..w[1] as usize])
    }

    /// Fan triangulation of every face: a polygon v0 … v(n−1) gives the n − 2 triangles
    /// (v0, vi, vi+1), i = 1 … n − 2, which keeps its orientation. Exact for convex faces;
    /// a face of fewer than three vertices gives no triangle.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.iter().flat_map(|face| {
            let first = face.first().copied().unwrap_or(0);
            face.windows(2).skip(1).map(move |pair| [first, pair[0], pair[1]])
        })
    }

    /// Appends a face.
    ///
    /// # Panics
    ///
    /// If the total number of indices would exceed `u32::MAX` (the offsets are 32-bit).
    pub fn push(&mut self, face: &[u32]) {
        assert!(self.try_push(face), "more than u32::MAX face indices");
    }

    /// Appends a face; returns false, leaving the faces unchanged, if the total number of
    /// indices would exceed `u32::MAX`.
    pub(crate) fn try_push(&mut self, face: &[u32]) -> bool {
        let Some(end) = self.indices.len().checked_add(face.len()).and_then(|end| u32::try_from(end).ok()) else {
            return false;
        };
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.indices.extend_from_slice(face);
        self.offsets.push(end);
        true
    }

    /// Appends a face read from a file, within the limits: at most
    /// [`MAX_FACE_CORNERS`](crate::limits::MAX_FACE_CORNERS) corners, at most
    /// [`MAX_FACES`](crate::limits::MAX_FACES) faces, and at most as many triangles once
    /// fan-triangulated (a face of n ≥ 3 corners gives n − 2). On error the faces are unchanged.
    #[cfg_attr(not(feature = "formats"), allow(dead_code, reason = "the file readers push faces"))]
    pub(crate) fn push_within_limits(&mut self, face: &[u32]) -> Result<(), LimitError> {
        Limited::FaceCorners.check(face.len() as u64)?;
        Limited::Faces.check(self.len() as u64 + 1)?;
        // Each face of n corners gives n − 2 triangles: indices − 2 × faces in all.
        let triangles = ((self.indices.len() + face.len()) as u64).saturating_sub(2 * (self.len() as u64 + 1));
        Limited::Triangles.check(triangles)?;
        let pushed = self.try_push(face);
        debug_assert!(pushed, "the limits keep the indices within u32");
        Ok(())
    }

    /// Checks that `offsets` describes `indices`: starts at 0 (or is empty with no index),
    /// never decreases, and ends at `indices.len()`.
    pub(crate) fn check_offsets(&self) -> Result<(), MeshDataError> {
        let malformed = |reason| Err(MeshDataError::MalformedFaces { reason });
        match self.offsets.first() {
            None if self.indices.is_empty() => return Ok(()),
            None => return malformed("offsets is empty but indices is not"),
            Some(0) => {}
            Some(_) => return malformed("offsets[0] is not 0"),
        }
        if self.offsets.windows(2).any(|w| w[1] < w[0]) {
            return malformed("offsets decrease");
        }
        if self.offsets.last().map(|&l| l as usize) != Some(self.indices.len()) {
            return malformed("the last offset is not indices.len()");
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad_and_triangle() -> Faces {
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2, 3]);
        faces.push(&[3, 2, 4]);
        faces
    }

    #[test]
    fn new_faces_have_a_zero_offset() {
        let faces = Faces::new();
        assert_eq!(faces.offsets, vec![0]);
        assert!(faces.is_empty());
        assert_eq!(faces.len(), 0);
    }

    #[test]
    fn default_faces_count_as_empty_and_accept_push() {
        let mut faces = Faces::default();
        assert_eq!(faces.len(), 0);
        assert_eq!(faces.iter().count(), 0);
        faces.push(&[2, 1, 0]);
        assert_eq!(faces.offsets, vec![0, 3]);
        assert_eq!(faces.face(0), &[2, 1, 0]);
    }

    #[test]
    fn push_and_face_agree() {
        let faces = quad_and_triangle();
        assert_eq!(faces.len(), 2);
        assert_eq!(faces.offsets, vec![0, 4, 7]);
        assert_eq!(faces.face(0), &[0, 1, 2, 3]);
        assert_eq!(faces.face(1), &[3, 2, 4]);
        let all: Vec<&[u32]> = faces.iter().collect();
        assert_eq!(all, vec![&[0, 1, 2, 3][..], &[3, 2, 4][..]]);
    }

    #[test]
    fn triangles_fan_from_first_vertex() {
        let faces = quad_and_triangle();
        let tris: Vec<[u32; 3]> = faces.triangles().collect();
        assert_eq!(tris, vec![[0, 1, 2], [0, 2, 3], [3, 2, 4]]);
    }

    #[test]
    fn triangles_of_pentagon_are_three() {
        let mut faces = Faces::new();
        faces.push(&[5, 6, 7, 8, 9]);
        let tris: Vec<[u32; 3]> = faces.triangles().collect();
        assert_eq!(tris, vec![[5, 6, 7], [5, 7, 8], [5, 8, 9]]);
    }

    #[test]
    fn push_within_limits_refuses_a_face_of_too_many_corners() {
        let mut faces = Faces::new();
        let corners = crate::limits::MAX_FACE_CORNERS;
        let big: Vec<u32> = (0..corners as u32).collect();
        assert_eq!(faces.push_within_limits(&big), Ok(()));
        let bigger: Vec<u32> = (0..=corners as u32).collect();
        let err = faces.push_within_limits(&bigger).unwrap_err();
        assert_eq!(err.to_string(), "65537 vertices in one face, over the limit of 65536 (limits::MAX_FACE_CORNERS)");
        assert_eq!(faces.len(), 1);
    }

    #[test]
    fn check_offsets_rejects_each_broken_invariant() {
        let ok = quad_and_triangle();
        assert_eq!(ok.check_offsets(), Ok(()));
        assert_eq!(Faces::default().check_offsets(), Ok(()));
        let broken = [
            (vec![], vec![1]),
            (vec![1, 4], vec![0, 1, 2, 3]),
            (vec![0, 3, 2], vec![0, 1, 2]),
            (vec![0, 3], vec![0, 1, 2, 3]),
        ];
        for (offsets, indices) in broken {
            let faces = Faces { offsets, indices };
            assert!(matches!(faces.check_offsets(), Err(MeshDataError::MalformedFaces { .. })), "{faces:?}");
        }
    }
}
