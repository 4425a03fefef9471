//! A limb as a chain of sweeps (§5's hierarchy, a branch child on its parent): where a limb
//! ends in a widening (a hand past its wrist, a foot past its ankle, a hoof), one tube's keys
//! describe it poorly, so the limb is split at the narrowest place before the widening into
//! the limb proper and its end, the end a child of the limb so that turning the limb carries
//! it.
//!
//! The place is found from the limb's own profile: the geodesic distance s from its rim (where
//! it is attached to the body), cut at [`LEVELS`] levels whose perimeters give a radius
//! r(s) = P(s)/2π (`super::limb::perimeters`). The wrist is the level of least radius between
//! [`FIRST`] and [`LAST`] of the limb's length beyond which the radius grows to at least
//! [`WIDENING`] times it. A limb with no rim (a whole component) or no such level stays one
//! sweep.

use std::f64::consts::TAU;

use super::geodesic::EdgeGraph;
use super::limb::perimeters;
use super::part::Part;
use crate::mesh::Mesh;

/// Levels of the limb's profile.
pub const LEVELS: usize = 32;
/// The wrist lies at least this fraction of the limb's length from its rim…
pub const FIRST: f64 = 0.3;
/// …and at most this fraction.
pub const LAST: f64 = 0.85;
/// Past the wrist the radius grows to at least this many times the wrist's.
pub const WIDENING: f64 = 1.3;

/// The limb of `mesh` made of `vertices` split at its widening (see the module docs): the part
/// attached to the body first, then its end; `None` where it has none.
pub fn split_at_widening(mesh: &Mesh, vertices: &[u32]) -> Option<[Vec<u32>; 2]> {
    let part = Part::new(mesh, vertices);
    if part.rim.is_empty() || part.triangles.len() < 8 {
        return None;
    }
    let graph = EdgeGraph::new(&part.positions, &part.triangles);
    let mut sources: Vec<u32> = part.rim.iter().flatten().copied().collect();
    sources.sort_unstable();
    sources.dedup();
    let s = graph.distances(&sources);
    let length = s.iter().copied().filter(|d| d.is_finite()).fold(0.0, f64::max);
    if length <= 0.0 {
        return None;
    }
    let h = length / LEVELS as f64;
    let radius: Vec<f64> =
        perimeters(&part.positions, &part.triangles, &s, h, LEVELS, length).iter().map(|p| p / TAU).collect();
    let (first, last) = ((FIRST * LEVELS as f64).ceil() as usize, (LAST * LEVELS as f64).floor() as usize);
    let wrist = (first..=last)
        .filter(|&k| radius[k] > 0.0)
        .filter(|&k| radius[k + 1..].iter().copied().fold(0.0, f64::max) >= WIDENING * radius[k])
        .min_by(|&a, &b| radius[a].total_cmp(&radius[b]).then(a.cmp(&b)))?;
    let cut = wrist as f64 * h;
    let (mut near, mut far) = (Vec::new(), Vec::new());
    for (local, &v) in part.vertices.iter().enumerate() {
        if s[local] < cut {
            near.push(v);
        } else {
            far.push(v);
        }
    }
    (near.len() >= 4 && far.len() >= 4).then_some([near, far])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Faces;
    use glam::DVec3;

    /// A surface of revolution about z: rings of `around` vertices at the heights and radii of
    /// `profile`, the first ring the rim of a flat flange (the body) of radius 4 at its height,
    /// the last closed by a cap. Returns the mesh and the limb's vertices (every ring's and the
    /// cap's, not the flange's).
    fn limb_on_a_flange(profile: &[(f64, f64)], around: u32) -> (Mesh, Vec<u32>) {
        let mut positions = Vec::new();
        let ring = |positions: &mut Vec<DVec3>, z: f64, r: f64| {
            let first = positions.len() as u32;
            for a in 0..around {
                let angle = std::f64::consts::TAU * a as f64 / around as f64;
                positions.push(DVec3::new(r * angle.cos(), r * angle.sin(), z));
            }
            first
        };
        let mut faces = Faces::new();
        let flange = ring(&mut positions, profile[0].0, 4.0);
        let rings: Vec<u32> = profile.iter().map(|&(z, r)| ring(&mut positions, z, r)).collect();
        let cap = positions.len() as u32;
        positions.push(DVec3::new(0.0, 0.0, profile.last().unwrap().0 + 0.2));
        let band = |faces: &mut Faces, lo: u32, hi: u32| {
            for a in 0..around {
                let b = (a + 1) % around;
                faces.push(&[lo + a, lo + b, hi + b, hi + a]);
            }
        };
        band(&mut faces, flange, rings[0]);
        for pair in rings.windows(2) {
            band(&mut faces, pair[0], pair[1]);
        }
        let last = *rings.last().unwrap();
        for a in 0..around {
            faces.push(&[last + a, last + (a + 1) % around, cap]);
        }
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        (mesh, (around..=cap).collect())
    }

    #[test]
    fn a_limb_ending_in_a_widening_splits_at_its_wrist() {
        // Radius 1 up to z = 6, a wrist of 0.8 at z = 6.5, a hand of radius 2 from z = 7.5 to 9.
        let mut profile: Vec<(f64, f64)> = (0..=12).map(|k| (0.5 * k as f64, 1.0)).collect();
        profile.extend([(6.5, 0.8), (7.0, 1.4), (7.5, 2.0), (8.0, 2.0), (8.5, 2.0), (9.0, 1.6)]);
        let (mesh, limb) = limb_on_a_flange(&profile, 16);
        let [near, far] = split_at_widening(&mesh, &limb).expect("a wrist");
        let top = |vertices: &[u32]| vertices.iter().map(|&v| mesh.positions[v as usize].z).fold(f64::MIN, f64::max);
        let bottom = |vertices: &[u32]| vertices.iter().map(|&v| mesh.positions[v as usize].z).fold(f64::MAX, f64::min);
        eprintln!("near up to z = {}, far from z = {}", top(&near), bottom(&far));
        assert!(top(&near) < 6.6 && top(&near) >= 6.0, "the limb ends at its wrist: {}", top(&near));
        assert!(bottom(&far) > 6.0 && bottom(&far) <= 7.0, "the hand starts past it: {}", bottom(&far));
        assert_eq!(near.len() + far.len(), limb.len());
    }

    #[test]
    fn a_tube_without_a_widening_stays_one_limb() {
        // A tube tapering from radius 1 to 0.6: no level grows again.
        let profile: Vec<(f64, f64)> = (0..=18).map(|k| (0.5 * k as f64, 1.0 - 0.4 * k as f64 / 18.0)).collect();
        let (mesh, limb) = limb_on_a_flange(&profile, 16);
        assert!(split_at_widening(&mesh, &limb).is_none());
        // Nor does a part with no rim (the whole mesh, attached nowhere).
        let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
        assert!(split_at_widening(&mesh, &all).is_none());
    }
}
