//! The triangles around each vertex a falloff band may reach, in compressed rows: what both
//! the boundary search ([`super::boundary`]) and the fast marching ([`super::geodesic`]) read.

use crate::mesh::Faces;

/// For each selected vertex v, every triangle of the fan triangulation
/// ([`Faces::triangles`]) that has v as a corner, stored as its two other corners in winding
/// order. Rows of unselected vertices are empty; a triangle with a corner index at or past
/// the vertex count is left out. Degenerate triangles are kept as they are (a repeated corner
/// shows up as v itself among the others; readers skip it).
///
/// Compressed rows: vertex v's triangles are `others[offsets[v]..offsets[v + 1]]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Corners {
    offsets: Vec<usize>,
    others: Vec<[u32; 2]>,
}

impl Corners {
    /// The rows of the vertices with `selected[v]` (`selected.len()` is the vertex count),
    /// in two passes over the triangles: count, then fill.
    pub(super) fn new(faces: &Faces, selected: &[bool]) -> Corners {
        let count = selected.len();
        let in_range = |triangle: &[u32; 3]| triangle.iter().all(|&v| (v as usize) < count);
        let mut offsets = vec![0usize; count + 1];
        for triangle in faces.triangles().filter(in_range) {
            for v in triangle {
                if selected[v as usize] {
                    offsets[v as usize + 1] += 1;
                }
            }
        }
        for v in 0..count {
            offsets[v + 1] += offsets[v];
        }
        let mut cursor = offsets.clone();
        let mut others = vec![[0u32; 2]; offsets[count]];
        for [a, b, c] in faces.triangles().filter(in_range) {
            for (v, pair) in [(a, [b, c]), (b, [c, a]), (c, [a, b])] {
                if selected[v as usize] {
                    others[cursor[v as usize]] = pair;
                    cursor[v as usize] += 1;
                }
            }
        }
        Corners { offsets, others }
    }

    /// Whether vertex `v`'s triangles leave an edge of it unmatched, so that `v` lies on an
    /// open boundary of the mesh, such as an unwelded seam. Around an inner vertex of a
    /// consistently wound surface the triangles (v, b, c) chain, each c the next one's b, so
    /// the b's and the c's are the same vertices; around a boundary vertex the chain is open
    /// and its first b and last c differ, and so do the sums (and the XORs) of the b's and of
    /// the c's. Not selected or out of range: false.
    pub(super) fn on_open_boundary(&self, v: usize) -> bool {
        let (mut sums, mut xors) = ([0u64; 2], [0u32; 2]);
        for pair in self.of(v) {
            for side in 0..2 {
                sums[side] += u64::from(pair[side]);
                xors[side] ^= pair[side];
            }
        }
        sums[0] != sums[1] || xors[0] != xors[1]
    }

    /// The triangles around vertex `v`, each as its two other corners; empty for a vertex
    /// that was not selected or is out of range.
    pub(super) fn of(&self, v: usize) -> &[[u32; 2]] {
        match (self.offsets.get(v), self.offsets.get(v + 1)) {
            (Some(&start), Some(&end)) => &self.others[start..end],
            _ => &[],
        }
    }
}
