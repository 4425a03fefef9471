//! Which vertices take Jacobian normals ([`crate::deform::jacobian`]): those whose whole
//! one-ring one sweep moves by one smooth map. There the normal of the deformation is the limit
//! of the deformed facets' normals; across a hard boundary between two sweeps (or a sweep and
//! the unmoved rest) and in falloff bands the facets bend by two maps at once, and the normals
//! of the deformed triangles are the right ones. Within the reach,
//! [`crate::deform::jacobian_normal_vertices`] leaves out the rings too coarse for the deformation.

use crate::layout::UNOWNED;

/// For each vertex, whether its `influence` (the sweep moving it whole, or [`UNOWNED`] for a
/// vertex that no sweep moves alone: unbound, or in a falloff band) is a sweep shared by every
/// vertex of every triangle of `triangles` (three indices each) it belongs to.
pub fn jacobian_reach(triangles: &[u32], influence: &[u32]) -> Vec<bool> {
    let mut reach: Vec<bool> = influence.iter().map(|&s| s != UNOWNED).collect();
    for triangle in triangles.chunks_exact(3) {
        let sweep = influence[triangle[0] as usize];
        if triangle.iter().any(|&v| influence[v as usize] != sweep) {
            for &v in triangle {
                reach[v as usize] = false;
            }
        }
    }
    reach
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_across_two_influences_leaves_the_reach() {
        // Two triangles sharing edge 1-2: the first all sweep 0, the second with vertex 3 unowned.
        let triangles = [0, 1, 2, 1, 3, 2];
        assert_eq!(jacobian_reach(&triangles, &[0, 0, 0, UNOWNED]), [true, false, false, false]);
        assert_eq!(jacobian_reach(&triangles, &[0, 0, 0, 0]), [true; 4]);
        assert_eq!(jacobian_reach(&triangles, &[0, 0, 0, 1]), [true, false, false, false]);
        // A vertex in no triangle keeps its own influence's answer.
        assert_eq!(jacobian_reach(&[], &[2, UNOWNED]), [true, false]);
    }
}
