//! Geodesic distance over a part's surface, approximated by shortest paths along the edges of
//! its triangles (Dijkstra's algorithm, with edge lengths as weights).
//!
//! Edge paths overestimate the true geodesic distance by a few percent on a regular
//! triangulation (at most by √2 on a grid of right triangles), uniformly enough that the level
//! sets keep their shape: the skeleton ([`super::skeleton`]) uses only their centroids. The
//! distances depend on the mesh's edge lengths only, so they are unchanged by a rigid motion.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::DVec3;

/// The part's edges as adjacency lists: for each vertex, its neighbours and the edge lengths.
#[derive(Clone, Debug)]
pub struct EdgeGraph {
    /// `starts[v]..starts[v + 1]` indexes `v`'s entries in `neighbours`.
    starts: Vec<usize>,
    neighbours: Vec<(u32, f64)>,
}

impl EdgeGraph {
    /// The edges of `triangles` (indices into `positions`), each once per direction.
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> EdgeGraph {
        EdgeGraph::with_bridges(positions, triangles, &[])
    }

    /// The edges of `triangles` and the `bridges` (edges that no triangle has, such as those
    /// between components that touch), each once per direction.
    pub fn with_bridges(positions: &[DVec3], triangles: &[[u32; 3]], bridges: &[[u32; 2]]) -> EdgeGraph {
        let mut edges: Vec<(u32, u32)> = Vec::with_capacity(6 * triangles.len() + 2 * bridges.len());
        for &[a, b] in bridges {
            if a != b {
                edges.push((a, b));
                edges.push((b, a));
            }
        }
        for t in triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if a != b {
                    edges.push((a, b));
                    edges.push((b, a));
                }
            }
        }
        edges.sort_unstable();
        edges.dedup();
        let mut starts = vec![0usize; positions.len() + 1];
        for &(a, _) in &edges {
            starts[a as usize + 1] += 1;
        }
        for v in 0..positions.len() {
            starts[v + 1] += starts[v];
        }
        let neighbours =
            edges.iter().map(|&(a, b)| (b, positions[a as usize].distance(positions[b as usize]))).collect();
        EdgeGraph { starts, neighbours }
    }

    /// The neighbours of `v` with the lengths of the edges to them.
    pub fn neighbours(&self, v: u32) -> &[(u32, f64)] {
        &self.neighbours[self.starts[v as usize]..self.starts[v as usize + 1]]
    }

    /// Vertices in the graph.
    pub fn len(&self) -> usize {
        self.starts.len() - 1
    }

    /// Whether the graph has no vertices.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The edge-path distance of every vertex from the nearest of `sources` (0 at a source,
    /// `f64::INFINITY` where no path reaches).
    pub fn distances(&self, sources: &[u32]) -> Vec<f64> {
        self.distances_within(sources, f64::INFINITY)
    }

    /// [`EdgeGraph::distances`] up to `limit`: every vertex whose distance is at most `limit`
    /// gets it, the others (which the search stops before settling) `f64::INFINITY` or a
    /// distance above `limit`.
    pub fn distances_within(&self, sources: &[u32], limit: f64) -> Vec<f64> {
        let mut distance = vec![f64::INFINITY; self.len()];
        let mut queue = BinaryHeap::new();
        for &s in sources {
            if distance[s as usize] > 0.0 {
                distance[s as usize] = 0.0;
                queue.push(Pending { distance: 0.0, vertex: s });
            }
        }
        while let Some(Pending { distance: d, vertex }) = queue.pop() {
            if d > limit {
                break;
            }
            if d > distance[vertex as usize] {
                continue;
            }
            for &(next, length) in self.neighbours(vertex) {
                let through = d + length;
                if through < distance[next as usize] {
                    distance[next as usize] = through;
                    queue.push(Pending { distance: through, vertex: next });
                }
            }
        }
        distance
    }
}

/// A vertex waiting in Dijkstra's queue, smallest distance first.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pending {
    distance: f64,
    vertex: u32,
}

impl Eq for Pending {}

impl Ord for Pending {
    fn cmp(&self, other: &Pending) -> Ordering {
        other.distance.total_cmp(&self.distance).then_with(|| other.vertex.cmp(&self.vertex))
    }
}

impl PartialOrd for Pending {
    fn partial_cmp(&self, other: &Pending) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_along_a_strip_of_triangles() {
        // A strip of unit squares along x, each split by its diagonal from (i, 0) to (i + 1, 1).
        let positions: Vec<DVec3> =
            (0..4).flat_map(|i| [DVec3::new(i as f64, 0.0, 0.0), DVec3::new(i as f64, 1.0, 0.0)]).collect();
        let triangles: Vec<[u32; 3]> =
            (0..3u32).flat_map(|i| [[2 * i, 2 * i + 2, 2 * i + 3], [2 * i, 2 * i + 3, 2 * i + 1]]).collect();
        let graph = EdgeGraph::new(&positions, &triangles);
        let d = graph.distances(&[0]);
        assert_eq!(d[0], 0.0);
        assert_eq!(d[6], 3.0);
        assert!((d[7] - (2.0 + 2f64.sqrt())).abs() < 1e-12, "{}", d[7]);
        // From both ends, the middle is nearest to either.
        let d = graph.distances(&[0, 1, 6, 7]);
        assert_eq!(d[2], 1.0);
        assert_eq!(d[4], 1.0);
    }

    #[test]
    fn a_bounded_search_settles_the_vertices_within_its_limit() {
        let positions: Vec<DVec3> = (0..6).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        let triangles: Vec<[u32; 3]> = (0..5u32).map(|i| [i, i + 1, i]).collect();
        let graph = EdgeGraph::new(&positions, &triangles);
        let d = graph.distances_within(&[0], 2.5);
        assert_eq!(&d[..3], &[0.0, 1.0, 2.0]);
        assert!(d[3..].iter().all(|&x| x > 2.5), "{d:?}");
    }

    #[test]
    fn unreachable_vertices_are_infinitely_far() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let graph = EdgeGraph::new(&positions, &[[0, 1, 2]]);
        let d = graph.distances(&[0]);
        assert_eq!(d[3], f64::INFINITY);
        assert!(graph.distances(&[]).iter().all(|d| d.is_infinite()));
    }
}
