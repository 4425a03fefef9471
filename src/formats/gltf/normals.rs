//! Area-weighted vertex normals: n(v) = normalize(Σ (b − a) × (c − a)) over the triangles
//! (a, b, c) at v — each triangle weighs twice its area.

use glam::DVec3;

/// The unnormalized area-weighted normal of each of `count` vertices.
pub(super) fn sums(positions: impl Fn(u32) -> DVec3, count: usize, triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; count];
    for &[a, b, c] in triangles {
        let (pa, pb, pc) = (positions(a), positions(b), positions(c));
        let n = (pb - pa).cross(pc - pa);
        for v in [a, b, c] {
            if let Some(sum) = sums.get_mut(v as usize) {
                *sum += n;
            }
        }
    }
    sums
}

/// A sum of [`sums`] as a unit f32 normal, or `None` for a vertex of no (or only degenerate)
/// triangle.
pub(super) fn unit(sum: DVec3) -> Option<[f32; 3]> {
    let n = sum.try_normalize()?.as_vec3();
    n.is_finite().then(|| n.to_array())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn larger_triangles_weigh_more() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.0, 0.0, 0.1)];
        let sums = sums(|v| p[v as usize], 4, &[[0, 1, 2], [0, 3, 1]]);
        let n = unit(sums[0]).unwrap();
        assert!(n[2] > 0.99 && n[1] > 0.0, "{n:?}");
        assert_eq!(unit(DVec3::ZERO), None);
    }
}
