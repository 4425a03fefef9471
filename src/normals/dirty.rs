//! The vertices whose normal can change: those with a moving vertex in their one-ring.
//!
//! A vertex's area-weighted normal (see [`super`]) depends only on the positions of the
//! vertices of its incident triangles. A vertex that no sweep owns never moves (its position
//! stays the rest position, [`UNOWNED`](crate::coeffs::UNOWNED)), so a vertex whose incident
//! triangles are made only of such vertices keeps its rest normal for every pose: its normal is
//! computed once, and only the others are recomputed per frame.

use super::{FAN_INDEX, NormalAdjacency};

/// The vertices, ascending, with at least one incident triangle that has a vertex for which
/// `moves` is true (the vertex itself or a one-ring neighbour): exactly the vertices whose
/// normal can differ from the rest normal. A vertex without incident triangles is never listed
/// (its normal is zero whatever its position).
pub fn dirty_vertices(adjacency: &NormalAdjacency, moves: impl Fn(usize) -> bool) -> Vec<u32> {
    (0..adjacency.vertex_count())
        .filter(|&i| {
            let fans = adjacency.fans_of(i);
            !fans.is_empty() && (moves(i) || fans.iter().any(|&entry| moves((entry & FAN_INDEX) as usize)))
        })
        .map(|i| i as u32)
        .collect()
}

/// `vertices` (indices into one mesh of `vertex_count` vertices) repeated for `instances`
/// instances of the mesh laid out one after another: instance k's copy of vertex v is
/// `k · vertex_count + v`. Ascending if `vertices` is.
pub fn instanced(vertices: &[u32], vertex_count: u32, instances: u32) -> Vec<u32> {
    (0..instances).flat_map(|k| vertices.iter().map(move |&v| k * vertex_count + v)).collect()
}
