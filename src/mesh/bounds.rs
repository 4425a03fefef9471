//! Axis-aligned bounds of a mesh.

use glam::DVec3;

use super::Mesh;

impl Mesh {
    /// Axis-aligned bounds (min, max) of [`Mesh::positions`]; `(0, 0)` if there is none.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        bounds_of(&self.positions)
    }

    /// Length of the bounding-box diagonal, |max − min| (0 without positions).
    pub fn diagonal(&self) -> f64 {
        let (min, max) = self.bounds();
        (max - min).length()
    }
}

/// Axis-aligned bounds (min, max) of `positions`; `(0, 0)` for an empty list.
pub(crate) fn bounds_of(positions: &[DVec3]) -> (DVec3, DVec3) {
    let Some(&first) = positions.first() else {
        return (DVec3::ZERO, DVec3::ZERO);
    };
    positions.iter().fold((first, first), |(min, max), &p| (min.min(p), max.max(p)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_of_scattered_points() {
        let points = [DVec3::new(1.0, -2.0, 3.0), DVec3::new(-1.0, 5.0, 0.5), DVec3::new(0.0, 0.0, 4.0)];
        let (min, max) = bounds_of(&points);
        assert_eq!(min, DVec3::new(-1.0, -2.0, 0.5));
        assert_eq!(max, DVec3::new(1.0, 5.0, 4.0));
    }

    #[test]
    fn bounds_of_nothing_is_the_origin() {
        assert_eq!(bounds_of(&[]), (DVec3::ZERO, DVec3::ZERO));
    }

    #[test]
    fn diagonal_of_a_box() {
        let mesh =
            Mesh::from_parts(vec![DVec3::ZERO, DVec3::new(1.0, 2.0, 2.0)], crate::mesh::Faces::new(), Vec::new())
                .unwrap();
        assert_eq!(mesh.diagonal(), 3.0);
    }
}
