//! The node graph of a glTF scene, checked and measured before anything is built.
//!
//! A file controls the shape of its node graph, so nothing here recurses: one iterative
//! depth-first pass from the scene's roots finds cycles, the height of every node (the
//! longest path below it) and, memoized per node, what one instance of the node's subtree
//! gives: mesh instances, vertices, triangles and node visits, all with saturating
//! arithmetic. A graph whose nodes share children at every level doubles its instances per
//! level; this pass stays linear in nodes and edges, and its counts let the caller refuse
//! such a file before expanding it.

use super::GltfDataError;
use crate::limits::MAX_GLTF_NODE_DEPTH;

/// What one instance of a node's subtree (or of a mesh) gives, each count saturating.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Totals {
    /// Mesh instances.
    pub instances: usize,
    /// Vertices of those instances (primitives sharing a POSITION accessor counted once).
    pub vertices: usize,
    /// Triangles of those instances.
    pub triangles: usize,
    /// Nodes the expansion visits: every node instance with a mesh instance at or below it.
    pub visits: usize,
}

impl Totals {
    /// The sum of two totals, saturating.
    pub fn plus(self, other: Totals) -> Totals {
        Totals {
            instances: self.instances.saturating_add(other.instances),
            vertices: self.vertices.saturating_add(other.vertices),
            triangles: self.triangles.saturating_add(other.triangles),
            visits: self.visits.saturating_add(other.visits),
        }
    }
}

/// The node graph: each node's children and mesh, indices checked against the arrays.
pub(super) struct Graph {
    /// Children of each node, in file order.
    pub children: Vec<Vec<usize>>,
    /// Mesh of each node.
    pub mesh: Vec<Option<usize>>,
}

/// [`Totals`] of every node reachable from `roots`, given the totals of one instance of each
/// mesh (`meshes`); unreachable nodes get zero.
///
/// # Errors
///
/// [`GltfDataError::NodeCycle`] when a node reachable from `roots` is its own descendant,
/// [`GltfDataError::NodeTooDeep`] when a node lies deeper than [`MAX_GLTF_NODE_DEPTH`]
/// below a root (the error names the first such node on a longest path).
pub(super) fn measure(graph: &Graph, roots: &[usize], meshes: &[Totals]) -> Result<Vec<Totals>, GltfDataError> {
    const NEW: u8 = 0;
    const OPEN: u8 = 1;
    const DONE: u8 = 2;
    let n = graph.children.len();
    let mut state = vec![NEW; n];
    let mut height = vec![0usize; n];
    let mut totals = vec![Totals::default(); n];
    for &root in roots {
        if state[root] == DONE {
            continue;
        }
        state[root] = OPEN;
        let mut stack = vec![(root, 0usize)];
        while let Some((node, next)) = stack.last_mut() {
            let node = *node;
            if let Some(&child) = graph.children[node].get(*next) {
                *next += 1;
                match state[child] {
                    NEW => {
                        state[child] = OPEN;
                        stack.push((child, 0));
                    }
                    OPEN => return Err(GltfDataError::NodeCycle { node: child }),
                    _ => {}
                }
                continue;
            }
            stack.pop();
            state[node] = DONE;
            let mut sum = graph.mesh[node].and_then(|m| meshes.get(m)).copied().unwrap_or_default();
            for &child in &graph.children[node] {
                height[node] = height[node].max(height[child] + 1);
                sum = sum.plus(totals[child]);
            }
            sum.visits = if sum.instances == 0 { 0 } else { sum.visits.saturating_add(1) };
            totals[node] = sum;
        }
    }
    for &root in roots {
        if height[root] > MAX_GLTF_NODE_DEPTH {
            return Err(too_deep(graph, &height, root));
        }
    }
    Ok(totals)
}

/// The error for the node at depth `MAX_GLTF_NODE_DEPTH + 1` on a longest path below `root`.
fn too_deep(graph: &Graph, height: &[usize], root: usize) -> GltfDataError {
    let mut node = root;
    for _ in 0..=MAX_GLTF_NODE_DEPTH {
        let deeper = graph.children[node].iter().find(|&&c| height[c] + 1 == height[node]);
        node = *deeper.unwrap_or(&node);
    }
    GltfDataError::NodeTooDeep { node, depth: MAX_GLTF_NODE_DEPTH + 1, limit: MAX_GLTF_NODE_DEPTH }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One mesh instance of one vertex and no triangle.
    const POINT: Totals = Totals { instances: 1, vertices: 1, triangles: 0, visits: 0 };

    fn chain(n: usize) -> Graph {
        Graph { children: (0..n).map(|i| if i + 1 < n { vec![i + 1] } else { vec![] }).collect(), mesh: vec![None; n] }
    }

    #[test]
    fn a_chain_at_the_depth_limit_passes_and_one_deeper_fails_naming_the_node() {
        let mut graph = chain(MAX_GLTF_NODE_DEPTH + 1);
        graph.mesh[MAX_GLTF_NODE_DEPTH] = Some(0);
        let totals = measure(&graph, &[0], &[POINT]).unwrap();
        assert_eq!(totals[0], Totals { visits: MAX_GLTF_NODE_DEPTH + 1, ..POINT });
        let graph = chain(20_000);
        assert_eq!(
            measure(&graph, &[0], &[]).unwrap_err(),
            GltfDataError::NodeTooDeep { node: 1025, depth: 1025, limit: MAX_GLTF_NODE_DEPTH }
        );
    }

    #[test]
    fn shared_children_double_the_counts_per_level_and_saturate() {
        // Node i has node i + 1 twice as a child; the last node draws the mesh.
        let levels = 100;
        let mut graph = Graph { children: (0..levels).map(|i| vec![i + 1, i + 1]).collect(), mesh: vec![None; levels] };
        graph.children.push(vec![]);
        graph.mesh.push(Some(0));
        let totals = measure(&graph, &[0], &[POINT]).unwrap();
        assert_eq!(totals[levels - 10].instances, 1 << 10);
        assert_eq!(totals[levels - 10].visits, (1 << 11) - 1);
        assert_eq!(totals[0].instances, usize::MAX);
    }

    #[test]
    fn cycles_are_found_and_empty_subtrees_are_not_visited() {
        let graph = Graph { children: vec![vec![1], vec![2], vec![1]], mesh: vec![None; 3] };
        assert_eq!(measure(&graph, &[0], &[]).unwrap_err(), GltfDataError::NodeCycle { node: 1 });
        let graph = Graph { children: vec![vec![1, 2], vec![], vec![]], mesh: vec![None, None, Some(0)] };
        let totals = measure(&graph, &[0], &[POINT]).unwrap();
        assert_eq!(totals[0].visits, 2, "node 1 has no mesh below it");
    }
}
