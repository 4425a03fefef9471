//! Falloff weights (rig field `falloff`): how much of its own sweep's deformation each owned
//! vertex near its part's boundary follows, computed once at bind time.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind** (falloff weights) → deform → normals
//! → output.
//!
//! The part of sweep s is the set of vertices it owns; its falloff W_s ≥ 0 (mesh units) is the
//! width of the band inside the part where the deformation fades out. The mesh is taken as the
//! fan triangulation of its faces ([`Faces::triangles`]); its edges are the triangles' edges,
//! and the copies of a vertex along an unwelded seam (one position, bit for bit, no edge
//! between them) are one vertex where one sweep owns them and face each other across the
//! part's boundary where two owners meet there (see `seams`), so that they move together.
//!
//! 1. **Boundary.** A vertex of the part is on its boundary when it shares an edge with a
//!    vertex the sweep does not own. It faces what lies across: the rest position
//!    ([`UNOWNED`]) if any such neighbour is unowned, otherwise the sweep that owns most of
//!    them (one per distinct neighbour; the lower index on a tie).
//! 2. **Distance.** g is the geodesic distance from the boundary along the part's own surface
//!    (g = 0 on the boundary), by fast marching on the triangles whose corners all belong to
//!    the part (R. Kimmel and J. A. Sethian, "Computing geodesic paths on manifolds", PNAS
//!    95(15), 1998), stopped at g = W_s; see `geodesic`. Each vertex faces what the boundary
//!    vertex its distance came from faces.
//! 3. **Weight.** With x = g / W_s and the C¹ smoothstep S(x) = 3x² − 2x³ on [0, 1] (S = 1
//!    past 1):
//!    - facing the rest, or a sweep B with W_B = 0: w = S(x), fading fully into the rest
//!      position or into B;
//!    - facing a sweep B with W_B > 0: w = ½ + ½·S(x), so that the two bands of a seam
//!      both meet at w = ½ and the blend is continuous across it.
//!
//! A sweep with W_s = 0 has a hard boundary: no band. A part with no boundary (a component
//! of its own) has none either. Only vertices with w < 1 (g < W_s) are listed, and the march
//! visits no vertex past its band's one-ring.

mod boundary;
mod corners;
mod geodesic;
mod seams;

use std::collections::HashMap;

use glam::DVec3;

use crate::bind::UNOWNED;
use crate::mesh::Faces;
use corners::Corners;
use geodesic::Reached;

/// A vertex in a falloff band and what its deformation fades into.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandWeight {
    /// The vertex, an index into the mesh's positions.
    pub vertex: u32,
    /// w ∈ [0, 1): the share of its own sweep's deformation the vertex follows.
    pub weight: f64,
    /// The sweep whose deformation the rest (1 − w) comes from, or [`UNOWNED`]: the rest position.
    pub neighbour: u32,
}

impl BandWeight {
    /// Whether the vertex fades into the rest position rather than a neighbouring sweep.
    pub fn fades_to_rest(&self) -> bool {
        self.neighbour == UNOWNED
    }

    /// Whether the vertex keeps its rest position exactly: weight 0 against the rest position.
    pub fn keeps_rest(&self) -> bool {
        self.weight == 0.0 && self.fades_to_rest()
    }
}

/// The falloff band of every part (see the module docs): one entry for each owned vertex with
/// w < 1, sorted by vertex. `owners[i]` is the sweep owning vertex i (an index into
/// `falloff`) or [`UNOWNED`]; `falloff[s]` is W_s in mesh units.
///
/// The caller validates the rig (finite W_s ≥ 0, one owner per position); beyond that any
/// mesh is accepted without panicking and never gives NaN: polygons count as their fan
/// triangles, degenerate triangles (zero area, repeated corners) only update along their
/// edges, faces of fewer than three vertices add no edge, and triangles with a vertex index
/// past `positions` are ignored. So are vertices past the shorter of `positions` and `owners`,
/// and a sweep whose W_s is not positive and finite, or that `falloff` does not list, gets no
/// band.
pub fn band_weights(faces: &Faces, positions: &[DVec3], owners: &[u32], falloff: &[f64]) -> Vec<BandWeight> {
    let widths = band_widths(falloff);
    band_distances(faces, positions, owners, &widths)
        .into_iter()
        .map(|reached| {
            let width = widths[owners[reached.vertex as usize] as usize];
            let meets_half = width_of(&widths, reached.label) > 0.0;
            let weight = falloff_weight(reached.distance / width, meets_half);
            BandWeight { vertex: reached.vertex, weight, neighbour: reached.label }
        })
        .filter(|band| band.weight < 1.0)
        .collect()
}

/// The geodesic distance g < W_s of every vertex in a band, sorted by vertex, with the label
/// it faces; `widths` from [`band_widths`].
fn band_distances(faces: &Faces, positions: &[DVec3], owners: &[u32], widths: &[f64]) -> Vec<Reached> {
    let count = positions.len().min(owners.len());
    let (positions, owners) = (&positions[..count], &owners[..count]);
    let active: Vec<bool> = owners.iter().map(|&owner| width_of(widths, owner) > 0.0).collect();
    if !active.contains(&true) {
        return Vec::new();
    }
    let mut corners = Corners::new(faces, &active);
    let seams = seams::seams(&corners, positions, owners, &active).unwrap_or_default();
    let joins = seams.joins();
    if joins {
        let first = |v: u32| seams.first.get(v as usize).copied().unwrap_or(v);
        let indices = faces.indices.iter().map(|&v| first(v)).collect();
        corners = Corners::new(&Faces { offsets: faces.offsets.clone(), indices }, &active);
    }
    let sources = boundary::sources(&corners, owners, &active, &seams.across);
    let mut reached = geodesic::march(&corners, positions, owners, widths, &sources);
    if joins {
        let mut copies: HashMap<u32, Vec<u32>> = HashMap::new();
        for (v, &first) in seams.first.iter().enumerate() {
            if first as usize != v {
                copies.entry(first).or_default().push(v as u32);
            }
        }
        let of_copies: Vec<Reached> = reached
            .iter()
            .flat_map(|r| copies.get(&r.vertex).into_iter().flatten().map(|&vertex| Reached { vertex, ..*r }))
            .collect();
        reached.extend(of_copies);
    }
    reached.sort_unstable_by_key(|reached| reached.vertex);
    reached
}

/// W_s for each sweep, with 0 (no band) for a falloff that is not positive and finite.
fn band_widths(falloff: &[f64]) -> Vec<f64> {
    falloff.iter().map(|&width| if width > 0.0 && width.is_finite() { width } else { 0.0 }).collect()
}

/// W of a sweep, or 0 for [`UNOWNED`] and an index past `widths`.
fn width_of(widths: &[f64], sweep: u32) -> f64 {
    widths.get(sweep as usize).copied().unwrap_or(0.0)
}

/// The smoothstep S(x) = 3x² − 2x³ on [0, 1], 0 below and 1 above: S(0) = 0, S(1) = 1,
/// S′(0) = S′(1) = 0, so the clamped curve is C¹.
fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// The weight at x = g / W: S(x) when the band fades fully (into the rest position or a sweep
/// with no band of its own), ½ + ½·S(x) when it `meets_half` of a neighbouring band.
fn falloff_weight(x: f64, meets_half: bool) -> f64 {
    if meets_half { 0.5 + 0.5 * smoothstep(x) } else { smoothstep(x) }
}

#[cfg(test)]
mod tests;
