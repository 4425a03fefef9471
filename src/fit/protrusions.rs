//! Finding a mesh's protrusions (legs, arms, ears, a tail, a spout) for [`super::autorig`]:
//! the branches of the merge tree of the superlevel sets of geodesic distance from the body's
//! center, kept where they are long (their *persistence*). This is the geodesic-distance Reeb
//! graph of Hilaga et al. ("Topology matching for fully automatic similarity estimation of 3D
//! shapes", SIGGRAPH 2001, §3) read as a 0-dimensional persistence diagram (Edelsbrunner,
//! Letscher & Zomorodian, "Topological persistence and simplification", 2002, §3): each tip
//! (a local maximum of the distance) starts a branch, which ends where its superlevel set
//! meets the set of a farther tip; its persistence is the drop in distance between the two.
//!
//! 1. **Connectivity.** The search runs on the mesh's [`Body`]: vertices within a small reach
//!    welded (unwelded patch seams, as in the Newell teapot; a game mesh's open seams), small
//!    components joined to those they touch (a blocky limb's box, a tuft on a tail); then the
//!    body splits into its connected components; each is searched alone.
//! 2. **Distance.** g = edge-path geodesic distance ([`EdgeGraph::distances`]) from the
//!    component's vertex nearest its centroid, a center inside the body for a star-shaped
//!    body.
//! 3. **Merge tree.** Vertices in decreasing g join the components of their neighbours
//!    already added (union-find); where two meet, the one with the lower tip ends there at
//!    level g(v), with persistence g(tip) − g(v). The farthest tip's branch never ends: it
//!    is closed at the highest level where a kept branch ends in it, and also at each next
//!    level down (of at most [`ELDEST_ENDS`]) where the limb found there holds at least
//!    [`ELDEST_GROWTH`] times the vertices of the last one kept (the dino's farthest toe meets
//!    its other toe first, then its leg the body; an ogre's farthest fingertip meets four
//!    fingers before its arm meets the body).
//! 4. **Parts.** Branches with persistence at least `min_length` are kept, the longest first,
//!    at most `max_parts`; each part is its tip's limb ([`super::limb`]): the vertices nearer
//!    the tip than where the level sets of distance from it open onto the body, the tip moved
//!    to the limb's end along its skeleton so the cut is normal to the limb. A branch whose
//!    level sets never open (a bump, the body's far side) gives no part; a part holding more than a
//!    quarter of its component's vertices and of its area, unless it is the whole component (a
//!    spout that is a mesh component of its own), is the body's far side and is dropped. By
//!    area as well: a figure's head is often modelled far more densely than its body (the
//!    dino's head and neck hold 29% of its vertices and 17% of its surface, the blocky man's
//!    head 52% and 9%); and one modelled at least twice as densely as its component is kept up
//!    to half its area ([`far_side`]: a game figure's head, 63% of its vertices on 29% of its
//!    area).
//!
//! 5. **Mirror twins.** Where the searched vertices have a mirror plane ([`super::mirror`]; or
//!    a near one where they have none, [`super::mirror::near_mirror_map`]: a model made
//!    lopsided), a part that shares most of its vertices with another part's mirror image takes
//!    that image's vertices too ([`made_alike`]): the limb search from two mirror tips, whose
//!    persistences differ, may keep a ring's vertex in one limb and not in the other.
//!
//! Everything depends on edge lengths, connectivity, the order of distances (ties broken by
//! vertex index) and the vertices' own principal axes, so a rigidly moved mesh gives the same
//! parts.

use std::collections::HashMap;

use glam::DVec3;

use super::body::Body;
use super::geodesic::EdgeGraph;
use super::limb::{MAX_SHARE, aligned_limb};
use super::mirror::{Mirror, NO_TWIN, mirror_map, near_mirror_map};
use crate::mesh::Mesh;
use crate::parallel::prelude::*;

/// A protrusion: a tip and the vertices of its branch.
#[derive(Clone, Debug, PartialEq)]
pub struct Protrusion {
    /// The mesh vertices of the part, increasing, a vertex welded for the search
    /// ([`Body::weld`]) with every vertex welded to it; it may overlap a longer part.
    pub vertices: Vec<u32>,
    /// The tip: the part's vertex farthest from the body's center.
    pub tip: u32,
    /// The persistence: the drop in geodesic distance from the tip to where the part meets
    /// the body, mesh units (for a joined piece, the reach of its axis).
    pub length: f64,
    /// For a piece joined to the body at one end ([`Body::leaves`]): its axis, from the end
    /// where it touches the body to its tip, as the fit's first guess.
    pub axis: Option<Vec<DVec3>>,
}

/// A branch of the merge tree.
#[derive(Clone, Copy, Debug)]
struct Branch {
    tip: u32,
    /// The level where it ended.
    end: f64,
    /// The tip of the branch it ended in.
    into: u32,
}

/// The protrusions of `mesh` (see the module docs), longest first: those found
/// ([`found_protrusions`]), mirror twins made alike where the searched vertices have a mirror
/// plane ([`made_alike`]), each welded vertex standing for every vertex welded to it; and
/// that plane, if any.
pub fn protrusions(mesh: &Mesh, body: &Body, min_length: f64, max_parts: usize) -> (Vec<Protrusion>, Option<Mirror>) {
    // The search and the mirror plane, which does not depend on it, side by side; a near one
    // where the mesh has none.
    let (mut found, mirror) = crate::parallel::join(
        || found_protrusions(mesh, body, min_length, max_parts),
        || {
            let searched = searched_vertices(mesh, body);
            mirror_map(&mesh.positions, &searched).or_else(|| near_mirror_map(&mesh.positions, &searched))
        },
    );
    if let Some(mirror) = &mirror {
        made_alike(&mut found, &mirror.map);
    }
    for part in &mut found {
        part.vertices = body.unwelded(&part.vertices);
    }
    (found, mirror)
}

/// The vertices the search runs on: the welded representatives on the body's triangles,
/// increasing.
pub fn searched_vertices(mesh: &Mesh, body: &Body) -> Vec<u32> {
    let mut used = vec![false; mesh.positions.len()];
    for &v in body.triangles.iter().flatten() {
        used[v as usize] = true;
    }
    (0..mesh.positions.len() as u32).filter(|&v| used[v as usize]).collect()
}

/// The protrusions found by the search (see the module docs), longest first, as the welded
/// vertices of the search (welded representatives).
pub fn found_protrusions(mesh: &Mesh, body: &Body, min_length: f64, max_parts: usize) -> Vec<Protrusion> {
    let (graph, triangles) = (&body.graph, &body.triangles[..]);
    let welded = body.welded_mesh(mesh);
    // Each searched vertex's component size (0: not yet searched).
    let mut sizes = vec![0; mesh.positions.len()];
    let mut found: Vec<Protrusion> = Vec::new();
    for start in searched_vertices(mesh, body) {
        if sizes[start as usize] > 0 {
            continue;
        }
        let component = flood(graph, start, |_| true);
        for &v in &component {
            sizes[v as usize] = component.len();
        }
        found.extend(component_protrusions(mesh, welded.as_ref(), graph, triangles, &component, min_length));
    }
    longest_first(&mut found);
    // Pieces joined at one end come first: their ends are known.
    let mut pieces = joined_pieces(mesh, body, min_length, &sizes);
    pieces.append(&mut found);
    let mut found = pieces;
    // Two branches whose limbs were found again from the same aligned tip are one part.
    let mut seen = std::collections::HashSet::new();
    found.retain(|part| seen.insert(part.vertices.clone()));
    found.truncate(max_parts);
    found
}

/// Mirror twins made alike (see [`super::mirror`]): each part whose mirror image (by `map`, a
/// vertex's twin) shares at least [`TWIN_OVERLAP`] of the vertices of both with another part,
/// the most of all, takes that image's vertices too, so that both are the union of one and the
/// other's image, mirror images of each other.
pub fn made_alike(found: &mut [Protrusion], map: &[u32]) {
    let images: Vec<Vec<u32>> = found
        .iter()
        .map(|part| {
            let mut image: Vec<u32> =
                part.vertices.iter().map(|&v| map[v as usize]).filter(|&w| w != NO_TWIN).collect();
            image.sort_unstable();
            image.dedup();
            image
        })
        .collect();
    // The share of the vertices of both (both increasing) that they share: merged in one pass,
    // and not at all where their sizes alone rule out a twin.
    let overlap = |a: &[u32], b: &[u32]| {
        if (a.len().min(b.len()) as f64) < TWIN_OVERLAP * a.len().max(b.len()) as f64 {
            return 0.0;
        }
        let (mut i, mut j, mut common) = (0, 0, 0);
        while i < a.len() && j < b.len() {
            match a[i].cmp(&b[j]) {
                std::cmp::Ordering::Less => i += 1,
                std::cmp::Ordering::Greater => j += 1,
                std::cmp::Ordering::Equal => (i, j, common) = (i + 1, j + 1, common + 1),
            }
        }
        common as f64 / (a.len() + b.len() - common).max(1) as f64
    };
    let twins: Vec<Option<usize>> = (0..found.len())
        .map(|i| {
            (0..found.len())
                .filter(|&j| j != i)
                .map(|j| (j, overlap(&found[i].vertices, &images[j])))
                .filter(|&(_, shared)| shared >= TWIN_OVERLAP)
                .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
                .map(|(j, _)| j)
        })
        .collect();
    for (i, twin) in twins.into_iter().enumerate() {
        let Some(j) = twin else { continue };
        let part = &mut found[i].vertices;
        part.extend(&images[j]);
        part.sort_unstable();
        part.dedup();
    }
}

/// See [`made_alike`]: a part and another's mirror image are twins where they share at least
/// this share of the vertices of both (wuson's hind legs share 116 of 117).
pub const TWIN_OVERLAP: f64 = 0.8;

/// Sorts `found` longest first; lengths within rounding of each other (mirror twins, such as a
/// pair of legs, whose lengths a rigid motion perturbs in the last bits) by tip index, so that
/// a moved mesh names its parts alike.
fn longest_first(found: &mut [Protrusion]) {
    let quantum = 1e-9 * found.iter().map(|p| p.length).fold(0.0, f64::max);
    let rounded = |p: &Protrusion| if quantum > 0.0 { (p.length / quantum).round() as i64 } else { 0 };
    found.sort_by(|a, b| rounded(b).cmp(&rounded(a)).then(a.tip.cmp(&b.tip)));
}

/// The body's pieces joined to it at one end ([`Body::leaves`]) that are limbs: elongated
/// (their extent along their principal axis at least [`ELONGATED`] times across it), at
/// least `min_length` long and at most [`MAX_SHARE`] of their joined component (whose size
/// at each searched vertex is `sizes`). Each runs along its principal axis from the end nearer where
/// it touches to its tip.
fn joined_pieces(mesh: &Mesh, body: &Body, min_length: f64, sizes: &[usize]) -> Vec<Protrusion> {
    let mut found = Vec::new();
    for leaf in &body.leaves {
        let points: Vec<DVec3> = leaf.vertices.iter().map(|&v| mesh.positions[v as usize]).collect();
        if points.len() < 4 || leaf.touching.is_empty() {
            continue;
        }
        let (centroid, axis) = super::axis::principal_axis(&points);
        let along = |p: DVec3| (p - centroid).dot(axis);
        let (lo, hi) = points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(along(p)), hi.max(along(p)))
        });
        let across = points.iter().map(|&p| (p - centroid - axis * along(p)).length()).fold(0.0, f64::max);
        let share = leaf.vertices.len() as f64 / sizes[leaf.vertices[0] as usize].max(1) as f64;
        if hi - lo < min_length || hi - lo < ELONGATED * 2.0 * across || share > MAX_SHARE {
            continue;
        }
        let touch = leaf.touching.iter().map(|&v| mesh.positions[v as usize]).sum::<DVec3>()
            / leaf.touching.len() as f64;
        let (start, end) = if along(touch) <= (lo + hi) / 2.0 { (lo, hi) } else { (hi, lo) };
        let tip = leaf.vertices.iter().copied().max_by(|&a, &b| {
            let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
            ((along(pa) - start).abs()).total_cmp(&(along(pb) - start).abs()).then(b.cmp(&a))
        });
        let Some(tip) = tip else { continue };
        found.push(Protrusion {
            vertices: leaf.vertices.clone(),
            tip,
            length: hi - lo,
            axis: Some(vec![centroid + axis * start, centroid + axis * end]),
        });
    }
    longest_first(&mut found);
    found
}

/// A joined piece is a limb when it is at least this many times as long as it is wide.
const ELONGATED: f64 = 2.5;

/// The vertices reachable from `start` through vertices that `keep` accepts, increasing.
pub(super) fn flood(graph: &EdgeGraph, start: u32, keep: impl Fn(u32) -> bool) -> Vec<u32> {
    let mut reached = vec![start];
    let mut visited = std::collections::HashSet::from([start]);
    let mut i = 0;
    while i < reached.len() {
        for &(n, _) in graph.neighbours(reached[i]) {
            if keep(n) && visited.insert(n) {
                reached.push(n);
            }
        }
        i += 1;
    }
    reached.sort_unstable();
    reached
}

/// The protrusions of one component (its vertices increasing).
fn component_protrusions(
    mesh: &Mesh,
    welded: Option<&Mesh>,
    graph: &EdgeGraph,
    triangles: &[[u32; 3]],
    component: &[u32],
    min_length: f64,
) -> Vec<Protrusion> {
    if component.len() < 16 {
        return Vec::new();
    }
    let centroid = component.iter().map(|&v| mesh.positions[v as usize]).sum::<DVec3>() / component.len() as f64;
    let center = component
        .iter()
        .copied()
        .min_by(|&a, &b| {
            let (da, db) =
                (mesh.positions[a as usize].distance(centroid), mesh.positions[b as usize].distance(centroid));
            da.total_cmp(&db).then(a.cmp(&b))
        })
        .unwrap_or(component[0]);
    let g = graph.distances(&[center]);
    let (branches, eldest) = merge_tree(graph, component, &g);
    let kept: Vec<(u32, f64)> =
        branches.iter().filter(|b| g[b.tip as usize] - b.end >= min_length).map(|b| (b.tip, b.end)).collect();
    let limb_of = |(tip, end): (u32, f64)| {
        let length = g[tip as usize] - end;
        let (vertices, tip) = aligned_limb(mesh, welded, graph, triangles, tip, length, component.len())?;
        Some(Protrusion { vertices, tip, length, axis: None })
    };
    // The eldest branch ends at the highest level where a kept branch ends in it; and at the
    // next such level down (of at most [`ELDEST_ENDS`]) where it reaches on as a limb of at
    // least [`ELDEST_GROWTH`] times the vertices: a leg whose farthest toe meets its other toe
    // first, an arm whose farthest finger meets the hand's other fingers one by one.
    let mut ends: Vec<f64> = branches
        .iter()
        .filter(|b| b.into == eldest && g[b.tip as usize] - b.end >= min_length)
        .map(|b| b.end)
        .collect();
    ends.sort_by(|a, b| b.total_cmp(a));
    ends.dedup();
    let ends: Vec<f64> = ends.into_iter().filter(|&end| g[eldest as usize] - end >= min_length).collect();
    // Each branch's limb on its own, the branches in parallel, kept in their order, and beside
    // them the eldest branch's limbs, which are tried one end after the other.
    let (mut found, eldest_found): (Vec<Protrusion>, Vec<Protrusion>) = crate::parallel::join(
        || kept.par_iter().filter_map(|&branch| limb_of(branch)).collect(),
        || eldest_limbs(&ends, |end| limb_of((eldest, end)), component.len()),
    );
    found.extend(eldest_found);
    // The component's area, measured only where a part holds more than its share of the
    // vertices.
    let mut component_area = None;
    found.retain(|p| {
        let vertex_share = p.vertices.len() as f64 / component.len() as f64;
        if vertex_share <= MAX_SHARE || p.vertices.len() == component.len() {
            return true;
        }
        let whole = *component_area.get_or_insert_with(|| area_within(mesh, triangles, component));
        !far_side(vertex_share, area_within(mesh, triangles, &p.vertices) / whole)
    });
    found
}

/// A part modelled at least this many times as densely as its component (its share of the
/// component's vertices over its share of the area) is detail its modeller added, not the
/// body's far side ([`far_side`]).
pub const DENSER: f64 = 2.0;

/// Whether a part holding `vertex_share` of its component's vertices and `area_share` of its
/// area is the body's far side: more than [`MAX_SHARE`] of both, unless it is modelled at least
/// [`DENSER`] times as densely and holds at most twice [`MAX_SHARE`] of the area. The far side of
/// a body is more of the body, modelled as it is (spot's head with its neck and shoulders: 41%
/// of the vertices on 36% of the area; the chair's back: 31% on 33%; the McGuire teapot's body:
/// 38% on 46%); a game figure's head is often modelled far more densely (a 3,273-vertex
/// figure's head with its neck: 63% on 29%).
fn far_side(vertex_share: f64, area_share: f64) -> bool {
    let detailed = vertex_share >= DENSER * area_share && area_share <= 2.0 * MAX_SHARE;
    vertex_share > MAX_SHARE && area_share > MAX_SHARE && !detailed
}

/// The area of the triangles of `triangles` whose three vertices are all in `vertices`
/// (increasing).
pub fn area_within(mesh: &Mesh, triangles: &[[u32; 3]], vertices: &[u32]) -> f64 {
    triangles
        .iter()
        .filter(|t| t.iter().all(|v| vertices.binary_search(v).is_ok()))
        .map(|t| {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            0.5 * (b - a).cross(c - a).length()
        })
        .sum()
}

/// See `component_protrusions`: the eldest branch reaching on to the next level where a
/// branch ends in it is a limb of its own where it holds this many times the vertices.
pub const ELDEST_GROWTH: f64 = 2.0;

/// See `component_protrusions`: the eldest branch is tried to at most this many levels where
/// a branch ends in it (an ogre's farthest fingertip meets the hand's four other fingers
/// before its arm meets the body).
pub const ELDEST_ENDS: usize = 6;

/// The limbs of the eldest branch closed at `ends` (levels, highest first), `limb_at` the limb
/// closed at each: the first, and the next (of at most [`ELDEST_ENDS`] levels) that holds at
/// least [`ELDEST_GROWTH`] times its vertices, where the first holds at most [`MAX_SHARE`] of
/// the `component_size` vertices (past that, the body's far side, the search stops).
fn eldest_limbs(
    ends: &[f64],
    limb_at: impl Fn(f64) -> Option<Protrusion>,
    component_size: usize,
) -> Vec<Protrusion> {
    let mut kept: Vec<Protrusion> = Vec::new();
    for &end in ends.iter().take(ELDEST_ENDS) {
        let Some(limb) = limb_at(end) else { continue };
        let count = limb.vertices.len();
        if kept.last().is_some_and(|last| (count as f64) < ELDEST_GROWTH * last.vertices.len() as f64) {
            continue;
        }
        kept.push(limb);
        if kept.len() == 2 || count as f64 > MAX_SHARE * component_size as f64 {
            break;
        }
    }
    kept
}

/// The branches of the merge tree of superlevel sets of `g` over `component` and the
/// eldest tip (the farthest vertex).
fn merge_tree(graph: &EdgeGraph, component: &[u32], g: &[f64]) -> (Vec<Branch>, u32) {
    let mut order = component.to_vec();
    order.sort_by(|&a, &b| g[b as usize].total_cmp(&g[a as usize]).then(a.cmp(&b)));
    let mut parent: HashMap<u32, u32> = HashMap::with_capacity(order.len());
    let mut peak: HashMap<u32, u32> = HashMap::new();
    fn root(parent: &mut HashMap<u32, u32>, mut v: u32) -> u32 {
        while let Some(&p) = parent.get(&v) {
            if p == v {
                break;
            }
            let grand = parent[&p];
            parent.insert(v, grand);
            v = p;
        }
        v
    }
    let mut branches = Vec::new();
    for &v in &order {
        parent.insert(v, v);
        peak.insert(v, v);
        for &(n, _) in graph.neighbours(v) {
            if !parent.contains_key(&n) {
                continue;
            }
            let (rv, rn) = (root(&mut parent, v), root(&mut parent, n));
            if rv == rn {
                continue;
            }
            let (pv, pn) = (peak[&rv], peak[&rn]);
            let elder_first =
                |a: u32, b: u32| g[a as usize] > g[b as usize] || (g[a as usize] == g[b as usize] && a < b);
            let (elder, younger, elder_root, younger_root) =
                if elder_first(pv, pn) { (pv, pn, rv, rn) } else { (pn, pv, rn, rv) };
            if younger != v {
                branches.push(Branch { tip: younger, end: g[v as usize], into: elder });
            }
            parent.insert(younger_root, elder_root);
            peak.insert(elder_root, elder);
        }
    }
    (branches, order[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(vertices: &[u32]) -> Protrusion {
        Protrusion { vertices: vertices.to_vec(), tip: vertices[0], length: 1.0, axis: None }
    }

    /// Vertices 0–9 mirror 10–19 (v ↔ v + 10), 20–29 lie on the plane (each its own twin).
    fn map() -> Vec<u32> {
        (0..30u32).map(|v| if v < 10 { v + 10 } else if v < 20 { v - 10 } else { v }).collect()
    }

    #[test]
    fn a_part_takes_its_twins_image_and_each_becomes_the_others_image() {
        // The left leg 0–8, its twin 10–19 holds the image of vertex 9 too.
        let mut found = vec![part(&[0, 1, 2, 3, 4, 5, 6, 7, 8]), part(&(10..20).collect::<Vec<_>>())];
        made_alike(&mut found, &map());
        assert_eq!(found[0].vertices, (0..10).collect::<Vec<u32>>());
        assert_eq!(found[1].vertices, (10..20).collect::<Vec<u32>>());
    }

    #[test]
    fn parts_that_are_no_ones_image_are_left_as_they_are() {
        // A tail on the plane (its own image: no twin of another part), and a part whose image
        // shares under 80% with the other.
        let tail: Vec<u32> = (20..30).collect();
        let mut found = vec![part(&tail), part(&[0, 1, 2, 3, 4, 5, 6]), part(&[10, 11, 12, 13, 14, 15, 16, 17, 18, 19])];
        made_alike(&mut found, &map());
        assert_eq!(found[0].vertices, tail);
        assert_eq!(found[1].vertices, vec![0, 1, 2, 3, 4, 5, 6], "7 of 10 shared: no twin");
        assert_eq!(found[2].vertices, (10..20).collect::<Vec<u32>>());
    }

    /// The far side of a body is modelled as the body is; a head modelled more densely is not
    /// it. The shares are the parts measured on spot, the chair, the McGuire teapot and a game
    /// figure (`CesiumMan`), and a limb's.
    #[test]
    fn a_part_modelled_far_more_densely_than_its_body_is_no_far_side() {
        assert!(far_side(0.41, 0.357), "spot's head with its neck and shoulders");
        assert!(far_side(0.31, 0.325), "the chair's back");
        assert!(far_side(0.378, 0.456), "the McGuire teapot's body");
        assert!(!far_side(0.63, 0.288), "a game figure's head and neck, modelled 2.2 times as densely");
        assert!(!far_side(0.2, 0.3), "a limb's share of the vertices");
        assert!(!far_side(0.3, 0.2), "and of the area");
        // Densely modelled but most of the surface: the body itself.
        assert!(far_side(0.9, 0.6));
        // The rule before: more than a quarter of both.
        let quarter = |vertices: f64, area: f64| vertices > MAX_SHARE && area > MAX_SHARE;
        assert!(quarter(0.63, 0.288), "which dropped the head");
    }

    /// A limb of `count` vertices.
    fn limb_of(count: usize) -> Protrusion {
        Protrusion { vertices: (0..count as u32).collect(), tip: 0, length: count as f64, axis: None }
    }

    /// The eldest branch is an ogre's farthest fingertip: the hand's four other fingers meet it
    /// at four levels, each closing it to the finger (about 400 vertices), before its arm meets
    /// the body (about 3,900). Closed at its first two levels only (as it was), it is a finger
    /// twice and the arm is never found; tried further, the arm is found at the fifth level,
    /// and no level below it is tried.
    #[test]
    fn the_eldest_branch_reaches_its_arm_past_the_hands_other_fingers() {
        let ends = [9.0, 8.9, 8.8, 8.7, 3.0, 1.0];
        let sizes = |end: f64| match end {
            e if e > 8.75 => Some(limb_of(400)),
            e if e > 8.0 => Some(limb_of(410)),
            e if e > 2.0 => Some(limb_of(3900)),
            _ => Some(limb_of(30000)),
        };
        let counts = |ends: &[f64]| -> Vec<usize> {
            eldest_limbs(ends, sizes, 62000).iter().map(|limb| limb.vertices.len()).collect()
        };
        assert_eq!(counts(&ends[..2]), vec![400], "closed at two levels: a finger alone");
        assert_eq!(counts(&ends), vec![400, 3900], "the finger and its arm, and no level further");
        // Past a limb's share, the search stops: the body's far side is the last one tried.
        let calls = std::cell::Cell::new(0);
        let counted = |end: f64| {
            calls.set(calls.get() + 1);
            if end > 5.0 { Some(limb_of(16000)) } else { Some(limb_of(40000)) }
        };
        assert_eq!(eldest_limbs(&ends, counted, 62000).len(), 1);
        assert_eq!(calls.get(), 1);
        // A level whose limb is refused (a bump) is passed over.
        let bumps = |end: f64| (end < 8.0).then(|| limb_of(3900));
        assert_eq!(eldest_limbs(&ends, bumps, 62000).len(), 1);
    }
}
