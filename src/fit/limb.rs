//! Where a protrusion meets the body, for [`super::protrusions`]: the level sets of geodesic
//! distance d from the protrusion's tip are loops around the limb whose total length (the
//! perimeter P(d)) changes slowly along it, a tube's or a tapering cone's, and opens up
//! where the level set spreads onto the body. The limb ends where P grows faster than
//! [`OPENING`] per unit of d: dP/dd is 0 on a cylinder, 2π sin α on a cone of half-angle α,
//! and 2π cos(d/R) on a ball of radius R around a point, so the test is dimensionless and the
//! same for a finger and a leg. This is the level-set diagram's change in a level set's
//! size (Lazarus & Verroust, "Level Set Diagrams of Polyhedral Objects", ACM Solid Modeling
//! 1999, §3), read as a rate.
//!
//! 1. d = edge-path distance from the tip ([`EdgeGraph::distances_within`]), out to [`REACH`]
//!    × the protrusion's length (its persistence).
//! 2. P(d_k) at levels d_k = k·h, h = length / [`LEVELS_PER_LENGTH`], from the segments where
//!    the piecewise-linear d crosses d_k on each triangle.
//! 3. The first level k, at least [`START`] × the length from the tip (past a hand's or a
//!    foot's widening below its fingers or toes) and past the tip's own cap (where the rate
//!    first falls below [`CAPPED`]), where (P(d_k) − P(d_{k−w}))/(w·h) exceeds
//!    [`OPENING`] with w = [`WINDOW`], sustained (P does not fall back by more than
//!    1 − [`KEEPS`] over the next [`SUSTAIN`] levels, as it does past a hand or a foot): the
//!    limb is the vertices with d < d_{k−w}, where the opening began.
//! 4. Tubularity: a limb shorter than [`TUBULAR`] × the radius P/2π of its cut is a bump,
//!    not a limb. Where no level opens and d reaches the whole component (a spout or a handle
//!    that is a component of its own, a snake), the component is the limb if it is that
//!    tubular.
//!
//! Everything depends on edge lengths and connectivity, so a rigidly moved mesh gives the
//! same limb.

use std::f64::consts::TAU;

use glam::DVec3;

use super::geodesic::EdgeGraph;
use super::part::Part;
use super::skeleton::skeleton;
use crate::mesh::Mesh;

/// The search reaches this many times the protrusion's length from its tip.
pub const REACH: f64 = 4.0;
/// Levels per protrusion length.
pub const LEVELS_PER_LENGTH: f64 = 40.0;
/// No cut nearer the tip than this fraction of the protrusion's length.
pub const START: f64 = 0.25;
/// The levels over which the growth of P is measured.
pub const WINDOW: usize = 4;
/// The rate dP/dd above which a level set opens onto the body (2π sin 23.5°).
pub const OPENING: f64 = 2.5;
/// The rate dP/dd below which the level sets have left the tip's cap (2π sin 18.6°).
pub const CAPPED: f64 = 2.0;
/// The levels after an opening over which the perimeter never falls below [`KEEPS`] times the
/// largest it has been since.
pub const SUSTAIN: usize = 20;
/// See [`SUSTAIN`].
pub const KEEPS: f64 = 0.85;
/// A component that is a limb of its own is at least this many times as long as its widest
/// level radius.
pub const WHOLE_TUBE: f64 = 5.0;
/// A limb is at least this many times as long as the radius of its cut.
pub const TUBULAR: f64 = 1.5;

/// The limb of the protrusion found at `tip` (see [`limb`]) and its tip, found again: the
/// merge tree's tip is the vertex farthest from the body's center, which sits to one side of
/// a round end, and the level sets of distance from it, the limb's rim among them, are
/// oblique. The tip is moved to the limb's vertex farthest along the direction of its
/// skeleton's end (from 60% to 90% of its length, [`skeleton`]), and the limb found again
/// from there, so that its rim is normal to it. Indices are the mesh's; `graph` and
/// `triangles` may join vertices `mesh` keeps apart (welded seams).
pub fn aligned_limb(
    mesh: &Mesh,
    graph: &EdgeGraph,
    triangles: &[[u32; 3]],
    tip: u32,
    length: f64,
    component_size: usize,
) -> Option<(Vec<u32>, u32)> {
    let first = limb(&mesh.positions, graph, triangles, tip, length, component_size)?;
    let Some(axis) = skeleton(&Part::new(mesh, &first)).map(|s| s.axis) else { return Some((first, tip)) };
    let Some(direction) = (axis.point(0.9 * axis.length()) - axis.point(0.6 * axis.length())).try_normalize() else {
        return Some((first, tip));
    };
    let along = |v: u32| mesh.positions[v as usize].dot(direction);
    let Some(end) = first.iter().copied().max_by(|&a, &b| along(a).total_cmp(&along(b)).then(b.cmp(&a))) else {
        return Some((first, tip));
    };
    if end == tip {
        return Some((first, tip));
    }
    match limb(&mesh.positions, graph, triangles, end, length, component_size) {
        Some(second) => Some((second, end)),
        None => Some((first, tip)),
    }
}

/// The vertices (increasing) of the limb whose tip is `tip` and whose length (persistence) is
/// `length`, within the component of `component_size` vertices of the mesh whose edges are
/// `graph` and triangles `triangles` (see the module docs); `None` for a bump.
pub fn limb(
    positions: &[DVec3],
    graph: &EdgeGraph,
    triangles: &[[u32; 3]],
    tip: u32,
    length: f64,
    component_size: usize,
) -> Option<Vec<u32>> {
    if !(length > 0.0 && length.is_finite()) {
        return None;
    }
    let limit = REACH * length;
    let d = graph.distances_within(&[tip], limit);
    let h = length / LEVELS_PER_LENGTH;
    let levels = (limit / h).ceil() as usize;
    let perimeter = perimeters(positions, triangles, &d, h, levels, limit);
    let start = (START * LEVELS_PER_LENGTH).ceil() as usize;
    let rate = |k: usize| (perimeter[k] - perimeter[k - WINDOW]) / (WINDOW as f64 * h);
    // Past the tip's own cap (a round end, a hoof's sole), where the level sets grow like
    // circles around a point: the first level where they grow slower than [`CAPPED`].
    let past_cap = (WINDOW..levels).find(|&k| rate(k) < CAPPED).unwrap_or(levels);
    let opening = ((start + WINDOW).max(past_cap + WINDOW)..levels).find(|&k| {
        let rate = (perimeter[k] - perimeter[k - WINDOW]) / (WINDOW as f64 * h);
        // A widening that narrows again (a hand's or a foot's below its wrist or ankle) is
        // not the body.
        let after = &perimeter[k..(k + 1 + SUSTAIN).min(levels)];
        let mut peak = 0.0;
        let keeps = after.iter().all(|&p| {
            peak = f64::max(peak, p);
            p >= KEEPS * peak
        });
        rate > OPENING && after.len() == SUSTAIN + 1 && keeps
    });
    let within = |level: f64| {
        let mut v: Vec<u32> = (0..d.len() as u32).filter(|&v| d[v as usize] < level).collect();
        v.sort_unstable();
        v
    };
    match opening {
        Some(k) => {
            let cut = (k - WINDOW) as f64 * h;
            let tubular = cut >= TUBULAR * perimeter[k - WINDOW] / TAU;
            tubular.then(|| within(cut))
        }
        None => {
            let reached = d.iter().filter(|&&x| x <= limit).count();
            let far = d.iter().copied().filter(|&x| x <= limit).fold(0.0, f64::max);
            let last = ((far / h).floor() as usize).min(levels);
            let whole = reached == component_size && last > 1;
            // A component that is a tube everywhere: no level set's radius over
            // 1/WHOLE_TUBE of its length.
            let widest = perimeter[1..last].iter().copied().fold(0.0, f64::max) / TAU;
            (whole && far >= WHOLE_TUBE * widest).then(|| within(f64::INFINITY))
        }
    }
}

/// P(k·h) for k = 0 … `levels` − 1: the length of the level set d = k·h over the triangles
/// whose three distances are at most `limit`.
pub fn perimeters(positions: &[DVec3], triangles: &[[u32; 3]], d: &[f64], h: f64, levels: usize, limit: f64) -> Vec<f64> {
    let mut perimeter = vec![0.0; levels];
    for t in triangles {
        let g = t.map(|v| d[v as usize]);
        if g.iter().any(|&x| x > limit) {
            continue;
        }
        let (lo, hi) = (g[0].min(g[1]).min(g[2]), g[0].max(g[1]).max(g[2]));
        let first = (lo / h).floor() as usize + 1;
        let last = ((hi / h).ceil() as usize).min(levels);
        for (k, sum) in perimeter.iter_mut().enumerate().take(last).skip(first) {
            let level = k as f64 * h;
            let mut ends = [DVec3::ZERO; 2];
            let mut found = 0;
            for e in 0..3 {
                let (a, b) = (e, (e + 1) % 3);
                if (g[a] < level) != (g[b] < level) && found < 2 {
                    let (pa, pb) = (positions[t[a] as usize], positions[t[b] as usize]);
                    ends[found] = pa + (pb - pa) * ((level - g[a]) / (g[b] - g[a]));
                    found += 1;
                }
            }
            if found == 2 {
                *sum += ends[0].distance(ends[1]);
            }
        }
    }
    perimeter
}
