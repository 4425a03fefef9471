//! Vertex normals of the deformed mesh: for each vertex, the sum of the cross products of the
//! edges of its incident triangles (each cross product is twice the triangle's area times its
//! normal, so the sum is area-weighted), normalized. Polygons count as their fan triangles.
//!
//! Data flow: rig → sweep → sweep coefficients → bind → deform → **normals** → output.
//!
//! The adjacency is built once per mesh; every vertex then gathers its own sum, so no atomics
//! (and no float atomics) are needed on the GPU. The f32 twin of the GPU kernel is
//! `crate::cpu::normals`.
//!
//! Only vertices with a moving vertex in their one-ring need new normals per pose
//! ([`dirty_vertices`]); [`tangents`] turns rest tangents with the normals.

use crate::parallel::prelude::*;
use glam::DVec3;

use crate::mesh::Faces;

mod dirty;
mod reach;
pub mod tangents;

pub use dirty::{dirty_vertices, instanced};
pub use reach::jacobian_reach;

/// Marks the first neighbour of a fan in [`NormalAdjacency::fans`].
pub const FAN_START: u32 = 1 << 31;
/// Marks the last neighbour of a closed fan in [`NormalAdjacency::fans`]: the fan's last
/// triangle runs from this neighbour back to the fan's first, which is not repeated.
pub const FAN_CLOSE: u32 = 1 << 30;
/// Marks the last entry of a vertex's row in [`NormalAdjacency::fans`], so that a reader needs
/// only the row's start.
pub const FAN_END: u32 = 1 << 29;
/// The neighbour's vertex index in a [`NormalAdjacency::fans`] entry (the bits below the
/// flags).
pub const FAN_INDEX: u32 = FAN_END - 1;

/// For each vertex i, its incident triangles as fans: runs of one-ring neighbours j_0, j_1, …
/// where each consecutive pair (j_m, j_{m+1}) makes the triangle (i, j_m, j_{m+1}) in winding
/// order, so that (p_{j_m} − p_i) × (p_{j_{m+1}} − p_i) is its area-weighted normal. A closed
/// manifold vertex of m triangles is one fan of m entries, the last carrying [`FAN_CLOSE`]: its
/// last triangle (i, j_{m−1}, j_0) closes back to the first neighbour, which is not repeated
/// (a reader keeps p_{j_0} rather than loading it twice). A boundary or non-manifold vertex has
/// several fans, each entry that starts one carrying [`FAN_START`]. Every triangle is counted
/// once. Compressed rows: vertex i's entries are `fans[offsets[i]..offsets[i + 1]]`, the last
/// of a non-empty row carrying [`FAN_END`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NormalAdjacency {
    /// `vertex count + 1` row starts into `fans`.
    pub offsets: Vec<u32>,
    /// Fan entries, row by row: a neighbour index, with [`FAN_START`] on a fan's first entry.
    pub fans: Vec<u32>,
}

impl NormalAdjacency {
    /// Builds the fans of the fan triangulation of `faces` over `vertex_count` vertices
    /// (`vertex_count` at most [`FAN_INDEX`] + 1).
    ///
    /// The vertices are split into a few ranges per thread, built in parallel: each range
    /// gathers the edges of its vertices from every triangle and chains them into its rows
    /// (`chain_range`); the rows are then joined in order.
    pub fn new(faces: &Faces, vertex_count: usize) -> NormalAdjacency {
        // A triangle list (every face a triangle, as the GPU engine's) is read three indices at
        // a time rather than fanned face by face.
        let list = faces.offsets.windows(2).all(|w| w[1] - w[0] == 3);
        let fanned: Vec<[u32; 3]>;
        let triangles: &[[u32; 3]] = match list {
            true => bytemuck::cast_slice(&faces.indices),
            false => {
                fanned = faces.triangles().collect();
                &fanned
            }
        };
        // Few ranges (each reads every triangle), enough for every thread and to balance them.
        let ranges = (crate::parallel::thread_count()).clamp(1, vertex_count.max(1));
        let span = vertex_count.div_ceil(ranges).max(1);
        let blocks: Vec<(Vec<u32>, Vec<u32>)> = (0..vertex_count.div_ceil(span))
            .into_par_iter()
            .map(|part| chain_range(triangles, part * span..((part + 1) * span).min(vertex_count)))
            .collect();
        let mut offsets = Vec::with_capacity(vertex_count + 1);
        let mut fans = Vec::with_capacity(blocks.iter().map(|(fans, _)| fans.len()).sum());
        offsets.push(0u32);
        for (block_fans, lengths) in &blocks {
            let mut end = fans.len() as u32;
            offsets.extend(lengths.iter().map(|&length| {
                end += length;
                end
            }));
            fans.extend_from_slice(block_fans);
        }
        NormalAdjacency { offsets, fans }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The fan entries of vertex `i`.
    pub fn fans_of(&self, i: usize) -> &[u32] {
        &self.fans[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}

/// The rows of the vertices `range`: each vertex's triangles of `triangles` as directed edges
/// (j → k) of its one-ring, grouped by vertex, then chained ([`chain_edges`]); returns their
/// entries and each row's length.
fn chain_range(triangles: &[[u32; 3]], range: std::ops::Range<usize>) -> (Vec<u32>, Vec<u32>) {
    let inside = |v: u32| range.contains(&(v as usize));
    let mut starts = vec![0u32; range.len() + 1];
    for triangle in triangles {
        for &v in triangle {
            if inside(v) {
                starts[v as usize - range.start + 1] += 1;
            }
        }
    }
    for i in 0..range.len() {
        starts[i + 1] += starts[i];
    }
    let mut cursor = starts.clone();
    let mut edges = vec![(0u32, 0u32); starts[range.len()] as usize];
    for &[a, b, c] in triangles {
        for (v, edge) in [(a, (b, c)), (b, (c, a)), (c, (a, b))] {
            if inside(v) {
                let slot = &mut cursor[v as usize - range.start];
                edges[*slot as usize] = edge;
                *slot += 1;
            }
        }
    }
    let (mut fans, mut lengths) = (Vec::with_capacity(edges.len()), Vec::with_capacity(range.len()));
    let mut scratch = ChainScratch::default();
    for i in 0..range.len() {
        let row = fans.len();
        chain_edges(&edges[starts[i] as usize..starts[i + 1] as usize], &mut fans, &mut scratch);
        if fans.len() > row
            && let Some(last) = fans.last_mut()
        {
            *last |= FAN_END;
        }
        lengths.push((fans.len() - row) as u32);
    }
    (fans, lengths)
}

/// Edges of a row that [`chain_edges`] scans rather than bisects.
const SMALL_ROW: usize = 16;

/// The working lists of [`chain_edges`], kept from one vertex to the next so that chaining a
/// mesh allocates once a block, not once a vertex.
#[derive(Default)]
struct ChainScratch {
    edges: Vec<(u32, u32)>,
    ends: Vec<u32>,
    used: Vec<bool>,
    starts: Vec<usize>,
}

/// Appends to `fans` the one-ring edges (j → k) of one vertex chained into fans: first from
/// every j that no edge ends at (boundaries), then around the remaining cycles. Each edge is
/// used once; a fan of two or more edges that ends at its first neighbour drops that repeat
/// and flags its new last entry [`FAN_CLOSE`]. Sorting by j makes finding the edge that
/// continues a fan a binary search.
fn chain_edges(row: &[(u32, u32)], fans: &mut Vec<u32>, scratch: &mut ChainScratch) {
    let ChainScratch { edges, ends, used, starts } = scratch;
    edges.clear();
    edges.extend_from_slice(row);
    edges.sort_unstable();
    // A row of a few edges (a vertex of a regular mesh has six) is searched by scanning it, a
    // larger one by bisection: the same edges found either way.
    let small = edges.len() <= SMALL_ROW;
    ends.clear();
    if !small {
        ends.extend(edges.iter().map(|&(_, k)| k));
        ends.sort_unstable();
    }
    used.clear();
    used.resize(edges.len(), false);
    let edges = &edges[..];
    let next_unused = |used: &[bool], j: u32| match small {
        true => (0..edges.len()).find(|&e| edges[e].0 == j && !used[e]),
        false => {
            let first = edges.partition_point(|&(a, _)| a < j);
            (first..edges.len()).take_while(|&e| edges[e].0 == j).find(|&e| !used[e])
        }
    };
    let is_end = |j: u32| match small {
        true => edges.iter().any(|&(_, k)| k == j),
        false => ends.binary_search(&j).is_ok(),
    };
    starts.clear();
    starts.extend((0..edges.len()).filter(|&e| !is_end(edges[e].0)));
    for start in starts.iter().copied().chain(0..edges.len()) {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (j, mut k) = edges[start];
        let first = fans.len();
        fans.push(j | FAN_START);
        fans.push(k);
        while let Some(e) = next_unused(used, k) {
            used[e] = true;
            k = edges[e].1;
            fans.push(k);
        }
        if k == j && fans.len() - first >= 3 {
            fans.pop();
            if let Some(last) = fans.last_mut() {
                *last |= FAN_CLOSE;
            }
        }
    }
}

/// Area-weighted unit normals of every vertex (f64 reference). A vertex with no incident
/// triangle, or whose triangles cancel or have no area, gets the zero vector.
pub fn vertex_normals(positions: &[DVec3], adjacency: &NormalAdjacency) -> Vec<DVec3> {
    (0..adjacency.vertex_count()).into_par_iter().map(|i| fan_normal(adjacency, i, |v| positions[v])).collect()
}

/// The area-weighted unit normal of vertex `i` from the `position` of each vertex of its fans
/// (f64), or the zero vector as in [`vertex_normals`].
pub(crate) fn fan_normal(adjacency: &NormalAdjacency, i: usize, position: impl Fn(usize) -> DVec3) -> DVec3 {
    let p = position(i);
    let (mut sum, mut previous, mut first) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for &entry in adjacency.fans_of(i) {
        let q = position((entry & FAN_INDEX) as usize) - p;
        if entry & FAN_START == 0 {
            sum += previous.cross(q);
        } else {
            first = q;
        }
        if entry & FAN_CLOSE != 0 {
            sum += q.cross(first);
        }
        previous = q;
    }
    sum.normalize_or_zero()
}

#[cfg(test)]
mod tests;
