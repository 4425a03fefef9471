//! Disjoint sets of vertices (union-find with path halving), for grouping a part's vertices
//! or edges into connected pieces.

/// Every vertex 0..n in a set; each set is named by its root.
#[derive(Clone, Debug)]
pub(crate) struct DisjointSets {
    parent: Vec<u32>,
}

impl DisjointSets {
    /// `n` vertices, each alone.
    pub(crate) fn new(n: usize) -> DisjointSets {
        DisjointSets { parent: (0..n as u32).collect() }
    }

    /// The root of `v`'s set.
    pub(crate) fn root(&mut self, mut v: u32) -> u32 {
        let parent = &mut self.parent;
        while parent[v as usize] != v {
            parent[v as usize] = parent[parent[v as usize] as usize];
            v = parent[v as usize];
        }
        v
    }

    /// Makes the root `root` a child of the root `onto`: their sets become one, named `onto`.
    pub(crate) fn attach(&mut self, root: u32, onto: u32) {
        self.parent[root as usize] = onto;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joined_vertices_share_the_root_they_were_attached_onto() {
        let mut sets = DisjointSets::new(5);
        let (a, b) = (sets.root(0), sets.root(1));
        sets.attach(a, b);
        let (c, d) = (sets.root(1), sets.root(3));
        sets.attach(d, c);
        assert_eq!([0, 1, 3].map(|v| sets.root(v)), [1, 1, 1]);
        assert_eq!(sets.root(2), 2);
        assert_eq!(sets.root(4), 4);
    }
}
