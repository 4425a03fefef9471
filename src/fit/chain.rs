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
