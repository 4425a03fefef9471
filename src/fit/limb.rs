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
//!    1 − [`KEEPS`] over the next [`SUSTAIN`] levels, as it does past a hand or a foot, unless
//!    the level set falls apart first and stays apart, as past a crotch seen from a foot:
//!    `falls_apart_before_falling`): the limb is the vertices with d < d_{k−w}, where the
//!    opening began. A widening that falls
//!    back later, to a wrist and a forearm (`wrist_within`), is a long hand (a cartoon's),
//!    not the body: the limb runs on through it to the next opening where it is still at most
//!    [`MAX_SHARE`] of its component (past a body's neck it is not).
//! 4. **Forks.** A limb that would hold more than [`MAX_SHARE`] of its component is cut
//!    instead at the lowest level below its opening where the region farther from the tip
//!    falls apart into two pieces each reaching on at least [`START`] × the length
//!    ([`fork_level`]): a coarse crotch seen from a foot, the body above and the other leg
//!    below, reached before the level sets open.
//! 5. Tubularity: a limb shorter than [`TUBULAR`] × the radius P/2π of its cut is a bump,
//!    not a limb. Where no level opens and d reaches the whole component (a spout or a handle
//!    that is a component of its own, a snake), the component is the limb if it is that
//!    tubular; where it forks as in 4, into a limb of at most [`FORKED_SHARE`] of it, it is cut
//!    at the fork instead (a slim figure of one piece seen from her foot, whose waist narrows
//!    past her hips so that her level sets never open for long: her other leg and her body
//!    part there).
//!
//! Everything depends on edge lengths and connectivity, so a rigidly moved mesh gives the
//! same limb.

use std::collections::HashMap;
use std::collections::hash_map::Entry;
use std::f64::consts::TAU;
use std::hash::BuildHasherDefault;

use glam::DVec3;

use super::disjoint_sets::DisjointSets;
use super::geodesic::EdgeGraph;
use super::axis::Polyline;
use super::part::Part;
use super::skeleton::skeleton;
use crate::mesh::Mesh;
use crate::mesh::weld::PositionHasher;

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
/// A widening is a hand (not the body) where within this many levels its perimeter falls below
/// [`WRIST`] times its largest since…
pub const HAND: usize = 40;
/// …(see [`HAND`])…
pub const WRIST: f64 = 0.75;
/// …and then holds within [`FOREARM_SPREAD`] of that for this many levels, a forearm's.
pub const FOREARM: usize = 10;
/// See [`FOREARM`].
pub const FOREARM_SPREAD: f64 = 0.1;
/// A component that is a limb of its own is at least this many times as long as its widest
/// level radius.
pub const WHOLE_TUBE: f64 = 5.0;
/// A limb of fewer vertices than this is coarse (fewer than the 6 × 32 radii the fit's first
/// keys sample): its level sets may cut it obliquely, one triangle deep (`squared_off`).
pub const COARSE: usize = 192;
/// A coarse limb's rim is oblique where it spreads along the limb's skeleton over at least this
/// many times its mean radius (a cut at 45° or more off the plane normal to the limb).
pub const OBLIQUE: f64 = 2.0;
/// A limb holds at most this share of its component's vertices: more is the body's far side
/// (the eldest branch of a body with short protrusions, such as the bunny's back), not a limb.
pub const MAX_SHARE: f64 = 0.25;
/// A coarse limb whose rim is oblique is grown by at most 1/this of its vertices to even it
/// (`evened`): a ring's vertex or two left out by the cut, not a share of the body.
pub const GROWN_SHARE: usize = 5;
/// A coarse limb grown to even its rim (`evened`) is kept grown only where its rim then
/// spreads along its skeleton over at most this many times its radius (a cut within about 27°
/// of the plane normal to the limb; an oblique one spreads over [`OBLIQUE`] times or more):
/// a ring completed, not a rim that crept a little way into a crotch.
pub const EVEN: f64 = 1.0;
/// A component reached whole from a tip, its level sets never opening (see [`limb`]), is cut at
/// its fork where the limb so cut holds at most this share of it.
pub const FORKED_SHARE: f64 = 0.5;
/// A limb is at least this many times as long as the radius of its cut.
pub const TUBULAR: f64 = 1.5;
/// A spike of a coarse limb lies farther than this many of its rim's radii from the rim's
/// centroid (`without_spikes`).
pub const SPIKE: f64 = 2.0;

/// The limb of the protrusion found at `tip` (see [`limb`]) and its tip, found again: the
/// merge tree's tip is the vertex farthest from the body's center, which sits to one side of
/// a round end, and the level sets of distance from it, the limb's rim among them, are
/// oblique. The tip is moved to the limb's vertex farthest along the direction of its
/// skeleton's end (from 60% to 90% of its length, [`skeleton`]), and the limb found again
/// from there, so that its rim is normal to it. A limb of fewer than [`COARSE`] vertices whose
/// rim is still oblique is then evened where a few more vertices complete the ring its cut
/// passed through (`evened`), and otherwise squared off (`squared_off`); then it drops its
/// spikes (`without_spikes`). Indices are the mesh's; `graph` and `triangles` may join
/// vertices `mesh` keeps apart (welded seams), and `welded` is then `mesh` on `triangles`.
pub fn aligned_limb(
    mesh: &Mesh,
    welded: Option<&Mesh>,
    graph: &EdgeGraph,
    triangles: &[[u32; 3]],
    tip: u32,
    length: f64,
    component_size: usize,
) -> Option<(Vec<u32>, u32)> {
    let (vertices, tip) = aligned(mesh, welded, graph, triangles, tip, length, component_size)?;
    if vertices.len() >= COARSE {
        return Some((vertices, tip));
    }
    let vertices = evened(mesh, graph, triangles, vertices, tip, length);
    let vertices = squared_off(mesh, triangles, vertices, tip);
    Some((without_spikes(mesh, triangles, vertices), tip))
}

/// The coarse limb `vertices` without its spikes: rim vertices (on a triangle that leaves the
/// limb) that share no limb triangle with a vertex off the rim, and lie farther than [`SPIKE`]
/// times the radius of the rest of the rim from its centroid. On a mesh this coarse a level set
/// may reach one vertex of the body past the limb's last ring (a blocky figure's shoulder
/// corner, on the torso's top, as near the hand as the arm's top ring): the limb reaches it only
/// through its rim, and a section through the long triangles to it is no tube's.
fn without_spikes(mesh: &Mesh, triangles: &[[u32; 3]], vertices: Vec<u32>) -> Vec<u32> {
    let count = mesh.positions.len();
    let inside = mask(count, &vertices);
    let on_rim = rim_mask(triangles, &inside);
    // Per limb vertex, whether it shares a limb triangle with a limb vertex off the rim.
    let mut reaches_inside = vec![false; count];
    for t in triangles.iter().filter(|t| t.iter().all(|&v| inside[v as usize])) {
        if t.iter().any(|&v| !on_rim[v as usize]) {
            for &v in t {
                reaches_inside[v as usize] = true;
            }
        }
    }
    let dangling = |v: u32| on_rim[v as usize] && !reaches_inside[v as usize];
    if !vertices.iter().any(|&v| dangling(v)) {
        return vertices;
    }
    let rest: Vec<u32> = vertices.iter().copied().filter(|&v| on_rim[v as usize] && !dangling(v)).collect();
    if rest.is_empty() {
        return vertices;
    }
    let (centroid, radius) = spread_around_centroid(mesh, &rest);
    let near = |v: u32| mesh.positions[v as usize].distance(centroid) <= SPIKE * radius;
    vertices.into_iter().filter(|&v| !dangling(v) || near(v)).collect()
}

/// Per mesh vertex, whether it is a rim vertex of the limb marked `inside`: in the limb, on a
/// triangle that leaves it.
fn rim_mask(triangles: &[[u32; 3]], inside: &[bool]) -> Vec<bool> {
    let mut on_rim = vec![false; inside.len()];
    for t in triangles.iter().filter(|t| t.iter().any(|&v| !inside[v as usize])) {
        for &v in t {
            on_rim[v as usize] |= inside[v as usize];
        }
    }
    on_rim
}

/// The centroid of `vertices` and their mean distance from it.
fn spread_around_centroid(mesh: &Mesh, vertices: &[u32]) -> (DVec3, f64) {
    let position = |v: u32| mesh.positions[v as usize];
    let count = vertices.len().max(1) as f64;
    let centroid = vertices.iter().map(|&v| position(v)).sum::<DVec3>() / count;
    (centroid, vertices.iter().map(|&v| position(v).distance(centroid)).sum::<f64>() / count)
}

/// Where a coarse limb meets the rest of the mesh, seen along the limb's skeleton.
struct Rim {
    /// The limb's skeleton, from its attached end to its tip.
    axis: Polyline,
    /// The rim vertices' positions along `axis`, the nearest the body and the nearest the tip.
    shallowest: f64,
    deepest: f64,
    /// The rim vertices' mean distance from their centroid.
    radius: f64,
}

impl Rim {
    /// The rim of the limb made of `vertices`: its vertices on a triangle that leaves the limb.
    /// `None` where the limb has no skeleton.
    fn of(mesh: &Mesh, triangles: &[[u32; 3]], vertices: &[u32]) -> Option<Rim> {
        let axis = skeleton(&Part::new(mesh, vertices))?.axis;
        let on_rim = rim_mask(triangles, &mask(mesh.positions.len(), vertices));
        let rim: Vec<u32> = (0..on_rim.len() as u32).filter(|&v| on_rim[v as usize]).collect();
        let along: Vec<f64> = rim.iter().map(|&v| axis.project(mesh.positions[v as usize])).collect();
        let deepest = along.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let shallowest = along.iter().copied().fold(f64::INFINITY, f64::min);
        let (_, radius) = spread_around_centroid(mesh, &rim);
        Some(Rim { axis, shallowest, deepest, radius })
    }

    /// Whether the limb is to be squared off ([`squared_off`]): its rim spreads along the
    /// skeleton over [`OBLIQUE`] times its radius or more, down to no more than half the
    /// skeleton's length.
    fn squares_off(&self) -> bool {
        let oblique = self.deepest - self.shallowest >= OBLIQUE * self.radius;
        oblique && self.deepest > 0.0 && self.deepest <= 0.5 * self.axis.length()
    }

    /// The rim's spread along the skeleton over its radius.
    fn spread(&self) -> f64 {
        (self.deepest - self.shallowest) / self.radius
    }
}

/// Marks `vertices` in a mask over the mesh's vertices.
fn mask(count: usize, vertices: &[u32]) -> Vec<bool> {
    let mut inside = vec![false; count];
    for &v in vertices {
        inside[v as usize] = true;
    }
    inside
}

/// The coarse limb `vertices` (found from `tip`, of protrusion length `length`), grown where
/// its rim is [`OBLIQUE`] only because its cut passed between the vertices of one ring: on a
/// mesh this coarse the edge-path distances of a ring's vertices from the tip differ by up to
/// an edge, and a cut between them leaves a vertex of the ring outside, which drags the rim
/// down the limb to its neighbours (the faerie's shoulder ring, one vertex past the cut, took
/// the rim down to the elbow, and squaring off then cut the upper arm away). The limb takes
/// the next vertices in distance from the tip that share a triangle with it (not a touching
/// piece's across a bridge), one at a time, no farther than [`WINDOW`]
/// levels past its cut (where the opening onto the body was measured from) nor more than
/// 1/[`GROWN_SHARE`] of its vertices, and is the one of those whose rim is evenest (least
/// spread along the skeleton for its radius), where that is [`EVEN`]; where none is, it stays
/// as it was.
fn evened(mesh: &Mesh, graph: &EdgeGraph, triangles: &[[u32; 3]], vertices: Vec<u32>, tip: u32, length: f64) -> Vec<u32> {
    let count = mesh.positions.len();
    if !Rim::of(mesh, triangles, &vertices).is_some_and(|rim| rim.squares_off()) {
        return vertices;
    }
    let d = graph.distances_within(&[tip], REACH * length);
    let cut = vertices.iter().map(|&v| d[v as usize]).fold(0.0, f64::max);
    let reach = cut + WINDOW as f64 * length / LEVELS_PER_LENGTH;
    let inside = mask(count, &vertices);
    // The vertices on the limb's triangles (not across a bridge to a touching piece).
    let mut beside = vec![false; count];
    for t in triangles.iter().filter(|t| t.iter().any(|&v| inside[v as usize])) {
        for &v in t {
            beside[v as usize] = !inside[v as usize];
        }
    }
    let mut next: Vec<u32> =
        (0..count as u32).filter(|&v| beside[v as usize] && d[v as usize] > cut && d[v as usize] <= reach).collect();
    next.sort_by(|&a, &b| d[a as usize].total_cmp(&d[b as usize]).then(a.cmp(&b)));
    next.truncate(vertices.len() / GROWN_SHARE);
    // The evenest of the limbs grown by the first 1, 2, … of them: the least spread of its
    // rim along its skeleton for its radius, the fewest vertices on a tie.
    let mut best: Option<(f64, Vec<u32>)> = None;
    let mut grown = vertices.clone();
    for v in next {
        grown.push(v);
        let mut sorted = grown.clone();
        sorted.sort_unstable();
        let Some(rim) = Rim::of(mesh, triangles, &sorted) else { continue };
        let spread = rim.spread();
        if spread <= EVEN && best.as_ref().is_none_or(|(least, _)| spread < *least) {
            best = Some((spread, sorted));
        }
    }
    best.map_or(vertices, |(_, evenest)| evenest)
}

/// The limb found again from its aligned tip (see [`aligned_limb`]), not yet squared off.
fn aligned(
    mesh: &Mesh,
    welded: Option<&Mesh>,
    graph: &EdgeGraph,
    triangles: &[[u32; 3]],
    tip: u32,
    length: f64,
    component_size: usize,
) -> Option<(Vec<u32>, u32)> {
    let first = limb(&mesh.positions, graph, triangles, tip, length, component_size)?;
    // The limb found again from the far end of a skeleton of `first` on `faces`.
    let again = |faces: &Mesh| -> Option<(Vec<u32>, u32)> {
        let axis = skeleton(&Part::new(faces, &first))?.axis;
        let direction = (axis.point(0.9 * axis.length()) - axis.point(0.6 * axis.length())).try_normalize()?;
        let along = |v: u32| mesh.positions[v as usize].dot(direction);
        let end = first.iter().copied().max_by(|&a, &b| along(a).total_cmp(&along(b)).then(b.cmp(&a)))?;
        if end == tip {
            return Some((first.clone(), tip));
        }
        Some((limb(&mesh.positions, graph, triangles, end, length, component_size)?, end))
    };
    let found = again(mesh);
    // Where the mesh's seams are not welded, a skeleton of the limb on the file's triangles may
    // start at a seam's edge (a game character's leg, cut along its seams, gave one from the knee
    // to the thigh, and the limb found again from its end was a slab of the torso). A limb that
    // is not coarse is found again from the end of its skeleton on the welded triangles too,
    // and the one more nearly the limb first found (by shared vertices over all) is kept.
    let Some(welded) = welded.filter(|_| first.len() >= COARSE).and_then(again) else {
        return Some(found.unwrap_or((first, tip)));
    };
    let overlap = |vertices: &[u32]| {
        let common = vertices.iter().filter(|v| first.binary_search(v).is_ok()).count();
        common as f64 / (vertices.len() + first.len() - common) as f64
    };
    match found {
        Some(found) if found.1 == welded.1 || overlap(&found.0) >= overlap(&welded.0) => Some(found),
        _ => Some(welded),
    }
}

/// The coarse limb `vertices` without what lies before its rim's deepest point along its
/// skeleton, where its rim is [`OBLIQUE`]: where a coarse limb's level sets cut it obliquely
/// (an arm's from the shoulder's top down to the armpit), the cap beyond the first complete
/// section is the body's, and no section normal to the limb could hold it. What is kept is the
/// piece the tip's triangles reach, without the vertices of its cut on one of its triangles
/// only. The limb is kept whole where that would cut off its tip `tip` or more than half of
/// its skeleton's length.
fn squared_off(mesh: &Mesh, triangles: &[[u32; 3]], vertices: Vec<u32>, tip: u32) -> Vec<u32> {
    let Some(rim) = Rim::of(mesh, triangles, &vertices) else {
        return vertices;
    };
    if !rim.squares_off() {
        return vertices;
    }
    let (axis, deepest) = (&rim.axis, rim.deepest);
    let position = |v: u32| mesh.positions[v as usize];
    let mut beyond = vec![false; mesh.positions.len()];
    for &v in &vertices {
        beyond[v as usize] = axis.project(position(v)) >= deepest;
    }
    // No vertex left on a triangle of its own (a spike up the oblique rim of a coarse limb).
    let (mut triangles_at, mut on_cut) = (vec![0u8; mesh.positions.len()], vec![false; mesh.positions.len()]);
    for t in triangles {
        let kept = t.iter().all(|&v| beyond[v as usize]);
        for &v in t {
            if kept {
                triangles_at[v as usize] = triangles_at[v as usize].saturating_add(1);
            } else {
                on_cut[v as usize] = true;
            }
        }
    }
    for &v in &vertices {
        beyond[v as usize] &= !on_cut[v as usize] || triangles_at[v as usize] >= 2;
    }
    // The piece of it that the tip's triangles reach.
    let mut pieces = DisjointSets::new(mesh.positions.len());
    for t in triangles.iter().filter(|t| t.iter().all(|&v| beyond[v as usize])) {
        for pair in [[t[0], t[1]], [t[1], t[2]]] {
            let (a, b) = (pieces.root(pair[0]), pieces.root(pair[1]));
            if a != b {
                pieces.attach(a, b);
            }
        }
    }
    let reached = pieces.root(tip);
    let squared: Vec<u32> =
        vertices.iter().copied().filter(|&v| beyond[v as usize] && pieces.root(v) == reached).collect();
    if !beyond[tip as usize] || squared.len() < 4 {
        return vertices;
    }
    squared
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
    limb_through_hands(positions, graph, triangles, tip, length, component_size, true)
}

/// [`limb`], through the hands it passes (see [`wrist_within`]) only where `past_hands`.
fn limb_through_hands(
    positions: &[DVec3],
    graph: &EdgeGraph,
    triangles: &[[u32; 3]],
    tip: u32,
    length: f64,
    component_size: usize,
    past_hands: bool,
) -> Option<Vec<u32>> {
    if !(length > 0.0 && length.is_finite()) {
        return None;
    }
    let limit = REACH * length;
    let d = graph.distances_within(&[tip], limit);
    let h = length / LEVELS_PER_LENGTH;
    let levels = (limit / h).ceil() as usize;
    let perimeter = perimeters(positions, triangles, &d, h, levels, limit);
    let crossing = LevelTriangles::new(triangles, &d, h, perimeter.len());
    let start = (START * LEVELS_PER_LENGTH).ceil() as usize;
    let rate = |k: usize| (perimeter[k] - perimeter[k - WINDOW]) / (WINDOW as f64 * h);
    // Past the tip's own cap (a round end, a hoof's sole), where the level sets grow like
    // circles around a point: the first level where they grow slower than [`CAPPED`].
    let past_cap = (WINDOW..levels).find(|&k| rate(k) < CAPPED).unwrap_or(levels);
    // The first level where the level sets open onto the body, past the hands (see
    // [`wrist_within`]) where `past_hands`.
    let opening = |past_hands: bool| {
        ((start + WINDOW).max(past_cap + WINDOW)..levels).find(|&k| {
            let rate = (perimeter[k] - perimeter[k - WINDOW]) / (WINDOW as f64 * h);
            // A widening that narrows again (a hand's or a foot's below its wrist or ankle) is
            // not the body.
            let after = &perimeter[k..(k + 1 + SUSTAIN).min(levels)];
            // …unless its level set falls apart first and stays apart, never shorter than where the
            // widening began: a crotch seen from a foot, past which the level set runs around the
            // other leg and up the body (their sum below the loop that hugged both on the flat
            // between them, but longer than the leg). A coarse limb's level sets fall apart around
            // whatever lies near (a wing, a braid): there the rule is not applied, and a leg cut
            // past its crotch is trimmed when it is fitted.
            let falls_apart = || {
                d.iter().filter(|&&x| x < (k - WINDOW) as f64 * h).count() >= COARSE
                    && falls_apart_before_falling(after, perimeter[k - WINDOW], |j| {
                        level_loop_counts(crossing.at(k + j), &d, (k + j) as f64 * h).1
                    })
            };
            let sustained = rate > OPENING && after.len() == SUSTAIN + 1 && (keeps(after) || falls_apart());
            sustained
                && !(past_hands
                    && wrist_within(&perimeter[k..], |j| level_loops(crossing.at(k + j), &d, (k + j) as f64 * h) == 1))
        })
    };
    let within = |level: f64| {
        let mut v: Vec<u32> = (0..d.len() as u32).filter(|&v| d[v as usize] < level).collect();
        v.sort_unstable();
        v
    };
    let cut = |k: usize| {
        let level = k as f64 * h;
        (level >= TUBULAR * perimeter[k] / TAU).then(|| within(level))
    };
    let opening_at_palm = opening(false);
    // The limb through its hand where that is still a limb (not the body past its neck).
    if let Some(k) = past_hands.then(|| opening(true)).flatten().filter(|&k| Some(k) != opening_at_palm)
        && let Some(arm) = cut(k - WINDOW)
        && arm.len() as f64 <= MAX_SHARE * component_size as f64
    {
        return Some(arm);
    }
    match opening_at_palm {
        Some(k) => {
            let limb = cut(k - WINDOW)?;
            if limb.len() as f64 <= MAX_SHARE * component_size as f64 {
                return Some(limb);
            }
            // More than a limb's share: the opening lies past where the region beyond the limb
            // falls apart into two long pieces (a coarse crotch seen from a foot: the body above
            // and the other leg below, reached before the level sets open). Cut at that fork.
            let opened = (k - WINDOW) as f64 * h;
            match fork_level(graph, &d, limit, START * length) {
                Some(level) if level >= START * length && level < opened => cut((level / h).floor() as usize),
                _ => Some(limb),
            }
        }
        None => {
            let reached = d.iter().filter(|&&x| x <= limit).count();
            let far = d.iter().copied().filter(|&x| x <= limit).fold(0.0, f64::max);
            let last = ((far / h).floor() as usize).min(levels);
            let whole = reached == component_size && last > 1;
            // A component that is a tube everywhere: no level set's radius over
            // 1/WHOLE_TUBE of its length. One that forks far enough from its far end (a figure
            // of one piece seen from her foot) is cut at the fork.
            let widest = perimeter[1..last].iter().copied().fold(0.0, f64::max) / TAU;
            if !(whole && far >= WHOLE_TUBE * widest) {
                return None;
            }
            let limb = match fork_level(graph, &d, limit, START * length) {
                Some(level) if level >= START * length => cut((level / h).floor() as usize),
                _ => None,
            };
            Some(limb.filter(|limb| limb.len() as f64 <= FORKED_SHARE * component_size as f64).unwrap_or_else(|| within(f64::INFINITY)))
        }
    }
}

/// Whether `perimeters` never fall below [`KEEPS`] times the largest they have been since the
/// first: a widening that holds.
fn keeps(perimeters: &[f64]) -> bool {
    let mut peak: f64 = 0.0;
    perimeters.iter().all(|&p| {
        peak = peak.max(p);
        p >= KEEPS * peak
    })
}

/// Whether the level set past a widening (`after[0]` its perimeter at the widening, `loops(j)`
/// its count of closed loops `j` levels on, so that a hole in a scan, which opens a loop, is
/// no split) falls apart into more loops than it had at the widening and stays apart to the end
/// of `after`, its perimeter kept ([`keeps`]) until it falls apart and never below `began`, the
/// perimeter where the widening began (a bump's level set on a body may fall apart around
/// another part, and fall back below its own).
fn falls_apart_before_falling(after: &[f64], began: f64, loops: impl Fn(usize) -> usize) -> bool {
    if after.iter().any(|&p| p < began) {
        return false;
    }
    let base = loops(0);
    let Some(apart) = (1..after.len()).find(|&j| loops(j) > base) else { return false };
    keeps(&after[..=apart]) && (apart + 1..after.len()).all(|j| loops(j) > base)
}

/// Whether the perimeters `after` a widening (`after[0]` at the widening) fall, within
/// [`HAND`] levels, below [`WRIST`] times the largest they have been since and then hold as a
/// tube's for [`FOREARM`] levels (within [`FOREARM_SPREAD`] of the fallen value), the level set
/// one loop (`one_loop`, by level after the widening) where they fall and where they stop
/// holding: a hand whose palm is longer than [`SUSTAIN`] levels (a cartoon's), past its wrist
/// the forearm. A body's level sets may fall as much past its neck, as one loop where the arms
/// lie nearer the tip (a cartoon bear's, seen from its foot); the limb through such a fall is
/// then more than [`MAX_SHARE`] of its component, and [`limb`] keeps the opening before it.
fn wrist_within(after: &[f64], one_loop: impl Fn(usize) -> bool) -> bool {
    let mut peak: f64 = 0.0;
    for (j, &p) in after.iter().enumerate().take(HAND + 1) {
        peak = peak.max(p);
        if p > 0.0 && p < WRIST * peak {
            let Some(forearm) = after.get(j..=j + FOREARM) else { return false };
            if forearm.iter().all(|&q| (q - p).abs() <= FOREARM_SPREAD * p) && one_loop(j) && one_loop(j + FOREARM) {
                return true;
            }
        }
    }
    false
}

/// The number of loops of the level set d = `level` (the triangles it crosses, joined across
/// the edges it crosses).
fn level_loops(triangles: &[[u32; 3]], d: &[f64], level: f64) -> usize {
    level_loop_counts(triangles, d, level).0
}

/// For each level d_k = k·h, the triangles whose values of d span it (in their order in the
/// mesh): those the level set may cross, so that counting its loops visits the front, not the
/// whole mesh. A triangle with two vertices within reach spans the levels from its least value
/// to its greatest, one more on either side for rounding.
struct LevelTriangles {
    at_level: Vec<Vec<[u32; 3]>>,
}

impl LevelTriangles {
    fn new(triangles: &[[u32; 3]], d: &[f64], h: f64, levels: usize) -> LevelTriangles {
        let mut at_level = vec![Vec::new(); levels];
        for t in triangles {
            let (mut lo, mut hi, mut reached) = (f64::INFINITY, f64::NEG_INFINITY, 0);
            for x in t.iter().map(|&v| d[v as usize]).filter(|x| x.is_finite()) {
                (lo, hi, reached) = (lo.min(x), hi.max(x), reached + 1);
            }
            if reached < 2 {
                continue;
            }
            let first = ((lo / h).floor() as usize).saturating_sub(1);
            let last = ((hi / h).floor() as usize + 2).min(levels);
            for level in &mut at_level[first.min(levels)..last] {
                level.push(*t);
            }
        }
        LevelTriangles { at_level }
    }

    /// The triangles the level set d_k may cross (none past the last level).
    fn at(&self, k: usize) -> &[[u32; 3]] {
        self.at_level.get(k).map_or(&[], Vec::as_slice)
    }
}

/// The number of loops of the level set d = `level` (see [`level_loops`]) and how many of them
/// close: a loop that runs into the mesh's boundary (a hole in a scan) is open.
fn level_loop_counts(triangles: &[[u32; 3]], d: &[f64], level: f64) -> (usize, usize) {
    let crosses = |a: u32, b: u32| {
        let (da, db) = (d[a as usize], d[b as usize]);
        da.is_finite() && db.is_finite() && (da < level) != (db < level)
    };
    let crossing: Vec<usize> =
        (0..triangles.len()).filter(|&i| (0..3).any(|e| crosses(triangles[i][e], triangles[i][(e + 1) % 3]))).collect();
    let mut sets = DisjointSets::new(crossing.len());
    // Per crossed edge, the first triangle met on it and whether a second one was.
    let mut first_at: HashMap<(u32, u32), (u32, bool), BuildHasherDefault<PositionHasher>> = HashMap::default();
    for (local, &i) in crossing.iter().enumerate() {
        let t = triangles[i];
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            if !crosses(a, b) {
                continue;
            }
            match first_at.entry((a.min(b), a.max(b))) {
                Entry::Occupied(mut other) => {
                    let (x, y) = (sets.root(local as u32), sets.root(other.get().0));
                    if x != y {
                        sets.attach(x, y);
                    }
                    other.get_mut().1 = true;
                }
                Entry::Vacant(slot) => {
                    slot.insert((local as u32, false));
                }
            }
        }
    }
    let mut open = vec![false; crossing.len()];
    for &(local, shared) in first_at.values() {
        if !shared {
            open[sets.root(local) as usize] = true;
        }
    }
    let roots: Vec<u32> = (0..crossing.len() as u32).filter(|&i| sets.root(i) == i).collect();
    let closed = roots.iter().filter(|&&r| !open[r as usize]).count();
    (roots.len(), closed)
}

/// The lowest level of `d` (distance from a limb's tip, reached out to `limit`) at which the
/// vertices farther from the tip fall apart into two pieces that each reach at least
/// `significant` beyond it: the saddles of the merge tree of `d`'s superlevel sets whose
/// younger branch persists that long (a crotch seen from a foot: the other leg below it,
/// the body above; a finger beside the one holding the tip is too short to count). A piece
/// that runs past `limit` reaches on without end. `None` where the region never forks.
pub fn fork_level(graph: &EdgeGraph, d: &[f64], limit: f64, significant: f64) -> Option<f64> {
    fork_levels(graph, d, limit, significant).into_iter().reduce(f64::min)
}

/// Every level of `d` at which two pieces of the region farther than it meet that each reach
/// at least `significant` beyond it (see [`fork_level`]), highest first.
pub fn fork_levels(graph: &EdgeGraph, d: &[f64], limit: f64, significant: f64) -> Vec<f64> {
    let mut order: Vec<u32> = (0..d.len() as u32).filter(|&v| d[v as usize] <= limit).collect();
    order.sort_by(|&a, &b| d[b as usize].total_cmp(&d[a as usize]).then(a.cmp(&b)));
    let mut sets = DisjointSets::new(d.len());
    // Per root, the farthest its piece reaches.
    let mut reach = vec![f64::NAN; d.len()];
    let mut forks = Vec::new();
    for &v in &order {
        let runs_on = graph.neighbours(v).iter().any(|&(n, _)| d[n as usize] > limit);
        reach[v as usize] = if runs_on { f64::INFINITY } else { d[v as usize] };
        for &(n, _) in graph.neighbours(v) {
            // Only the neighbours already taken: those farther, or as far and earlier.
            if reach[n as usize].is_nan() {
                continue;
            }
            let (rv, rn) = (sets.root(v), sets.root(n));
            if rv == rn {
                continue;
            }
            let level = d[v as usize];
            if reach[rv as usize] - level >= significant && reach[rn as usize] - level >= significant {
                forks.push(level);
            }
            reach[rv as usize] = reach[rv as usize].max(reach[rn as usize]);
            sets.attach(rn, rv);
        }
    }
    forks
}

/// Where the level set d = `level` crosses triangle `t`, whose corners have the finite
/// distances `g`: the segment between the points where it cuts two of its edges (d linear on
/// each), `None` where it does not cut two.
pub fn level_segment(positions: &[DVec3], t: [u32; 3], g: [f64; 3], level: f64) -> Option<[DVec3; 2]> {
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
    (found == 2).then_some(ends)
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
            if let Some([a, b]) = level_segment(positions, *t, g, k as f64 * h) {
                *sum += a.distance(b);
            }
        }
    }
    perimeter
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::common;
    use crate::fit::body::Body;
    use crate::fit::tests::bent_tube::{elbow_centers, tube_along};
    use crate::fit::protrusions::protrusions;

    /// A blocky arm: a square tube of three rings of four vertices (half-width 0.5) from a
    /// plate, with a cap; the plate's corner `spike`, 3 from the tube's axis, is in the limb
    /// (a coarse figure's shoulder corner, which a level set reached), joined to it by long
    /// triangles to its first ring only, and so is `near`, a corner of the plate beside the
    /// ring. The spike is dropped, the rest kept; with the spike the arm's sections are no
    /// tube's (over 35%), without it they fit at least twice as closely.
    #[test]
    fn a_coarse_limb_drops_a_spike_on_the_body() {
        let mut positions: Vec<DVec3> = Vec::new();
        for z in [0.0, 1.0, 2.0] {
            for (x, y) in [(0.5, 0.5), (-0.5, 0.5), (-0.5, -0.5), (0.5, -0.5)] {
                positions.push(DVec3::new(x, y, z));
            }
        }
        let cap = positions.len() as u32;
        positions.push(DVec3::new(0.0, 0.0, 2.3));
        // The plate around the first ring, at z = 0: `near` beside the ring, `spike` far off,
        // the other corners far off too (the body).
        let near = positions.len() as u32;
        positions.push(DVec3::new(0.9, 0.0, 0.0));
        let spike = positions.len() as u32;
        positions.push(DVec3::new(0.0, 3.0, 0.0));
        let body = positions.len() as u32;
        positions.extend([DVec3::new(-3.0, 0.0, 0.0), DVec3::new(0.0, -3.0, 0.0), DVec3::new(3.0, 0.0, 0.0)]);
        let mut faces = crate::mesh::Faces::new();
        for ring in 0..2u32 {
            for a in 0..4u32 {
                let b = (a + 1) % 4;
                faces.push(&[4 * ring + a, 4 * ring + b, 4 * ring + 4 + b, 4 * ring + 4 + a]);
            }
        }
        for a in 0..4u32 {
            faces.push(&[8 + a, 8 + (a + 1) % 4, cap]);
        }
        // The plate: from the ring's corners (0: +x+y, 1: −x+y, 2: −x−y, 3: +x−y) out to its
        // corners, `near` off the +x side, `spike` off the +y side.
        for t in [
            [0, near, 3],
            [1, spike, 0],
            [2, body, 1],
            [3, body + 1, 2],
            [0, body + 2, near],
            [near, body + 2, 3],
            [1, body, spike],
            [2, body + 1, body],
            [3, body + 2, body + 1],
            [0, spike, body + 2],
        ] {
            faces.push(&t);
        }
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        let triangles: Vec<[u32; 3]> = mesh.faces.triangles().collect();
        let arm: Vec<u32> = (0..=cap).chain([near, spike]).collect();
        let kept = without_spikes(&mesh, &triangles, arm.clone());
        let expected: Vec<u32> = (0..=cap).chain([near]).collect();
        assert_eq!(kept, expected);
        let options = crate::fit::FitOptions::default();
        let with_spike = crate::fit::fit(&mesh, &arm, &options).unwrap().sections_quality().rms_d;
        let without = crate::fit::fit(&mesh, &kept, &options).unwrap().sections_quality().rms_d;
        println!("sections' RMS |d|: {:.1}% with the spike, {:.1}% without", 100.0 * with_spike, 100.0 * without);
        assert!(with_spike > 0.35, "with its spike the arm's sections are no tube's");
        assert!(without < 0.5 * with_spike, "without its spike the arm fits at least twice as closely");
    }

    /// A surface of revolution about z through the profile `(z, r)` (r > 0), its rings about
    /// `spacing` apart along the profile, 24 vertices each, closed by a vertex on the axis at
    /// each end.
    fn revolved(profile: &[(f64, f64)], spacing: impl Fn(f64) -> f64) -> Mesh {
        const AROUND: u32 = 24;
        let mut rings: Vec<(f64, f64)> = vec![profile[0]];
        for pair in profile.windows(2) {
            let ((z0, r0), (z1, r1)) = (pair[0], pair[1]);
            let steps = ((z1 - z0).hypot(r1 - r0) / spacing(z0)).ceil().max(1.0) as usize;
            rings.extend((1..=steps).map(|i| {
                let f = i as f64 / steps as f64;
                (z0 + f * (z1 - z0), r0 + f * (r1 - r0))
            }));
        }
        let mut positions = vec![DVec3::new(0.0, 0.0, rings[0].0 - rings[0].1)];
        for &(z, r) in &rings {
            positions.extend((0..AROUND).map(|a| {
                let angle = std::f64::consts::TAU * a as f64 / AROUND as f64;
                DVec3::new(r * angle.cos(), r * angle.sin(), z)
            }));
        }
        let last = rings.last().unwrap();
        positions.push(DVec3::new(0.0, 0.0, last.0 + last.1));
        let top = positions.len() as u32 - 1;
        let mut faces = crate::mesh::Faces::new();
        let at = |ring: u32, a: u32| 1 + ring * AROUND + a % AROUND;
        for a in 0..AROUND {
            faces.push(&[0, at(0, a + 1), at(0, a)]);
            faces.push(&[at(rings.len() as u32 - 1, a), at(rings.len() as u32 - 1, a + 1), top]);
        }
        for ring in 0..rings.len() as u32 - 1 {
            for a in 0..AROUND {
                faces.push(&[at(ring, a), at(ring, a + 1), at(ring + 1, a + 1), at(ring + 1, a)]);
            }
        }
        Mesh::from_parts(positions, faces, Vec::new()).unwrap()
    }

    /// A cartoon's arm on its body: a ball of radius 6 (z < 0), an arm of radius 0.3 up to
    /// z = 4, a hand of radius 0.9 from 4.5 to 6 (its palm longer than [`SUSTAIN`] levels) and
    /// a finger of radius 0.2 from 6.3 to 7. Seen from the fingertip, the level sets widen at
    /// the palm and hold there for more than [`SUSTAIN`] levels, as they do where a limb meets
    /// the body; but past the palm they fall back to the wrist's and hold as the forearm's. The
    /// limb runs through the hand to the body; cut at the palm, as before the hand was told
    /// from the body, it is the finger alone.
    #[test]
    fn a_limb_is_found_through_a_long_hand() {
        let mut profile: Vec<(f64, f64)> = (0..=16)
            .map(|i| {
                // The ball's lower part, from its bottom pole up to where the arm leaves it.
                let angle = std::f64::consts::PI * (i as f64 / 16.0) * 0.97;
                (-6.0 - 6.0 * angle.cos(), 6.0 * angle.sin())
            })
            .filter(|&(_, r)| r > 0.0)
            .collect();
        profile.extend([(-0.3, 0.6), (0.0, 0.3), (4.0, 0.3), (4.5, 0.9), (6.0, 0.9), (6.3, 0.2), (7.0, 0.2)]);
        // The body's rings closer together than the limb's, so that the limb is a limb's share.
        let mesh = revolved(&profile, |z| if z < 0.0 { 0.05 } else { 0.1 });
        let triangles: Vec<[u32; 3]> = mesh.faces.triangles().collect();
        let graph = EdgeGraph::new(&mesh.positions, &triangles);
        let tip = mesh.positions.len() as u32 - 1;
        let size = mesh.positions.len();
        let (length, z) = (3.0, |v: &u32| mesh.positions[*v as usize].z);
        let through =
            limb_through_hands(&mesh.positions, &graph, &triangles, tip, length, size, true).expect("a limb");
        let at_palm =
            limb_through_hands(&mesh.positions, &graph, &triangles, tip, length, size, false).expect("a limb");
        let lowest = |vertices: &[u32]| vertices.iter().map(z).fold(f64::INFINITY, f64::min);
        eprintln!(
            "through the hand: {} vertices down to z = {:.2}; cut at the palm: {} down to z = {:.2}",
            through.len(),
            lowest(&through),
            at_palm.len(),
            lowest(&at_palm)
        );
        assert!(lowest(&through) < 0.5 && lowest(&through) > -0.5, "the arm down to the body");
        assert!((through.len() as f64) <= MAX_SHARE * size as f64);
        assert_eq!(limb(&mesh.positions, &graph, &triangles, tip, length, size), Some(through));
        assert!(lowest(&at_palm) > 5.5, "cut at the palm, the finger alone");
    }

    /// The faerie's arms (366 vertices: each arm a tube of rings of five or six vertices, its
    /// forearm one span of long triangles): the level set where each arm's opens onto the body
    /// passes between the vertices of its shoulder's ring, so its rim runs down to the elbow.
    /// Squared off as it was found, an arm loses its upper arm and spans less than a quarter of
    /// the body's height; evened first (its shoulder's ring completed), it keeps it, and its
    /// rim is then no more oblique.
    #[test]
    fn a_coarse_arm_evened_keeps_its_upper_arm() {
        let Some(path) = common::shared_mesh("characters/faerie.obj") else { return };
        let mesh = Mesh::load(&path).unwrap();
        let body = Body::new(&mesh);
        let ys = || mesh.positions.iter().map(|p| p.y);
        let (bottom, top) = (ys().fold(f64::INFINITY, f64::min), ys().fold(f64::NEG_INFINITY, f64::max));
        let height = top - bottom;
        // How far a part reaches: the largest distance between two of its vertices.
        let span = |vertices: &[u32]| {
            let at = |v: &u32| mesh.positions[*v as usize];
            vertices.iter().flat_map(|a| vertices.iter().map(move |b| at(a).distance(at(b)))).fold(0.0, f64::max)
        };
        // The arms: the protrusions whose tips, the hands, hang at mid height, to either side.
        let (found, _) = protrusions(&mesh, &body, 0.04 * body.diagonal, 32);
        let arms: Vec<_> = found
            .iter()
            .filter(|p| {
                let tip = mesh.positions[p.tip as usize];
                // The wings spread behind her back (x < −8); she faces +x.
                (tip.y - (bottom + top) / 2.0).abs() < 0.1 * height && tip.z.abs() > 0.1 * height && tip.x > -5.0
            })
            .collect();
        assert_eq!(arms.len(), 2, "{:?}", found.iter().map(|p| p.tip).collect::<Vec<_>>());
        let (graph, triangles, size) = (&body.graph, &body.triangles[..], mesh.positions.len());
        let welded = body.welded_mesh(&mesh);
        for arm in arms {
            let (found_as, tip) = aligned(&mesh, welded.as_ref(), graph, triangles, arm.tip, arm.length, size).unwrap();
            let rim = |vertices: &[u32]| Rim::of(&mesh, triangles, vertices).unwrap();
            assert!(rim(&found_as).squares_off(), "tip {tip}: the rim as found is oblique");
            let squared = squared_off(&mesh, triangles, found_as.clone(), tip);
            let evened = evened(&mesh, graph, triangles, found_as.clone(), tip, arm.length);
            eprintln!(
                "faerie arm at tip {tip}: found {} vertices, squared off {} spanning {:.2}, evened {} spanning {:.2} \
                 (rim spread {:.2} → {:.2} radii) of {height:.2}",
                found_as.len(),
                squared.len(),
                span(&squared),
                evened.len(),
                span(&evened),
                rim(&found_as).spread(),
                rim(&evened).spread()
            );
            assert!(span(&squared) < 0.25 * height, "tip {tip}: squared off as found, the upper arm is lost");
            assert!(evened.len() > found_as.len() && evened.len() <= found_as.len() + found_as.len() / GROWN_SHARE);
            assert!(rim(&evened).spread() <= EVEN && !rim(&evened).squares_off());
            assert_eq!(squared_off(&mesh, triangles, evened.clone(), tip), evened, "tip {tip}: evened, kept whole");
            assert!(span(&evened) >= 0.25 * height, "tip {tip}: the arm spans {} of {height}", span(&evened));
        }
    }

    /// A leg bent at right angles into its foot ([`elbow_centers`]: up the z axis to z = 6, a
    /// quarter turn of radius 2, a foot along +x to x = 8), radius 1, 16 vertices a ring (not
    /// coarse), on a flange of radius 12, capped at the toe. The file's triangles are cut along
    /// a seam: the ring at z = 3 is stored twice, the triangles below on one copy and above on
    /// the other.
    fn seamed_leg() -> Mesh {
        tube_along(&elbow_centers(), 1.0, 16, 12.0, Some(6)).0
    }

    #[test]
    fn a_seamed_limb_is_aligned_by_its_skeleton_on_the_welded_triangles() {
        let mesh = seamed_leg();
        let body = Body::new(&mesh);
        let welded = body.welded_mesh(&mesh).expect("the seam is welded");
        let tip = mesh.positions.len() as u32 - 1;
        let size = mesh.positions.len();
        let (graph, triangles) = (&body.graph, &body.triangles[..]);
        let on_file = aligned_limb(&mesh, None, graph, triangles, tip, 14.0, size).expect("a limb");
        let on_welded = aligned_limb(&mesh, Some(&welded), graph, triangles, tip, 14.0, size).expect("a limb");
        let describe = |(vertices, tip): &(Vec<u32>, u32)| format!("{} vertices, tip at {}", vertices.len(), mesh.positions[*tip as usize]);
        eprintln!("on the file's triangles: {}; on the welded: {}", describe(&on_file), describe(&on_welded));
        // The welded skeleton runs up the leg and along the foot: the toe is the tip already.
        assert_eq!(on_welded.1, tip);
        assert!(on_welded.0.binary_search(&tip).is_ok());
        // The file's is cut at the seam, its end pointing up the shin: the tip moved to the top
        // of the foot's last ring, off the foot's axis (z = 8), as it did before the welded one
        // was tried.
        assert_ne!(on_file.1, tip);
        assert!(mesh.positions[on_file.1 as usize].z > 8.5, "{}", describe(&on_file));
    }

    #[test]
    fn a_widening_whose_level_set_falls_apart_before_it_falls_back_is_the_body() {
        // A crotch seen from a foot: the loop on the flat between the legs grows (0.44 to 1.48),
        // falls apart around the other leg (two loops from level 3 on) and falls back to their
        // sum (1.10), still apart.
        let perimeters = [0.47, 0.86, 1.27, 1.48, 1.40, 1.23, 1.10, 1.10, 1.10];
        let crotch = |j: usize| if j >= 3 { 2 } else { 1 };
        assert!(!keeps(&perimeters), "the old rule: a widening that falls back is no opening");
        assert!(falls_apart_before_falling(&perimeters, 0.44, crotch));
        // A bump's: it falls apart too, but back below where it began.
        assert!(!falls_apart_before_falling(&perimeters, 1.2, crotch));
        // A palm seen from a fingertip: the level set falls apart around the other fingers and
        // is one loop again at the wrist, where it has fallen back.
        let palm = |j: usize| if (3..6).contains(&j) { 4 } else { 1 };
        assert!(!falls_apart_before_falling(&perimeters, 0.44, palm));
        // A hand's widening that falls back as one loop: a wrist.
        assert!(!falls_apart_before_falling(&perimeters, 0.44, |_| 1));
        // One that falls back before it falls apart.
        let late = |j: usize| if j >= 6 { 2 } else { 1 };
        assert!(!falls_apart_before_falling(&perimeters, 0.44, late));
        assert!(keeps(&[0.5, 1.0, 0.9, 0.86]) && !keeps(&[0.5, 1.0, 0.84]));
    }
}
