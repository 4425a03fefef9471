//! Small pieces that sit on a rigged part go with it, for [`super::autorig`]: a game
//! character's fingernails, a cartoon's eyes, a strap are components of their own lying on the
//! surface of a limb; its hair or a helmet lies around it, off its surface ([`AROUND`]). Where such a piece lies along the surface (more than half its vertices
//! touching it) `super::body` does not join it for the search, which takes it for a shell, and
//! the fit runs on the part's own surface; so the piece was owned by no sweep, and posing the
//! limb left it in the air (the public ogre's ten fingernails, 258 vertices each, 3·10⁻⁴ of its
//! diagonal off its fingers).
//!
//! A piece is a component of the welded mesh's unowned vertices (joined by the triangles whose
//! corners no part owns), other than the largest (the body's rest), and small beside the
//! welded mesh's largest component, owned vertices and all (`super::body::is_piece`): a
//! fingernail, even where one of its corners is welded to its finger's (two of the ogre's), an
//! eye inside a head, or an island of surface a part surrounds. (Weighed against the body's
//! unowned rest, BCN_Epileptic's eyes, 81 vertices each beside 472, were no pieces, and stayed
//! in place when its head moved.) Each of its vertices looks for the nearest vertex of
//! another component within [`REACH`] of the diagonal, owned or not; where one part owns the
//! vertices found for more than half of the piece's, the piece goes to that part. A piece
//! sitting on such a piece follows it in a later round. Where no piece goes so, a piece that
//! rests on no surface goes to the part it lies around ([`AROUND`]), searched farther.

use std::collections::HashMap;

use glam::DVec3;

use super::body::{Body, is_piece};
use super::disjoint_sets::DisjointSets;
use super::grid::Grid;
use crate::mesh::{Mesh, bounds_of};

/// A piece sits on the vertices that lie within this fraction of the bounding-box diagonal of
/// its own (the ogre's fingernails lie 3·10⁻⁴ of its diagonal off their fingers at the
/// nearest, 1.4·10⁻³ at the median).
pub const REACH: f64 = 0.005;

/// A piece that rests on no surface (most of its vertices farther than [`REACH`] from every
/// other component) goes with a part where it lies around it: the nearest vertex of another
/// component of most of its vertices is the part's and within this fraction of the part's
/// mean radius (its sweep's). A game figure's hair, a helmet or a sleeve is a shell of its own
/// modelled off the surface it covers: the faerie's fringe, four locks of 7 vertices, lies
/// 0.5–2.5 off her head, of mean radius about 2.5, where [`REACH`] of her diagonal is 0.31.
/// Left behind, the locks stayed in the air when her head moved.
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
    // The welded mesh's components, owned vertices and all: a piece is small beside the body
    // as the file has it, not beside what the parts leave of it.
    let mut whole = DisjointSets::new(count);
    let mut used = vec![false; count];
    for t in &body.triangles {
        for &v in t {
            used[v as usize] = true;
        }
        for k in 1..3 {
            let (a, b) = (whole.root(t[0]), whole.root(t[k]));
            if a != b {
                whole.attach(b, a);
            }
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
    let mut sizes: HashMap<u32, usize> = HashMap::new();
    for &v in &searched {
        *sizes.entry(whole.root(v)).or_default() += 1;
    }
    let body_size = sizes.values().copied().max().unwrap_or(0);
    let unwelded: Vec<(u32, Vec<u32>)> = pieces
        .iter()
        .filter(|(_, members)| members.len() < largest && is_piece(members.len(), body_size))
        .map(|(&c, members)| (c, body.unwelded(&members.iter().map(|&i| searched[i]).collect::<Vec<_>>())))
        .filter(|(_, vertices)| vertices.iter().all(|&v| owner[v as usize].is_none()))
        .collect();
    if unwelded.is_empty() {
        return Vec::new();
    }
    let points: Vec<DVec3> = searched.iter().map(|&v| mesh.positions[v as usize]).collect();
    let on = REACH * body.diagonal;
    let grid = Grid::new(&points, on);
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
        // Pieces on a part first; where none goes, pieces around one (the wider search).
        let mut found: Vec<(usize, usize)> = Vec::new();
        for (k, (piece, _)) in unwelded.iter().enumerate().filter(|&(k, _)| !placed[k]) {
            let mut counts: std::collections::BTreeMap<usize, usize> = Default::default();
            for part in nearest[k].iter().filter_map(|near| near.and_then(|j| owner[searched[j] as usize])) {
                *counts.entry(part).or_default() += 1;
            }
            let best = counts.into_iter().max_by_key(|&(part, n)| (n, std::cmp::Reverse(part)));
            if let Some((part, _)) = best.filter(|&(_, n)| 2 * n > pieces[piece].len()) {
                found.push((k, part));
                // A piece sitting on this one follows it in a later round.
                for &v in &unwelded[k].1 {
                    owner[v as usize] = Some(part);
                }
            }
        }
        if found.is_empty() {
            let mut around = PartsAround::new(&points, &searched, owner, radii, on);
            for (k, (piece, _)) in unwelded.iter().enumerate().filter(|&(k, _)| !placed[k]) {
                // A piece resting on a surface (most of its vertices within [`REACH`] of
                // another component: the body's, where no part took it) lies around no part.
                let floating = nearest[k].iter().filter(|near| near.is_none()).count();
                if 2 * floating > nearest[k].len()
                    && let Some(part) = around.part_around(&pieces[piece], |j| component[j] != *piece, owner)
                {
                    found.push((k, part));
                }
            }
            for &(k, part) in &found {
                for &v in &unwelded[k].1 {
                    owner[v as usize] = Some(part);
                }
            }
        }
        if found.is_empty() {
            break;
        }
        for (k, part) in found {
            placed[k] = true;
            given.push((part, unwelded[k].1.clone()));
        }
    }
    given
}

/// A part's vertices bucketed for the search of the pieces lying around it ([`AROUND`]).
struct Around {
    part: usize,
    /// How far from its vertices a piece's vertex may lie: [`AROUND`] of its mean radius.
    reach: f64,
    positions: Vec<DVec3>,
    bounds: (DVec3, DVec3),
    grid: Grid,
}

/// The parts a piece may lie around, and every searched vertex bucketed for their reaches.
struct PartsAround<'a> {
    points: &'a [DVec3],
    searched: &'a [u32],
    /// The parts whose reach is wider than that of a piece on a part.
    parts: Vec<Around>,
    /// Per reach (its bits), the searched vertices bucketed for it, built where first needed.
    everything: HashMap<u64, Grid>,
}

impl<'a> PartsAround<'a> {
    /// The parts of `radii` (per part, its mean radius) whose reach is wider than `on`, with the
    /// searched vertices (`points`, the positions of `searched`) each owns (`owner`, per mesh
    /// vertex).
    fn new(
        points: &'a [DVec3],
        searched: &'a [u32],
        owner: &[Option<usize>],
        radii: &[f64],
        on: f64,
    ) -> PartsAround<'a> {
        let mut owned: Vec<Vec<DVec3>> = vec![Vec::new(); radii.len()];
        for (i, &v) in searched.iter().enumerate() {
            if let Some(part) = owner[v as usize].filter(|&part| part < radii.len()) {
                owned[part].push(points[i]);
            }
        }
        let parts = owned
            .into_iter()
            .enumerate()
            .filter(|(part, positions)| AROUND * radii[*part] > on && !positions.is_empty())
            .map(|(part, positions)| {
                let reach = AROUND * radii[part];
                let (bounds, grid) = (bounds_of(&positions), Grid::new(&positions, reach));
                Around { part, reach, positions, bounds, grid }
            })
            .collect();
        PartsAround { points, searched, parts, everything: Default::default() }
    }

    /// The part the piece of searched vertices `members` lies around, if any: of the parts
    /// within whose reach more than half of its vertices lie (the one most do first, the lowest
    /// of as many), the first that owns (`owner`) the nearest vertex of another component
    /// (`other`, by searched index) within that reach of more than half of them.
    fn part_around(&mut self, members: &[usize], other: impl Fn(usize) -> bool, owner: &[Option<usize>]) -> Option<usize> {
        let PartsAround { points, searched, parts, everything } = self;
        let piece: Vec<DVec3> = members.iter().map(|&i| points[i]).collect();
        let (lo, hi) = bounds_of(&piece);
        let mut near: Vec<(&Around, usize)> = parts
            .iter()
            .filter(|around| {
                let (plo, phi) = around.bounds;
                let reach = DVec3::splat(around.reach);
                (lo - reach).cmple(phi).all() && (hi + reach).cmpge(plo).all()
            })
            .map(|around| (around, piece.iter().filter(|&&p| around.grid.nearest(&around.positions, p).is_some()).count()))
            .filter(|&(_, count)| 2 * count > piece.len())
            .collect();
        near.sort_by_key(|&(around, count)| (std::cmp::Reverse(count), around.part));
        near.into_iter().map(|(around, _)| around).find(|around| {
            let grid = everything.entry(around.reach.to_bits()).or_insert_with(|| Grid::new(points, around.reach));
            // Counted until the count decides.
            let (mut owned, mut others) = (0, 0);
            for &p in &piece {
                let nearest = grid.nearest_where(points, p, &other);
                if nearest.is_some_and(|j| owner[searched[j] as usize] == Some(around.part)) {
                    owned += 1;
                } else {
                    others += 1;
                }
                if 2 * owned > piece.len() || 2 * others >= piece.len() {
                    break;
                }
            }
            2 * owned > piece.len()
        })
        .map(|around| around.part)
    }
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

    /// Per vertex of `mesh`, its owner: part 0 for `vertices`, none for the others.
    fn owned_by_part_0(mesh: &Mesh, vertices: &[u32]) -> Vec<Option<usize>> {
        let mut owner = vec![None; mesh.positions.len()];
        for &v in vertices {
            owner[v as usize] = Some(0);
        }
        owner
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
        let mut owner = owned_by_part_0(&mesh, finger);
        let given = hanging_pieces(&mesh, &body, &mut owner, &[0.3]);
        assert_eq!(given, vec![(0, nail.clone())]);
        assert!(nail.iter().all(|&v| owner[v as usize] == Some(0)));
        for piece in [body_ball, wart, speck] {
            assert!(piece.iter().all(|&v| owner[v as usize].is_none()));
        }
        // Before, nothing took the nail: the body does not join a piece lying along a surface.
        assert!(body.bridges.iter().flatten().all(|v| nail.binary_search(v).is_err()));
    }

    /// An eye inside a head: a ball whose part (the head) owns all but a cap of it (the body's
    /// rest), and a small ball inside it, under the part's surface. The eye goes with the part:
    /// it is small beside the ball ([`super::super::body::SMALL_SHARE`] of it), though not beside
    /// the cap the part leaves unowned, which the rule before weighed it against (a game
    /// figure's eyes stayed in place when its head moved).
    #[test]
    fn an_eye_inside_a_part_goes_with_it_however_little_of_the_body_is_left_unowned() {
        let (mesh, members) = spheres(&[(DVec3::ZERO, 1.0, 24), (DVec3::new(0.8, 0.0, 0.0), 0.05, 4)]);
        let (ball, eye) = (&members[0], &members[1]);
        let head: Vec<u32> = ball.iter().copied().filter(|&v| mesh.positions[v as usize].x > -0.9).collect();
        let rest = ball.len() - head.len();
        let body = Body::new(&mesh);
        let mut owner = owned_by_part_0(&mesh, &head);
        assert_eq!(hanging_pieces(&mesh, &body, &mut owner, &[1.0]), vec![(0, eye.clone())]);
        assert!(is_piece(eye.len(), ball.len()));
        assert!(!is_piece(eye.len(), rest), "an eye of {} beside a rest of {rest}", eye.len());
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
        let mut owner = owned_by_part_0(&mesh, finger);
        let given = hanging_pieces(&mesh, &body, &mut owner, &[0.3]);
        assert_eq!(given, vec![(0, shell.clone())]);
        assert!(body_shell.iter().all(|&v| owner[v as usize].is_none()));
        // Measured by the reach alone (a part of no radius), the shell stays where it was.
        let mut owner = owned_by_part_0(&mesh, finger);
        assert_eq!(hanging_pieces(&mesh, &body, &mut owner, &[0.0]), vec![]);
        assert!(shell.iter().all(|&v| owner[v as usize].is_none()));
    }
}
