//! The signed volume enclosed by a closed mesh (divergence theorem).

use glam::DVec3;

use super::bounds::bounds_of;
use super::{Mesh, MeshDataError};

impl Mesh {
    /// Signed volume enclosed by the faces at `positions` (one per vertex, e.g. deformed):
    ///
    /// ```text
    /// V = 1/6 · Σ (a − c) · ((b − c) × (d − c))
    /// ```
    ///
    /// over the fan triangles (a, b, d) of every face ([`Faces::triangles`]), with c the
    /// centre of the bounding box of `positions`. By the divergence theorem the sum does not
    /// depend on c for a closed mesh; taking c at the centre keeps the terms small, so
    /// translating the mesh far from the origin does not cost precision. Positive for outward
    /// (counter-clockwise seen from outside) orientation. For an open mesh the value depends on
    /// c and is only the volume of the cone from c over the faces.
    ///
    /// # Panics
    ///
    /// If `positions` is shorter than a face index requires; see
    /// [`Mesh::try_enclosed_volume`] for the checked variant.
    ///
    /// [`Faces::triangles`]: super::Faces::triangles
    pub fn enclosed_volume(&self, positions: &[DVec3]) -> f64 {
        let c = {
            let (min, max) = bounds_of(positions);
            (min + max) * 0.5
        };
        let six_v: f64 = self
            .faces
            .triangles()
            .map(|[a, b, d]| {
                let a = positions[a as usize] - c;
                let b = positions[b as usize] - c;
                let d = positions[d as usize] - c;
                a.dot(b.cross(d))
            })
            .sum();
        six_v / 6.0
    }

    /// Whether every edge of the faces is shared by exactly two faces, so that
    /// [`Mesh::enclosed_volume`] is a volume.
    pub fn is_closed(&self) -> bool {
        let mut edges: Vec<(u32, u32)> = self
            .faces
            .iter()
            .flat_map(|face| {
                let next = face.iter().cycle().skip(1);
                face.iter().zip(next).map(|(&a, &b)| (a.min(b), a.max(b)))
            })
            .collect();
        edges.sort_unstable();
        !edges.is_empty() && edges.chunk_by(|a, b| a == b).all(|run| run.len() == 2)
    }

    /// [`Mesh::enclosed_volume`], or [`MeshDataError::PositionCount`] if `positions` does not have
    /// one entry per vertex.
    pub fn try_enclosed_volume(&self, positions: &[DVec3]) -> Result<f64, MeshDataError> {
        if positions.len() != self.positions.len() {
            return Err(MeshDataError::PositionCount { expected: self.positions.len(), found: positions.len() });
        }
        Ok(self.enclosed_volume(positions))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Faces;

    /// Unit cube [0, 1]³ as six outward quads.
    fn cube() -> Mesh {
        let positions =
            (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64)).collect();
        let mut faces = Faces::new();
        for quad in [
            [0, 2, 3, 1], // z = 0, normal −z
            [4, 5, 7, 6], // z = 1, normal +z
            [0, 1, 5, 4], // y = 0, normal −y
            [2, 6, 7, 3], // y = 1, normal +y
            [0, 4, 6, 2], // x = 0, normal −x
            [1, 3, 7, 5], // x = 1, normal +x
        ] {
            faces.push(&quad);
        }
        Mesh::from_parts(positions, faces, Vec::new()).unwrap()
    }

    #[test]
    fn unit_cube_has_volume_one() {
        let cube = cube();
        let v = cube.enclosed_volume(&cube.positions);
        assert!((v - 1.0).abs() < 1e-14, "{v}");
    }

    #[test]
    fn reversed_cube_has_volume_minus_one() {
        let mut cube = cube();
        for f in 0..cube.faces.len() {
            let (s, e) = (cube.faces.offsets[f] as usize, cube.faces.offsets[f + 1] as usize);
            cube.faces.indices[s..e].reverse();
        }
        let v = cube.enclosed_volume(&cube.positions);
        assert!((v + 1.0).abs() < 1e-14, "{v}");
    }

    #[test]
    fn far_translated_scaled_cube_keeps_its_volume() {
        let cube = cube();
        let moved: Vec<DVec3> = cube.positions.iter().map(|&p| p * 2.0 + DVec3::new(1e6, -3e6, 2e6)).collect();
        let v = cube.enclosed_volume(&moved);
        assert!((v - 8.0).abs() < 1e-12, "{v}");
    }

    #[test]
    fn try_enclosed_volume_checks_the_length() {
        let cube = cube();
        let err = cube.try_enclosed_volume(&cube.positions[..7]).unwrap_err();
        assert_eq!(err.to_string(), "positions has 7 entries but the mesh has 8 vertices");
        assert!((cube.try_enclosed_volume(&cube.positions).unwrap() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn cube_is_closed_until_a_face_is_removed() {
        let cube = cube();
        assert!(cube.is_closed());
        let mut faces = crate::mesh::Faces::new();
        for face in cube.faces.iter().skip(1) {
            faces.push(face);
        }
        let open = Mesh::from_parts(cube.positions.clone(), faces, Vec::new()).unwrap();
        assert!(!open.is_closed());
    }
}
