//! Choosing a part by position: the vertices a test of their positions accepts, reduced to
//! the largest piece connected by the mesh's edges (so a box around a leg does not also pick
//! up a stray tip of a tail that happens to reach into it).

use glam::DVec3;

use super::disjoint_sets::DisjointSets;
use crate::mesh::Mesh;

/// The largest edge-connected set of vertices of `mesh` whose positions `inside` accepts,
/// increasing; empty when it accepts none.
pub fn largest_connected(mesh: &Mesh, inside: impl Fn(DVec3) -> bool) -> Vec<u32> {
    let pieces = Pieces::new(mesh, inside);
    let mut sizes = vec![0u32; mesh.positions.len()];
    for &root in pieces.roots.iter().flatten() {
        sizes[root as usize] += 1;
    }
    let Some(biggest) = (0..sizes.len()).filter(|&r| sizes[r] > 0).max_by_key(|&r| (sizes[r], std::cmp::Reverse(r)))
    else {
        return Vec::new();
    };
    pieces.members(biggest as u32)
}

/// The vertices whose positions `inside` accepts and that are edge-connected to `seed` through
/// such vertices, increasing; empty when `seed` itself is not accepted.
pub fn connected_to(mesh: &Mesh, seed: u32, inside: impl Fn(DVec3) -> bool) -> Vec<u32> {
    let pieces = Pieces::new(mesh, inside);
    match pieces.roots[seed as usize] {
        Some(root) => pieces.members(root),
        None => Vec::new(),
    }
}

/// The edge-connected pieces of the accepted vertices: each accepted vertex's piece, named by
/// one of its vertices.
struct Pieces {
    roots: Vec<Option<u32>>,
}

impl Pieces {
    /// Union-find over the edges of the faces whose two ends are both accepted.
    fn new(mesh: &Mesh, inside: impl Fn(DVec3) -> bool) -> Pieces {
        let chosen: Vec<bool> = mesh.positions.iter().map(|&p| inside(p)).collect();
        let mut sets = DisjointSets::new(mesh.positions.len());
        for face in mesh.faces.iter() {
            for (k, &a) in face.iter().enumerate() {
                let b = face[(k + 1) % face.len()];
                if chosen[a as usize] && chosen[b as usize] {
                    let (ra, rb) = (sets.root(a), sets.root(b));
                    sets.attach(ra, rb);
                }
            }
        }
        let roots = (0..mesh.positions.len() as u32).map(|v| chosen[v as usize].then(|| sets.root(v))).collect();
        Pieces { roots }
    }

    /// The vertices of the piece named `root`, increasing.
    fn members(&self, root: u32) -> Vec<u32> {
        (0..self.roots.len() as u32).filter(|&v| self.roots[v as usize] == Some(root)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Faces;

    #[test]
    fn the_largest_piece_wins() {
        let positions: Vec<DVec3> = (0..7).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2]);
        faces.push(&[2, 3, 4]);
        faces.push(&[4, 5, 6]);
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        // Vertex 4 is left out, which splits 0..=3 from 5..=6.
        assert_eq!(largest_connected(&mesh, |p| p.x != 4.0), vec![0, 1, 2, 3]);
        assert!(largest_connected(&mesh, |_| false).is_empty());
        assert_eq!(connected_to(&mesh, 6, |p| p.x != 4.0), vec![5, 6]);
        assert!(connected_to(&mesh, 4, |p| p.x != 4.0).is_empty());
    }
}
