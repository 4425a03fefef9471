//! The nearest of a set of triangles to a point within a reach, for the body's contacts
//! (`super::body`): a bounding-volume hierarchy over the triangles (median splits along the
//! longest axis of their centroids), searched branch and bound, the nearer child box first, so
//! that a query visits the few boxes near the point however densely the triangles lie around it.
//! The order of the visits cannot change the answer: the least distance, the lowest index among
//! equals.

use glam::DVec3;

use super::body::closest_on_triangle;

/// Triangles per leaf.
const LEAF: usize = 4;

/// A node: its box, and either its two children or its range of `order`.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: the range `order[start..end]`; inner node: `start` is the first child's index,
    /// the second follows its subtree at `end`.
    start: u32,
    end: u32,
    leaf: bool,
}

/// Triangles (as indices into a list and their corners) arranged for nearest queries.
pub struct NearestTriangle {
    nodes: Vec<Node>,
    /// The triangles' indices (as given), leaf by leaf.
    order: Vec<u32>,
    /// Each triangle's corners, by position in the list given.
    corners: Vec<[DVec3; 3]>,
}

impl NearestTriangle {
    /// The tree of `triangles` (each an index, as the caller names it, and its corners).
    pub fn new(triangles: Vec<(u32, [DVec3; 3])>) -> NearestTriangle {
        let (indices, corners): (Vec<u32>, Vec<[DVec3; 3]>) = triangles.into_iter().unzip();
        let mut tree = NearestTriangle { nodes: Vec::new(), order: Vec::new(), corners };
        let mut local: Vec<u32> = (0..indices.len() as u32).collect();
        if !local.is_empty() {
            tree.build(&mut local);
        }
        // From local positions to the caller's indices, and each node's range with them.
        tree.order = local.iter().map(|&i| indices[i as usize]).collect();
        tree.corners = local.iter().map(|&i| tree.corners[i as usize]).collect();
        tree
    }

    /// Builds the tree over `local` (positions into `corners`), which it reorders leaf by leaf;
    /// a leaf's range is into `local`.
    fn build(&mut self, local: &mut [u32]) {
        let mut stack: Vec<(usize, usize, Option<usize>)> = vec![(0, local.len(), None)];
        while let Some((start, end, parent)) = stack.pop() {
            let window = &mut local[start..end];
            let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            let (mut clo, mut chi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            for &i in window.iter() {
                let t = self.corners[i as usize];
                for p in t {
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
                let centroid = (t[0] + t[1] + t[2]) / 3.0;
                clo = clo.min(centroid);
                chi = chi.max(centroid);
            }
            let index = self.nodes.len();
            if let Some(parent) = parent {
                // A parent's second child is found at `end` (its first follows it directly).
                self.nodes[parent].end = index as u32;
            }
            let leaf = window.len() <= LEAF;
            self.nodes.push(Node { lo, hi, start: start as u32, end: end as u32, leaf });
            if leaf {
                continue;
            }
            let extent = chi - clo;
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            let middle = window.len() / 2;
            let key = |i: &u32| {
                let t = self.corners[*i as usize];
                (t[0] + t[1] + t[2])[axis]
            };
            window.select_nth_unstable_by(middle, |a, b| key(a).total_cmp(&key(b)).then(a.cmp(b)));
            self.nodes[index].start = index as u32 + 1;
            // The second child is pushed first, so the first is built next, right after this node.
            stack.push((start + middle, end, Some(index)));
            stack.push((start, start + middle, None));
        }
    }

    /// The triangle nearest `p` within `reach` (the caller's index and its distance), the
    /// lowest index among equally near ones; `None` where none is within reach.
    pub fn nearest(&self, p: DVec3, reach: f64) -> Option<(u32, f64)> {
        let mut best: Option<(f64, u32)> = None;
        let mut stack = Vec::with_capacity(64);
        if !self.nodes.is_empty() {
            stack.push(0usize);
        }
        while let Some(n) = stack.pop() {
            let node = self.nodes[n];
            let box_gap = self.box_gap(n, p);
            if box_gap > reach || best.is_some_and(|(gap, _)| box_gap > gap) {
                continue;
            }
            if node.leaf {
                for k in node.start as usize..node.end as usize {
                    let gap = closest_on_triangle(p, self.corners[k]).distance(p);
                    let index = self.order[k];
                    let better = best.is_none_or(|(least, at)| gap < least || (gap == least && index < at));
                    if gap <= reach && better {
                        best = Some((gap, index));
                    }
                }
            } else {
                // The nearer child first, so that the best found early prunes the farther one.
                let (first, second) = (node.start as usize, node.end as usize);
                if self.box_gap(second, p) < self.box_gap(first, p) {
                    stack.push(first);
                    stack.push(second);
                } else {
                    stack.push(second);
                    stack.push(first);
                }
            }
        }
        best.map(|(gap, index)| (index, gap))
    }

    /// The distance from `p` to node `n`'s box (0 inside it).
    fn box_gap(&self, n: usize, p: DVec3) -> f64 {
        let node = &self.nodes[n];
        (node.lo - p).max(p - node.hi).max(DVec3::ZERO).length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against a scan of every triangle: the same nearest (lowest index on ties) for points
    /// near and far, on a grid of triangles with repeated ones (exact ties).
    #[test]
    fn the_tree_finds_what_a_scan_finds() {
        let mut triangles = Vec::new();
        let mut seed = 7u64;
        let mut random = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for i in 0..400u32 {
            let base = DVec3::new(random(), random(), random()) * 10.0;
            let t = [base, base + DVec3::new(random(), 0.0, 0.1), base + DVec3::new(0.0, random(), 0.2)];
            triangles.push((3 * i, t));
            if i % 10 == 0 {
                // An exact twin at a higher index: the lower one is the nearest.
                triangles.push((3 * i + 1, t));
            }
        }
        let tree = NearestTriangle::new(triangles.clone());
        for _ in 0..500 {
            let p = DVec3::new(random(), random(), random()) * 12.0 - 1.0;
            for reach in [0.05, 0.5, 3.0] {
                let scanned = triangles
                    .iter()
                    .map(|&(i, t)| (i, closest_on_triangle(p, t).distance(p), t))
                    .filter(|&(_, gap, _)| gap <= reach)
                    .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                let found = tree.nearest(p, reach);
                assert_eq!(found, scanned.map(|s| (s.0, s.1)), "p {p}, reach {reach}");
            }
        }
        assert!(NearestTriangle::new(Vec::new()).nearest(DVec3::ZERO, 1.0).is_none());
    }
}
