//! Geodesic distance g from each part's boundary, within its band, by fast marching on the
//! triangle mesh (R. Kimmel and J. A. Sethian, "Computing geodesic paths on manifolds", Proc.
//! Natl. Acad. Sci. USA 95(15), 1998).
//!
//! The march solves the eikonal equation |∇g| = 1 on the part's surface with g = 0 on its
//! boundary vertices. Vertices are accepted in increasing g from a binary heap; accepting v
//! updates every vertex x of the part that shares a triangle with v:
//!
//! - along the edge: g_x ≤ g_v + |x − v|;
//! - across the triangle (v, y, x) when y is already accepted: the planar update
//!   ([`triangle_update`]), g_x ≤ the value of the plane wave that takes g_v at v and g_y at y.
//!
//! Distance never crosses the part's edge: an update only runs over an edge whose two ends,
//! or a triangle whose three corners, belong to the part, so a vertex never takes distance
//! through another part or through the rest of the mesh. Work is bounded by the band: a value
//! at or past the part's width W is never queued, so only the band's vertices are accepted and
//! only they and their one-ring are looked at.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::DVec3;

use super::boundary::Source;
use super::corners::Corners;
use crate::bind::UNOWNED;

/// A triangle whose angle at the updated corner has sin² below this (relative to its edge
/// lengths) is degenerate: it gives no planar update, only its edges do.
const DEGENERATE_SIN2: f64 = 1e-12;

/// A vertex reached within its part's band: g < W.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Reached {
    /// The vertex.
    pub vertex: u32,
    /// g: the geodesic distance from its part's boundary, mesh units, in [0, W).
    pub distance: f64,
    /// The label of the boundary vertex the distance came from (see [`march`]).
    pub label: u32,
}

/// The geodesic distance of every vertex of each part within its band, in the order the
/// march accepts them (increasing g). `owners` and `positions` have one entry per vertex,
/// `widths[s]` is the band width W of sweep s (only the parts of `sources` are marched, so
/// every source's sweep has W > 0). Each vertex carries the label of the accepted neighbour
/// its value came from; for a planar update, the nearer of the two (on a tie, [`UNOWNED`]
/// first, then the lower sweep index, as at the boundary).
pub(super) fn march(
    corners: &Corners,
    positions: &[DVec3],
    owners: &[u32],
    widths: &[f64],
    sources: &[Source],
) -> Vec<Reached> {
    let count = owners.len();
    let mut distance = vec![f64::INFINITY; count];
    let mut label = vec![UNOWNED; count];
    let mut known = vec![false; count];
    let mut heap = BinaryHeap::with_capacity(sources.len());
    for source in sources {
        distance[source.vertex as usize] = 0.0;
        label[source.vertex as usize] = source.label;
        heap.push(Trial { distance: 0.0, vertex: source.vertex });
    }
    let mut reached = Vec::new();
    while let Some(Trial { distance: g, vertex }) = heap.pop() {
        let v = vertex as usize;
        if known[v] || g > distance[v] {
            continue;
        }
        known[v] = true;
        reached.push(Reached { vertex, distance: g, label: label[v] });
        let owner = owners[v];
        let width = widths.get(owner as usize).copied().unwrap_or(0.0);
        for &[a, b] in corners.of(v) {
            for (x, y) in [(a as usize, b as usize), (b as usize, a as usize)] {
                if x == v || owners[x] != owner || known[x] {
                    continue;
                }
                let mut best = (g + positions[x].distance(positions[v]), label[v]);
                if y != v && y != x && owners[y] == owner && known[y] {
                    let update = triangle_update(positions[x], positions[v], g, positions[y], distance[y]);
                    if let Some(t) = update.filter(|&t| t < best.0) {
                        best = (t, nearer_label((g, label[v]), (distance[y], label[y])));
                    }
                }
                if best.0 < distance[x] && best.0 < width {
                    (distance[x], label[x]) = best;
                    heap.push(Trial { distance: best.0, vertex: x as u32 });
                }
            }
        }
    }
    reached
}

/// The planar (Kimmel–Sethian) update of corner c of a triangle from its accepted corners a
/// and b with values g_a and g_b: the value at c of the plane wave g(p) = g_c + n·(p − c),
/// |n| = 1, n in the triangle's plane, that takes g_a at a and g_b at b.
///
/// With e_a = a − c, e_b = b − c and the Gram determinant Δ = |e_a|²|e_b|² − (e_a·e_b)², the
/// conditions e_a·n = g_a − g_c, e_b·n = g_b − g_c and |n| = 1 give the quadratic
///
/// |e_a − e_b|²·g_c² − 2·B·g_c + C = 0, B = g_a(|e_b|² − e_a·e_b) + g_b(|e_a|² − e_a·e_b),
/// C = g_a²|e_b|² − 2·g_a·g_b·(e_a·e_b) + g_b²|e_a|² − Δ,
///
/// whose larger root is the update (solved with g_a, g_b shifted by their minimum, so that
/// the terms stay of the size of the triangle). It is `None`, leaving the edges to update c,
/// when the triangle is degenerate (sin² of the angle at c below 10⁻¹²: zero area, a zero
/// edge), when the wave cannot take both values (negative discriminant), when it would not
/// be causal (g_c below g_a or g_b) and when its direction leaves the triangle: the wave
/// must reach c from inside the angle at c, −n = λ_a·e_a + λ_b·e_b with λ_a, λ_b ≥ 0, where
/// Δ·λ_a = |e_b|²(g_c − g_a) − (e_a·e_b)(g_c − g_b) and Δ·λ_b = |e_a|²(g_c − g_b) −
/// (e_a·e_b)(g_c − g_a). Never NaN or infinite.
pub(super) fn triangle_update(c: DVec3, a: DVec3, g_a: f64, b: DVec3, g_b: f64) -> Option<f64> {
    let (ea, eb) = (a - c, b - c);
    let (aa, bb, ab) = (ea.length_squared(), eb.length_squared(), ea.dot(eb));
    let gram = aa * bb - ab * ab;
    // A NaN from overflowing coordinates passes these tests and fails the last.
    if gram <= DEGENERATE_SIN2 * aa * bb {
        return None;
    }
    let base = g_a.min(g_b);
    let (ta, tb) = (g_a - base, g_b - base);
    let qa = (ea - eb).length_squared();
    let qb = ta * (bb - ab) + tb * (aa - ab);
    let qc = ta * ta * bb - 2.0 * ta * tb * ab + tb * tb * aa - gram;
    let discriminant = qb * qb - qa * qc;
    if discriminant < 0.0 {
        return None;
    }
    let t = (qb + discriminant.sqrt()) / qa;
    let lambda_a = bb * (t - ta) - ab * (t - tb);
    let lambda_b = aa * (t - tb) - ab * (t - ta);
    let g_c = base + t;
    (lambda_a >= 0.0 && lambda_b >= 0.0 && t >= ta.max(tb) && g_c.is_finite()).then_some(g_c)
}

/// The label a planar update passes on: that of the nearer accepted corner; on a tie,
/// [`UNOWNED`] first, then the lower sweep index.
fn nearer_label((g_a, label_a): (f64, u32), (g_b, label_b): (f64, u32)) -> u32 {
    match g_a.total_cmp(&g_b) {
        Ordering::Less => label_a,
        Ordering::Greater => label_b,
        Ordering::Equal if label_a == UNOWNED || label_b == UNOWNED => UNOWNED,
        Ordering::Equal => label_a.min(label_b),
    }
}

/// A queued value: the heap pops the smallest distance first.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Trial {
    distance: f64,
    vertex: u32,
}

impl Eq for Trial {}

impl Ord for Trial {
    fn cmp(&self, other: &Trial) -> Ordering {
        other.distance.total_cmp(&self.distance).then_with(|| other.vertex.cmp(&self.vertex))
    }
}

impl PartialOrd for Trial {
    fn partial_cmp(&self, other: &Trial) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
