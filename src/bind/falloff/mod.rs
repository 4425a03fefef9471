//! Falloff weights (rig field `falloff`): how much of its own sweep's deformation each owned
//! vertex near its part's boundary follows, computed once at bind time.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind** (falloff weights) → deform → normals
//! → output.

use crate::bind::UNOWNED;

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
}

// PLACEHOLDER until the geodesic version lands: Dijkstra over edges, rest labels only.
pub fn band_weights(
    faces: &crate::mesh::Faces,
    positions: &[glam::DVec3],
    owners: &[u32],
    falloff: &[f64],
) -> Vec<BandWeight> {
    use std::collections::BinaryHeap;
    let n = positions.len();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    for [a, b, c] in faces.triangles() {
        for (x, y) in [(a, b), (b, c), (c, a)] {
            adj[x as usize].push(y);
            adj[y as usize].push(x);
        }
    }
    let mut dist = vec![f64::INFINITY; n];
    let mut label = vec![UNOWNED; n];
    let mut heap = BinaryHeap::new();
    for v in 0..n {
        let o = owners[v];
        if o == UNOWNED || falloff[o as usize] <= 0.0 {
            continue;
        }
        if let Some(&u) = adj[v].iter().find(|&&u| owners[u as usize] != o) {
            dist[v] = 0.0;
            label[v] = owners[u as usize];
            heap.push((std::cmp::Reverse(0u64), v));
        }
    }
    while let Some((std::cmp::Reverse(dbits), v)) = heap.pop() {
        let d = f64::from_bits(dbits);
        if d > dist[v] {
            continue;
        }
        let o = owners[v];
        for &u in &adj[v] {
            let u = u as usize;
            if owners[u] != o {
                continue;
            }
            let nd = d + positions[v].distance(positions[u]);
            if nd < dist[u] && nd < falloff[o as usize] {
                dist[u] = nd;
                label[u] = label[v];
                heap.push((std::cmp::Reverse(nd.to_bits()), u));
            }
        }
    }
    (0..n)
        .filter(|&v| dist[v].is_finite())
        .map(|v| {
            let x = dist[v] / falloff[owners[v] as usize];
            let s = x * x * (3.0 - 2.0 * x);
            let neighbour = label[v];
            let seam = neighbour != UNOWNED && falloff[neighbour as usize] > 0.0;
            BandWeight { vertex: v as u32, weight: if seam { 0.5 + 0.5 * s } else { s }, neighbour }
        })
        .filter(|b| b.weight < 1.0)
        .collect()
}
