//! Choosing a part by position: the vertices a test of their positions accepts, reduced to
//! the largest piece connected by the mesh's edges (so a box around a leg does not also pick
//! up a stray tip of a tail that happens to reach into it).

use glam::DVec3;

use crate::mesh::Mesh;

/// The largest edge-connected set of vertices of `mesh` whose positions `inside` accepts,
/// increasing; empty when it accepts none.
pub fn largest_connected(mesh: &Mesh, inside: impl Fn(DVec3) -> bool) -> Vec<u32> {
    let chosen: Vec<bool> = mesh.positions.iter().map(|&p| inside(p)).collect();
    let mut parent: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    fn root(parent: &mut [u32], mut v: u32) -> u32 {
        while parent[v as usize] != v {
            parent[v as usize] = parent[parent[v as usize] as usize];
            v = parent[v as usize];
        }
        v
    }
    for face in mesh.faces.iter() {
        for (k, &a) in face.iter().enumerate() {
            let b = face[(k + 1) % face.len()];
            if chosen[a as usize] && chosen[b as usize] {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent[ra as usize] = rb;
            }
        }
    }
    let mut sizes = vec![0u32; mesh.positions.len()];
    for v in 0..mesh.positions.len() as u32 {
        if chosen[v as usize] {
            let r = root(&mut parent, v);
            sizes[r as usize] += 1;
        }
    }
    let Some(biggest) = (0..sizes.len()).filter(|&r| sizes[r] > 0).max_by_key(|&r| (sizes[r], std::cmp::Reverse(r)))
    else {
        return Vec::new();
    };
    (0..mesh.positions.len() as u32).filter(|&v| chosen[v as usize] && root(&mut parent, v) == biggest as u32).collect()
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
    }
}
