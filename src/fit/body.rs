//! The body [`super::autorig`] searches, as one surface even where the file is not: game meshes
//! ship characters as several components (a head sitting on a neck, boxes for limbs) with
//! seams left open where their texture coordinates part.
//!
//! 1. **Welding.** Vertices within [`WELD`] × the bounding-box diagonal of each other are one
//!    vertex of the search (each joins the lowest-indexed vertex within reach that joined none,
//!    in vertex order), so open seams close; the mesh keeps its own vertices.
//! 2. **Contacts.** Edge-connected components of the welded mesh whose surfaces come within
//!    [`CONTACT`] × the diagonal of each other touch: each vertex that near another component's
//!    triangle is bridged to that triangle's nearest corner by an edge of the search graph.
//! 3. **One body.** A component joins another only as a piece of it: it has fewer than
//!    [`SMALL_COMPONENT`] vertices or at most [`SMALL_SHARE`] of the other's (a lid on its pot
//!    is a body of its own), and it touches with at most [`MAX_TOUCHING`] of its vertices (a
//!    hollow wall's two sides lie along each other). Contacts are taken by the larger
//!    component's surface area, largest first, then closest first, and only between
//!    components not yet joined (Kruskal's spanning tree over the contact graph), so a piece
//!    hangs from the largest component it touches (an arm from its torso, not from the leg
//!    its hand passes) and joining never closes a loop that the mesh itself does not have.
//!    A piece joined to one larger component only is a *leaf*: a blocky limb's box on its
//!    torso.
//!
//! Everything depends on distances and vertex order only, so a rigidly moved mesh gives the
//! same body (up to rounding at the reach itself).

use std::collections::{HashMap, HashSet};
use std::hash::BuildHasherDefault;

use glam::DVec3;

use super::disjoint_sets::DisjointSets;
use super::geodesic::EdgeGraph;
use super::nearest_triangle::NearestTriangle;
use crate::mesh::weld::PositionHasher;
use crate::mesh::{Faces, Mesh, bounds_of};
use crate::parallel::prelude::*;

/// Vertices nearer each other than this fraction of the bounding-box diagonal are welded.
pub const WELD: f64 = 1e-5;
/// Components nearer each other than this fraction of the bounding-box diagonal touch.
pub const CONTACT: f64 = 0.015;

/// A component with fewer vertices than this (a box of a blocky limb) joins any it touches…
pub const SMALL_COMPONENT: usize = 16;
/// …as does one with at most this share of the other's vertices (a hand on a body).
pub const SMALL_SHARE: f64 = 0.125;
/// A component touches another with at most this share of its vertices.
pub const MAX_TOUCHING: f64 = 0.5;

/// The hasher of the body's tables (weld cells, edges, components and their pairs): the fast
/// one the mesh's positions are hashed with, not the standard keyed one. Nothing is read from
/// the tables in the order they are stored (each is looked up, or sorted before use), so the
/// body is the same with either; the public 62k-vertex ogre's (44 components) is found in 0.79
/// of the time.
type FastHasher = BuildHasherDefault<PositionHasher>;

/// A table of the body's ([`FastHasher`]).
type Table<K, V> = HashMap<K, V, FastHasher>;

/// The searched body of a mesh (see the module docs). Indices are the mesh's; a welded vertex
/// stands for every vertex joined to it.
#[derive(Clone, Debug)]
pub struct Body {
    /// For each mesh vertex, the vertex it is welded to (itself for a representative).
    pub weld: Vec<u32>,
    /// The mesh's fan triangles on welded vertices, those that welding collapsed left out.
    pub triangles: Vec<[u32; 3]>,
    /// The edges added between touching components, each once, in the order they were found.
    pub bridges: Vec<[u32; 2]>,
    /// The joined components that hang from exactly one larger one (by surface area), with
    /// their vertices that touch it (a box of a blocky limb on its torso; smaller pieces may
    /// hang from it in turn).
    pub leaves: Vec<Leaf>,
    /// The edges of `triangles` and the bridges.
    pub graph: EdgeGraph,
    /// The mesh's bounding-box diagonal.
    pub diagonal: f64,
}

impl Body {
    /// The body of `mesh`.
    pub fn new(mesh: &Mesh) -> Body {
        let diagonal = mesh.diagonal();
        let weld = weld_within(&mesh.positions, WELD * diagonal);
        // Membranes are the file's own: welding may make edges of a seam's twins non-manifold.
        let triangles: Vec<[u32; 3]> = without_membranes(mesh.faces.triangles().collect())
            .into_iter()
            .map(|t| t.map(|v| weld[v as usize]))
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect();
        let (bridges, leaves) = bridges(&mesh.positions, &triangles, CONTACT * diagonal);
        let graph = EdgeGraph::with_bridges(&mesh.positions, &triangles, &bridges);
        Body { weld, triangles, bridges, leaves, graph, diagonal }
    }

    /// The mesh as the body sees it: its triangles on welded vertices (those that welding
    /// collapsed dropped) without membranes, its positions kept and its groups not (fitting
    /// reads none); `None` when welding joined nothing and no membrane was dropped.
    pub fn welded_mesh(&self, mesh: &Mesh) -> Option<Mesh> {
        let welded = self.weld.iter().enumerate().any(|(v, &w)| w as usize != v);
        if !welded && self.triangles.len() == mesh.faces.triangles().count() {
            return None;
        }
        let mut faces = Faces::new();
        for t in &self.triangles {
            faces.push(t);
        }
        Mesh::from_parts(mesh.positions.clone(), faces, Vec::new()).ok()
    }

    /// `vertices` (welded representatives) with every mesh vertex welded to them, increasing.
    pub fn unwelded(&self, vertices: &[u32]) -> Vec<u32> {
        let mut chosen = vec![false; self.weld.len()];
        for &v in vertices {
            chosen[v as usize] = true;
        }
        (0..self.weld.len() as u32).filter(|&v| chosen[self.weld[v as usize] as usize]).collect()
    }
}

/// `triangles` without membranes: triangles whose corners all lie on non-manifold edges (edges
/// of three or more triangles) and that have such an edge. A game mesh may close a limb with a
/// cap and glue the next piece onto the cap's ring (the faerie's forearms are capped at the
/// wrist, the hands glued on): the cap is a wall inside the surface, which would cut every
/// level set and section across the wrist.
fn without_membranes(triangles: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
    let edge = |a: u32, b: u32| (a.min(b), a.max(b));
    let edges_of = |t: &[u32; 3]| [edge(t[0], t[1]), edge(t[1], t[2]), edge(t[2], t[0])];
    let mut uses: Table<(u32, u32), u32> =
        Table::with_capacity_and_hasher(3 * triangles.len() / 2, Default::default());
    for t in &triangles {
        for e in edges_of(t) {
            *uses.entry(e).or_default() += 1;
        }
    }
    let non_manifold: HashSet<u32, FastHasher> =
        uses.iter().filter(|&(_, &n)| n > 2).flat_map(|(&(a, b), _)| [a, b]).collect();
    if non_manifold.is_empty() {
        return triangles;
    }
    triangles
        .into_iter()
        .filter(|t| {
            let on_ring = t.iter().all(|v| non_manifold.contains(v));
            !(on_ring && edges_of(t).iter().any(|e| uses[e] > 2))
        })
        .collect()
}

/// For each position, the lowest-indexed earlier representative within `reach` (itself when
/// none): a grid of cells `reach` wide finds the candidates.
fn weld_within(positions: &[DVec3], reach: f64) -> Vec<u32> {
    if !(reach > 0.0 && reach.is_finite()) {
        return crate::mesh::weld::weld(positions);
    }
    let cell = |p: DVec3| (p / reach).floor().as_i64vec3().to_array();
    let mut grid: Table<[i64; 3], Vec<u32>> = Table::default();
    let mut weld = Vec::with_capacity(positions.len());
    for (v, &p) in positions.iter().enumerate() {
        let c = cell(p);
        let mut best: Option<u32> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else { continue };
                    for &r in list {
                        if positions[r as usize].distance(p) <= reach && best.is_none_or(|b| r < b) {
                            best = Some(r);
                        }
                    }
                }
            }
        }
        match best {
            Some(r) => weld.push(r),
            None => {
                weld.push(v as u32);
                grid.entry(c).or_default().push(v as u32);
            }
        }
    }
    weld
}

/// A component joined to exactly one larger one (see [`Body::leaves`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Leaf {
    /// Its vertices (welded representatives), increasing.
    pub vertices: Vec<u32>,
    /// Its vertices that touch the other component, increasing.
    pub touching: Vec<u32>,
}

/// A contact between two components: a vertex of one and the nearest corner of the other's
/// triangle it lies within reach of, and the distance to that triangle.
#[derive(Clone, Copy, Debug)]
struct Contact {
    gap: f64,
    components: [u32; 2],
    edge: [u32; 2],
}

/// The bridges between the components of `triangles` within `reach` of each other, joined as a
/// spanning tree (see the module docs), and the joined components that hang from exactly one
/// larger one ([`Body::leaves`]).
fn bridges(positions: &[DVec3], triangles: &[[u32; 3]], reach: f64) -> (Vec<[u32; 2]>, Vec<Leaf>) {
    let mut sets = DisjointSets::new(positions.len());
    for t in triangles {
        for k in 1..3 {
            let (a, b) = (sets.root(t[0]), sets.root(t[k]));
            if a != b {
                sets.attach(b, a);
            }
        }
    }
    let component: Vec<u32> = (0..positions.len() as u32).map(|v| sets.root(v)).collect();
    let mut used = vec![false; positions.len()];
    for &v in triangles.iter().flatten() {
        used[v as usize] = true;
    }
    let first = triangles.first().map(|t| component[t[0] as usize]);
    if !(reach > 0.0 && reach.is_finite()) || triangles.iter().all(|t| Some(component[t[0] as usize]) == first) {
        return (Vec::new(), Vec::new());
    }
    let mut sizes: Table<u32, usize> = Table::default();
    for v in (0..positions.len()).filter(|&v| used[v]) {
        *sizes.entry(component[v]).or_default() += 1;
    }
    let contacts = contacts(positions, triangles, &component, &used, reach, |a, b| {
        let (smaller, larger) = (sizes[&a].min(sizes[&b]), sizes[&a].max(sizes[&b]));
        is_piece(smaller, larger)
    });
    // Kruskal over the components: each pair's contacts join them if they are not yet one.
    let mut joined = DisjointSets::new(positions.len());
    let mut by_pair: Table<[u32; 2], (f64, Vec<[u32; 2]>)> = Table::default();
    for c in &contacts {
        let key = [c.components[0].min(c.components[1]), c.components[0].max(c.components[1])];
        let entry = by_pair.entry(key).or_insert((f64::INFINITY, Vec::new()));
        entry.0 = entry.0.min(c.gap);
        entry.1.push(c.edge);
    }
    // A piece on a body, not two bodies: the smaller component has fewer than
    // [`SMALL_COMPONENT`] vertices or at most [`SMALL_SHARE`] of the other's (a lid on its pot
    // is a body of its own). A touch, not a shell: it meets the other with at most
    // [`MAX_TOUCHING`] of its vertices (a hollow wall's two sides lie along each other).
    by_pair.retain(|key, (_, edges)| {
        let (smaller, larger) = if sizes[&key[0]] <= sizes[&key[1]] { (key[0], key[1]) } else { (key[1], key[0]) };
        let piece = is_piece(sizes[&smaller], sizes[&larger]);
        let mut touching: Vec<u32> =
            edges.iter().flat_map(|e| e.iter().copied()).filter(|&v| component[v as usize] == smaller).collect();
        touching.sort_unstable();
        touching.dedup();
        piece && touching.len() as f64 <= MAX_TOUCHING * sizes[&smaller] as f64
    });
    let mut pairs: Vec<([u32; 2], f64)> = by_pair.iter().map(|(&key, &(gap, _))| (key, gap)).collect();
    // A piece hangs from the largest component it touches (an arm from the torso, not from
    // the leg its hand passes): pairs by the larger surface area first, then closest first.
    let mut area: Table<u32, f64> = Table::default();
    for t in triangles {
        let [a, b, c] = t.map(|v| positions[v as usize]);
        *area.entry(component[t[0] as usize]).or_default() += (b - a).cross(c - a).length() / 2.0;
    }
    let larger = |key: [u32; 2]| area[&key[0]].max(area[&key[1]]);
    pairs.sort_by(|a, b| larger(b.0).total_cmp(&larger(a.0)).then(a.1.total_cmp(&b.1)).then(a.0.cmp(&b.0)));
    let mut bridges = Vec::new();
    let mut joins: Table<u32, Vec<usize>> = Table::default();
    for (key, _) in pairs {
        let (a, b) = (joined.root(key[0]), joined.root(key[1]));
        if a == b {
            continue;
        }
        joined.attach(b, a);
        let mut edges = by_pair.remove(&key).map(|(_, edges)| edges).unwrap_or_default();
        edges.sort_unstable();
        edges.dedup();
        let first = bridges.len();
        bridges.extend(edges);
        for side in key {
            joins.entry(side).or_default().extend(first..bridges.len());
        }
    }
    // A leaf hangs from exactly one larger component; smaller ones (a tuft) may hang from it.
    let mut leaves: Vec<Leaf> = Vec::new();
    for (&piece, edges) in &joins {
        let mut larger: Vec<u32> = edges
            .iter()
            .flat_map(|&e| bridges[e])
            .map(|v| component[v as usize])
            .filter(|&c| c != piece && area[&c] > area[&piece])
            .collect();
        larger.sort_unstable();
        larger.dedup();
        let [parent] = larger[..] else { continue };
        let side = |v: u32| component[v as usize];
        let mut touching: Vec<u32> = edges
            .iter()
            .map(|&e| bridges[e])
            .filter(|e| e.iter().any(|&v| side(v) == parent))
            .flatten()
            .filter(|&v| side(v) == piece)
            .collect();
        touching.sort_unstable();
        touching.dedup();
        let vertices = (0..positions.len() as u32).filter(|&v| used[v as usize] && side(v) == piece).collect();
        leaves.push(Leaf { vertices, touching });
    }
    leaves.sort_by(|a, b| a.vertices.cmp(&b.vertices));
    (bridges, leaves)
}

/// Whether a component of `smaller` vertices may be a piece of one of `larger` (see the module
/// docs).
pub fn is_piece(smaller: usize, larger: usize) -> bool {
    smaller < SMALL_COMPONENT || smaller as f64 <= SMALL_SHARE * larger as f64
}

/// Every vertex within `reach` of a triangle of another component that it `may_join` (by their
/// components' roots), with the corner nearest it of the nearest such triangle (the first on a
/// tie). A grid of cells at least `reach` wide lists the components whose triangles come
/// within reach of each cell; each component's triangles are searched through their own tree
/// ([`NearestTriangle`]), so that a vertex near a densely meshed piece visits a few of its
/// triangles, not every one in its cell (a 62,000-vertex scan of 44 components took 23 s). The
/// vertices are searched in parallel; their contacts come in vertex order.
fn contacts(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    component: &[u32],
    used: &[bool],
    reach: f64,
    may_join: impl Fn(u32, u32) -> bool + Sync,
) -> Vec<Contact> {
    let (lo, hi) = bounds_of(positions);
    // Cells no smaller than 1/64 of the extent, and coarser while the triangles would fill more
    // than a bounded number of cell entries (large panels on a small mesh).
    let mut size = reach.max((hi - lo).max_element() / 64.0);
    let cells_of = |t: &[u32; 3], size: f64| {
        let (a, b) = t.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(positions[v as usize]), hi.max(positions[v as usize]))
        });
        let (a, b) = (((a - reach - lo) / size).floor(), ((b + reach - lo) / size).floor());
        (a.as_i64vec3(), b.as_i64vec3())
    };
    let budget = 16 * triangles.len() + (1 << 20);
    loop {
        let entries: usize = triangles
            .iter()
            .map(|t| {
                let (a, b) = cells_of(t, size);
                ((b - a).as_uvec3() + 1).element_product() as usize
            })
            .sum();
        if entries <= budget {
            break;
        }
        size *= 2.0;
    }
    // Per cell, the components whose triangles come within reach of it, each once.
    let mut grid: Table<[i64; 3], Vec<u32>> = Table::default();
    let mut by_component: Table<u32, Vec<(u32, [DVec3; 3])>> = Table::default();
    for (i, t) in triangles.iter().enumerate() {
        let owner = component[t[0] as usize];
        by_component.entry(owner).or_default().push((i as u32, t.map(|v| positions[v as usize])));
        let (a, b) = cells_of(t, size);
        for x in a.x..=b.x {
            for y in a.y..=b.y {
                for z in a.z..=b.z {
                    let list = grid.entry([x, y, z]).or_default();
                    if list.last() != Some(&owner) {
                        list.push(owner);
                    }
                }
            }
        }
    }
    for list in grid.values_mut() {
        list.sort_unstable();
        list.dedup();
    }
    let trees: Table<u32, NearestTriangle> =
        by_component.into_iter().map(|(owner, triangles)| (owner, NearestTriangle::new(triangles))).collect();
    // Each vertex's contacts, the vertices in parallel and their contacts in vertex order.
    let of_vertex = |v: usize| -> Vec<Contact> {
        let p = positions[v];
        if !used[v] {
            return Vec::new();
        }
        let c = ((p - lo) / size).floor().as_i64vec3().to_array();
        let Some(list) = grid.get(&c) else { return Vec::new() };
        let mut found = Vec::new();
        for &other in list {
            if other == component[v] || !may_join(component[v], other) {
                continue;
            }
            let Some((i, gap)) = trees[&other].nearest(p, reach) else { continue };
            let t = triangles[i as usize];
            let corner = *t
                .iter()
                .min_by(|&&a, &&b| positions[a as usize].distance(p).total_cmp(&positions[b as usize].distance(p)))
                .unwrap_or(&t[0]);
            found.push(Contact { gap, components: [component[v], other], edge: [v as u32, corner] });
        }
        found
    };
    let per_vertex: Vec<Vec<Contact>> = (0..positions.len()).into_par_iter().map(of_vertex).collect();
    per_vertex.into_iter().flatten().collect()
}

/// The point of the triangle `t` nearest `p` (Ericson, "Real-Time Collision Detection", §5.1.5).
pub fn closest_on_triangle(p: DVec3, t: [DVec3; 3]) -> DVec3 {
    let [a, b, c] = t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denominator = va + vb + vc;
    if denominator.abs() <= f64::MIN_POSITIVE {
        return a;
    }
    let (v, w) = (vb / denominator, vc / denominator);
    a + ab * v + ac * w
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis-aligned box from `lo` to `hi` as 6 quads, its vertices from `first`.
    fn boxed(positions: &mut Vec<DVec3>, faces: &mut Faces, lo: DVec3, hi: DVec3) {
        let first = positions.len() as u32;
        for i in 0..8 {
            positions.push(DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            ));
        }
        for quad in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
            faces.push(&quad.map(|v| first + v));
        }
    }

    #[test]
    fn boxes_that_nearly_touch_are_one_body_and_far_ones_are_not() {
        let (mut positions, mut faces) = (Vec::new(), Faces::new());
        boxed(&mut positions, &mut faces, DVec3::ZERO, DVec3::new(1.0, 4.0, 1.0));
        // 0.05 above the first: within 1.5% of the diagonal (about 9.1).
        boxed(&mut positions, &mut faces, DVec3::new(0.0, 4.05, 0.0), DVec3::new(1.0, 8.0, 1.0));
        // 0.5 beside the first: apart.
        boxed(&mut positions, &mut faces, DVec3::new(1.5, 0.0, 0.0), DVec3::new(2.5, 1.0, 1.0));
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        let body = Body::new(&mesh);
        assert!(!body.bridges.is_empty());
        assert!(body.bridges.iter().all(|e| e.iter().all(|&v| v < 16)), "{:?}", body.bridges);
        let d = body.graph.distances(&[0]);
        assert!(d[8..16].iter().all(|d| d.is_finite()), "{d:?}");
        assert!(d[16..].iter().all(|d| d.is_infinite()), "{d:?}");
    }

    /// A closed box with a second glued onto its top face's ring (no bottom of its own, as a
    /// game mesh glues a hand onto a capped forearm): the top face is a wall inside the
    /// surface, and the body drops it; everything else stays.
    #[test]
    fn a_cap_inside_the_surface_is_dropped() {
        let (mut positions, mut faces) = (Vec::new(), Faces::new());
        boxed(&mut positions, &mut faces, DVec3::ZERO, DVec3::new(1.0, 4.0, 1.0));
        // The top ring of the first box: vertices 2, 3, 6, 7 (y = 4).
        for (x, z) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            positions.push(DVec3::new(x, 8.0, z));
        }
        let (bottom, top) = ([2, 3, 7, 6], [8, 9, 11, 10]);
        for k in 0..4 {
            faces.push(&[bottom[k], bottom[(k + 1) % 4], top[(k + 1) % 4], top[k]]);
        }
        faces.push(&[8, 10, 11, 9]);
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        let cap: std::collections::HashSet<u32> = [2, 3, 6, 7].into();
        let on_cap = |t: &[u32; 3]| t.iter().all(|v| cap.contains(v));
        let raw: Vec<[u32; 3]> = mesh.faces.triangles().collect();
        assert_eq!(raw.iter().filter(|t| on_cap(t)).count(), 2, "the input has its cap");
        let body = Body::new(&mesh);
        assert_eq!(body.triangles.len(), raw.len() - 2);
        assert!(!body.triangles.iter().any(on_cap), "{:?}", body.triangles);
        let welded = body.welded_mesh(&mesh).expect("a mesh without its cap");
        assert_eq!(welded.faces.triangles().count(), raw.len() - 2);
        assert_eq!(welded.positions, mesh.positions);
    }

    #[test]
    fn a_seam_within_the_weld_reach_closes_and_the_mesh_keeps_its_vertices() {
        // Two triangles sharing an edge whose copies differ by 1e-6 of the diagonal.
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(1.0 + 1e-6, 0.0, 0.0),
            DVec3::new(0.0, 1.0 - 1e-6, 0.0),
            DVec3::ONE,
        ];
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2]);
        faces.push(&[3, 5, 4]);
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        let body = Body::new(&mesh);
        assert_eq!(body.weld, [0, 1, 2, 1, 2, 5]);
        assert!(body.bridges.is_empty());
        assert_eq!(body.unwelded(&[1]), [1, 3]);
        let welded = body.welded_mesh(&mesh).unwrap();
        assert_eq!(welded.positions, mesh.positions);
        assert_eq!(welded.faces.iter().nth(1).unwrap(), [1, 5, 2]);
    }

    #[test]
    fn two_bodies_that_touch_stay_apart() {
        // Boxes of 8 vertices, 0.01 apart, are pieces and join.
        let (mut positions, mut faces) = (Vec::new(), Faces::new());
        for (lo, hi) in [(0.0, 1.0), (1.01, 2.0)] {
            boxed(&mut positions, &mut faces, DVec3::new(0.0, lo, 0.0), DVec3::new(1.0, hi, 1.0));
        }
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        assert!(!Body::new(&mesh).bridges.is_empty(), "boxes of 8 vertices are pieces");
        // The same boxes with 20 vertices each (rings of 4 around y): neither has fewer than 16
        // vertices nor 1/8 of the other's, so they are two bodies (a lid on its pot).
        let mut positions = Vec::new();
        let mut faces = Faces::new();
        for (lo, hi) in [(0.0, 1.0), (1.01, 2.0)] {
            let first = positions.len() as u32;
            for k in 0..5 {
                let y = lo + (hi - lo) * k as f64 / 4.0;
                for (x, z) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                    positions.push(DVec3::new(x, y, z));
                }
            }
            for k in 0..4u32 {
                for a in 0..4u32 {
                    let b = (a + 1) % 4;
                    faces.push(&[first + 4 * k + a, first + 4 * k + b, first + 4 * k + 4 + b, first + 4 * k + 4 + a]);
                }
            }
            faces.push(&[first, first + 3, first + 2, first + 1]);
            faces.push(&[first + 16, first + 17, first + 18, first + 19]);
        }
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        let body = Body::new(&mesh);
        assert!(body.bridges.is_empty(), "{:?}", body.bridges);
        assert!(body.leaves.is_empty());
    }

    #[test]
    fn a_spanning_tree_joins_each_pair_of_components_once() {
        // Two boxes side by side and a third lying on both: of the three contacts, the last
        // would close a loop and is not taken.
        let (mut positions, mut faces) = (Vec::new(), Faces::new());
        boxed(&mut positions, &mut faces, DVec3::ZERO, DVec3::ONE);
        boxed(&mut positions, &mut faces, DVec3::new(1.01, 0.0, 0.0), DVec3::new(2.0, 1.0, 1.0));
        boxed(&mut positions, &mut faces, DVec3::new(0.0, 1.02, 0.0), DVec3::new(2.0, 2.0, 1.0));
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        let body = Body::new(&mesh);
        let pairs: std::collections::BTreeSet<[u32; 2]> =
            body.bridges.iter().map(|e| [e[0] / 8, e[1] / 8]).map(|[a, b]| [a.min(b), a.max(b)]).collect();
        assert_eq!(pairs.len(), 2, "{pairs:?}");
    }

    #[test]
    fn the_closest_point_of_a_triangle() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert!(closest_on_triangle(DVec3::new(0.2, 0.2, 3.0), t).distance(DVec3::new(0.2, 0.2, 0.0)) < 1e-15);
        assert_eq!(closest_on_triangle(DVec3::new(-1.0, -1.0, 0.0), t), DVec3::ZERO);
        assert_eq!(closest_on_triangle(DVec3::new(0.5, -2.0, 1.0), t), DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(closest_on_triangle(DVec3::new(1.0, 1.0, 0.0), t), DVec3::new(0.5, 0.5, 0.0));
    }
}
