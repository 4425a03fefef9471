//! Small pieces that sit on a rigged part go with it, for [`super::autorig`]: a game
//! character's fingernails, a cartoon's eyes, a strap are components of their own lying on the
//! surface of a limb; its hair or a helmet lies around it, off its surface ([`AROUND`]). Where such a piece lies along the surface (more than half its vertices
//! touching it) `super::body` does not join it for the search, which takes it for a shell, and
//! the fit runs on the part's own surface; so the piece was owned by no sweep, and posing the
//! limb left it in the air (the public ogre's ten fingernails, 258 vertices each, 3·10⁻⁴ of its
//! diagonal off its fingers).
//!
//! A piece is a component of the welded mesh's unowned vertices (joined by the triangles whose
//! corners no part owns), small beside the largest (the body, `super::body::is_piece`): a
//! fingernail, even where one of its corners is welded to its finger's (two of the ogre's), or
//! an island of surface a part surrounds. Each of its vertices looks for the nearest vertex of
//! another component within [`REACH`] of the diagonal, owned or not; where one part owns the
//! vertices found for more than half of the piece's, the piece goes to that part. A piece
//! sitting on such a piece follows it in a later round.

use glam::DVec3;

use super::body::{Body, is_piece};
use super::disjoint_sets::DisjointSets;
use super::grid::Grid;
use crate::mesh::Mesh;

/// A piece sits on the vertices that lie within this fraction of the bounding-box diagonal of
/// its own (the ogre's fingernails lie 3·10⁻⁴ of its diagonal off their fingers at the
/// nearest, 1.4·10⁻³ at the median).
pub const REACH: f64 = 0.005;

/// A piece also goes with a part where it lies around it within this fraction of the part's
/// mean radius (its sweep's): a game figure's hair, a helmet or a sleeve, a shell of its own
/// modelled off the surface it covers (the faerie's fringe and side locks, 28 vertices, lie
/// 0.5–2.5 off her head, of mean radius 2.5, and 0.3 of her mesh's diagonal is 0.31). Left
/// behind, they stayed in the air when the part moved.
pub const AROUND: f64 = 1.0;

/// The pieces of `mesh` (searched as `body`) that sit on a part (see the module docs), given
/// `owner`: per mesh vertex, the part that owns it, and `radii`: per part, its mean radius (a
/// piece within [`AROUND`] of it of the part goes with it too). Each as the part and the
/// piece's mesh vertices (with every vertex welded to them), increasing; `owner` is updated to
/// match.
pub fn hanging_pieces(
    mesh: &Mesh,
    body: &Body,
    owner: &mut [Option<usize>],
    radii: &[f64],
) -> Vec<(usize, Vec<u32>)> {
    let count = mesh.positions.len();
    let unowned = |v: u32| owner[v as usize].is_none();
    let mut sets = DisjointSets::new(count);
    let mut used = vec![false; count];
    for t in &body.triangles {
        for &v in t {
            used[v as usize] = true;
        }
        if t.iter().all(|&v| unowned(v)) {
            for k in 1..3 {
                let (a, b) = (sets.root(t[0]), sets.root(t[k]));
                if a != b {
                    sets.attach(b, a);
                }
            }
        }
    }
    let searched: Vec<u32> = (0..count as u32).filter(|&v| used[v as usize]).collect();
    // Per searched vertex, its component: of the unowned vertices, else (owned) its own.
    let component: Vec<u32> = searched.iter().map(|&v| if unowned(v) { sets.root(v) } else { v }).collect();
    let mut pieces: std::collections::BTreeMap<u32, Vec<usize>> = Default::default();
    for (i, &c) in component.iter().enumerate().filter(|&(i, _)| unowned(searched[i])) {
        pieces.entry(c).or_default().push(i);
    }
    let largest = pieces.values().map(Vec::len).max().unwrap_or(0);
    let unwelded: Vec<(u32, Vec<u32>)> = pieces
        .iter()
        .filter(|(_, members)| members.len() < largest && is_piece(members.len(), largest))
        .map(|(&c, members)| (c, body.unwelded(&members.iter().map(|&i| searched[i]).collect::<Vec<_>>())))
        .filter(|(_, vertices)| vertices.iter().all(|&v| owner[v as usize].is_none()))
        .collect();
    if unwelded.is_empty() {
        return Vec::new();
    }
    let points: Vec<DVec3> = searched.iter().map(|&v| mesh.positions[v as usize]).collect();
    // How near a piece's vertex lies to a vertex of part k for that vertex to go with it.
    let on = REACH * body.diagonal;
    let reach_of = |k: usize| radii.get(k).map_or(on, |&radius| on.max(AROUND * radius));
    let grid = Grid::new(&points, (0..radii.len()).map(reach_of).fold(on, f64::max));
    // Each piece's vertices' nearest vertex of another component, found once: what owns it
    // may change from round to round, the vertex does not.
    let nearest: Vec<Vec<Option<usize>>> = unwelded
        .iter()
        .map(|(piece, _)| {
            pieces[piece].iter().map(|&i| grid.nearest_where(&points, points[i], |j| component[j] != *piece)).collect()
        })
        .collect();
    let mut given = Vec::new();
    let mut placed = vec![false; unwelded.len()];
    loop {
        let mut changed = false;
        for (k, (piece, vertices)) in unwelded.iter().enumerate() {
            if placed[k] {
                continue;
            }
            let members = &pieces[piece];
            let mut counts: std::collections::BTreeMap<usize, usize> = Default::default();
            for (&i, near) in members.iter().zip(&nearest[k]) {
                let Some(j) = *near else { continue };
                if let Some(part) = owner[searched[j] as usize].filter(|&part| points[j].distance(points[i]) <= reach_of(part)) {
                    *counts.entry(part).or_default() += 1;
                }
            }
            let best = counts.into_iter().max_by_key(|&(part, n)| (n, std::cmp::Reverse(part)));
            let Some((part, _)) = best.filter(|&(_, n)| 2 * n > members.len()) else { continue };
            for &v in vertices {
                owner[v as usize] = Some(part);
            }
            placed[k] = true;
            changed = true;
            given.push((part, vertices.clone()));
        }
        if !changed {
            break;
        }
    }
    given
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::common::sphere;
    use crate::mesh::Faces;

    /// Unit spheres of `rings` rings scaled by `radius` and moved to `center`, one mesh, each a
    /// component; the vertices of each, in order.
    fn spheres(balls: &[(DVec3, f64, u32)]) -> (Mesh, Vec<Vec<u32>>) {
        let (mut positions, mut faces, mut members) = (Vec::new(), Faces::new(), Vec::new());
        for &(center, radius, rings) in balls {
            let unit = sphere(rings, 2 * rings);
            let first = positions.len() as u32;
            positions.extend(unit.positions.iter().map(|&p| center + p * radius));
            for t in unit.faces.triangles() {
                faces.push(&t.map(|v| v + first));
            }
            members.push((first..positions.len() as u32).collect());
        }
        (Mesh::from_parts(positions, faces, Vec::new()).unwrap(), members)
    }

    /// A body (unowned), a finger (owned by part 0), a nail lying on the finger, a wart on the
    /// body and a speck far from both: the nail goes with the finger; the wart stays with the
    /// unowned body and the speck, touching nothing, stays unowned.
    #[test]
    fn a_piece_on_a_part_goes_with_it_and_one_on_the_body_or_on_nothing_stays() {
        let (mesh, members) = spheres(&[
            (DVec3::ZERO, 1.0, 24),
            (DVec3::new(3.0, 0.0, 0.0), 0.3, 48),
            (DVec3::new(3.3, 0.0, 0.0), 0.015, 6),
            (DVec3::new(1.0, 0.0, 0.0), 0.015, 6),
            (DVec3::new(3.0, 1.5, 0.0), 0.015, 6),
        ]);
        let [body_ball, finger, nail, wart, speck] = [0, 1, 2, 3, 4].map(|k| &members[k]);
        let body = Body::new(&mesh);
        let mut owner = vec![None; mesh.positions.len()];
        for &v in finger {
            owner[v as usize] = Some(0);
        }
        let given = hanging_pieces(&mesh, &body, &mut owner, &[0.3]);
        assert_eq!(given, vec![(0, nail.clone())]);
        assert!(nail.iter().all(|&v| owner[v as usize] == Some(0)));
        for piece in [body_ball, wart, speck] {
            assert!(piece.iter().all(|&v| owner[v as usize].is_none()));
        }
        // Before, nothing took the nail: the body does not join a piece lying along a surface.
        assert!(body.bridges.iter().flatten().all(|v| nail.binary_search(v).is_err()));
    }

    /// A shell around a finger of radius 0.3, half its radius off its surface (a helmet, a
    /// game figure's hair), goes with the finger; the rule on its own reach alone (0.005 of the
    /// diagonal) left it behind. The same shell around the body, which no part owns, stays.
    #[test]
    fn a_shell_around_a_part_within_its_radius_goes_with_it() {
        let (mesh, members) = spheres(&[
            (DVec3::ZERO, 1.0, 24),
            (DVec3::new(3.0, 0.0, 0.0), 0.3, 48),
            (DVec3::new(3.0, 0.0, 0.0), 0.45, 6),
            (DVec3::ZERO, 1.15, 6),
        ]);
        let [finger, shell, body_shell] = [1, 2, 3].map(|k| &members[k]);
        let body = Body::new(&mesh);
        let owned_finger = || {
            let mut owner = vec![None; mesh.positions.len()];
            for &v in finger {
                owner[v as usize] = Some(0);
            }
            owner
        };
        let mut owner = owned_finger();
        let given = hanging_pieces(&mesh, &body, &mut owner, &[0.3]);
        assert_eq!(given, vec![(0, shell.clone())]);
        assert!(body_shell.iter().all(|&v| owner[v as usize].is_none()));
        // Measured by the reach alone (a part of no radius), the shell stays where it was.
        let mut owner = owned_finger();
        assert_eq!(hanging_pieces(&mesh, &body, &mut owner, &[0.0]), vec![]);
        assert!(shell.iter().all(|&v| owner[v as usize].is_none()));
    }
}
