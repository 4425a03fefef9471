//! A tube bent by a right angle on a flat flange, for the chain and limb search tests: up z
//! to (0, 0, 6), around a quarter circle of radius 2 to (2, 0, 8), then along +x to (8, 0, 8),
//! capped at the end.

use glam::DVec3;

use crate::mesh::{Faces, Mesh};

/// The ring centers of the bent tube, each with the tube's direction there.
pub(crate) fn elbow_centers() -> Vec<(DVec3, DVec3)> {
    let mut centers: Vec<(DVec3, DVec3)> = (0..=12).map(|k| (DVec3::new(0.0, 0.0, 0.5 * k as f64), DVec3::Z)).collect();
    for k in 1..8 {
        let angle = std::f64::consts::FRAC_PI_2 * k as f64 / 8.0;
        let center = DVec3::new(2.0 - 2.0 * angle.cos(), 0.0, 6.0 + 2.0 * angle.sin());
        centers.push((center, DVec3::new(angle.sin(), 0.0, angle.cos())));
    }
    centers.extend((0..=12).map(|k| (DVec3::new(2.0 + 0.5 * k as f64, 0.0, 8.0), DVec3::X)));
    centers
}

/// Rings of `around` vertices of radius `radius` about `centers`, the first ring the rim of a
/// flange of radius `flange`, the last capped 0.2 past its center. With `seam` = `Some(i)`, ring
/// `i` is stored twice, the triangles below it on one copy and those above on the other (an
/// unwelded seam; the copy comes after the last ring). The mesh and the vertices of the tube
/// (every ring and the cap, not the flange).
pub(crate) fn tube_along(
    centers: &[(DVec3, DVec3)],
    radius: f64,
    around: u32,
    flange: f64,
    seam: Option<usize>,
) -> (Mesh, Vec<u32>) {
    let mut positions = Vec::new();
    let ring = |positions: &mut Vec<DVec3>, (center, normal): (DVec3, DVec3), r: f64| {
        let first = positions.len() as u32;
        let x = normal.cross(DVec3::Y).normalize();
        let y = normal.cross(x);
        for a in 0..around {
            let angle = std::f64::consts::TAU * a as f64 / around as f64;
            positions.push(center + (x * angle.cos() + y * angle.sin()) * r);
        }
        first
    };
    let mut faces = Faces::new();
    let rim = ring(&mut positions, centers[0], flange);
    let rings: Vec<u32> = centers.iter().map(|&c| ring(&mut positions, c, radius)).collect();
    let copy = seam.map(|i| ring(&mut positions, centers[i], radius));
    let cap = positions.len() as u32;
    let (end, direction) = centers[centers.len() - 1];
    positions.push(end + direction * 0.2);
    let mut lower = rim;
    for (i, &upper) in rings.iter().enumerate() {
        for a in 0..around {
            let b = (a + 1) % around;
            faces.push(&[lower + a, lower + b, upper + b, upper + a]);
        }
        lower = match (seam, copy) {
            (Some(s), Some(copy)) if s == i => copy,
            _ => upper,
        };
    }
    let last = *rings.last().unwrap();
    for a in 0..around {
        faces.push(&[last + a, last + (a + 1) % around, cap]);
    }
    let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
    (mesh, (around..=cap).collect())
}
