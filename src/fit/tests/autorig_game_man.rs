//! `fit::autorig` on BCN_Epileptic (`tests/meshes/bcn_epileptic.obj`): a game character of
//! three meshes (lower body, upper body, head) whose seams are welded for the search, standing
//! with its arms down, facing +z. Its eyes (two balls of 81 vertices) and teeth (20) are
//! components of their own inside the head.

use crate::common;

use glam::DVec3;
use sweepffd::fit::autorig::{Autorig, AutorigOptions, RiggedPart, autorig, target_of};
use sweepffd::fit::key_path::zigzags;
use sweepffd::mesh::Mesh;

use common::autorig_report::print_parts;

use super::rigged_parts::{chain_of, chain_points, components};

/// The game man, rigged, his highest vertex (his crown) and his height.
fn rigged_game_man() -> (Mesh, Autorig, u32, f64) {
    let mesh = common::kept_mesh("bcn_epileptic.obj");
    let rigged = autorig(&mesh, &AutorigOptions::default()).unwrap();
    print_parts("bcn_epileptic", &mesh, &rigged);
    let y = |v: u32| mesh.positions[v as usize].y;
    let crown = (0..mesh.positions.len() as u32).max_by(|&a, &b| y(a).total_cmp(&y(b))).unwrap();
    let bottom = mesh.positions.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    let height = y(crown) - bottom;
    (mesh, rigged, crown, height)
}

/// The root parts of `rigged`: the head (it holds `crown`), the ponytail (every vertex above
/// 80% of the man's height), and the rest, his limbs.
fn head_ponytail_and_limbs<'a>(
    mesh: &Mesh,
    rigged: &'a Autorig,
    crown: u32,
    height: f64,
) -> (&'a RiggedPart, &'a RiggedPart, Vec<&'a RiggedPart>) {
    let above = mesh.positions[crown as usize].y - 0.2 * height;
    let roots = rigged.parts.iter().filter(|p| p.parent.is_none());
    let (heads, others): (Vec<&RiggedPart>, Vec<&RiggedPart>) =
        roots.partition(|p| p.vertices.binary_search(&crown).is_ok());
    assert_eq!(heads.len(), 1, "the head");
    let (ponytails, limbs): (Vec<&RiggedPart>, Vec<&RiggedPart>) =
        others.into_iter().partition(|p| p.vertices.iter().all(|&v| mesh.positions[v as usize].y > above));
    assert_eq!(ponytails.len(), 1, "{:?}", ponytails.iter().map(|p| &p.name).collect::<Vec<_>>());
    (heads[0], ponytails[0], limbs)
}

/// The game man gets what a user expects of a humanoid: two legs, hip to toe, and two arms,
/// shoulder to hand, each arm with its five fingers as children; the head with its neck, and
/// the ponytail behind it. Every chain reaches over a quarter of his height, their tips
/// distinct; left and right are rigged alike (as many keys, fits within 1.25 times of each
/// other, one on either side); every sweep fits within its target at the vertices it was
/// fitted to, none zigzags, every vertex binds with a root.
#[test]
fn the_game_man_gets_two_legs_two_arms_with_their_fingers_his_head_and_ponytail() {
    let (mesh, rigged, crown, height) = rigged_game_man();
    let position = |v: u32| mesh.positions[v as usize];
    for part in &rigged.parts {
        assert!(part.fit.quality.rms_d <= target_of(&part.fit), "{}: {:?}", part.name, part.fit.quality);
        assert!(!zigzags(&part.fit.keys), "{}", part.name);
        assert_eq!(part.fit.quality.without_root, 0, "{}", part.name);
    }
    let (head, ponytail, limbs) = head_ponytail_and_limbs(&mesh, &rigged, crown, height);
    assert!(ponytail.vertices.iter().all(|&v| position(v).z < head.fit.keys[0].center.z), "behind the neck");
    assert_eq!(limbs.len(), 4, "{:?}", limbs.iter().map(|p| &p.name).collect::<Vec<_>>());
    let bottom = position(crown).y - height;
    let (mut legs, mut arms, mut tips) = (Vec::new(), Vec::new(), Vec::new());
    for limb in limbs {
        let chain = chain_of(&rigged, limb);
        let points = chain_points(&mesh, &chain);
        let span = points.iter().flat_map(|a| points.iter().map(move |b| a.distance(*b))).fold(0.0, f64::max);
        eprintln!("bcn_epileptic {}: {} links, spans {span:.3} of {height:.3}", limb.name, chain.len());
        assert!(span >= 0.25 * height, "{}: spans {span} of {height}", limb.name);
        tips.extend(chain.iter().map(|p| p.tip));
        if points.iter().any(|p| p.y < bottom + 0.05 * height) {
            legs.push(limb);
        } else {
            assert_eq!(chain.len(), 6, "{}: an arm and its five fingers", limb.name);
            assert!(chain[1..].iter().all(|finger| finger.parent.as_ref() == Some(&limb.name)));
            arms.push(limb);
        }
    }
    assert_eq!((legs.len(), arms.len()), (2, 2));
    for pair in [&legs, &arms] {
        let (a, b) = (pair[0], pair[1]);
        assert_eq!(a.fit.keys.len(), b.fit.keys.len(), "{} and {}", a.name, b.name);
        let (qa, qb) = (a.fit.quality.rms_d, b.fit.quality.rms_d);
        assert!(qa.max(qb) <= 1.25 * qa.min(qb), "{} {qa} and {} {qb}", a.name, b.name);
        let side = |p: &RiggedPart| p.vertices.iter().map(|&v| position(v).x).sum::<f64>().signum();
        assert_eq!(side(a), -side(b), "{} and {}", a.name, b.name);
    }
    let count = tips.len();
    tips.sort_unstable();
    tips.dedup();
    assert_eq!(tips.len(), count, "distinct tips");
}

/// The head part holds the head's mesh (a component of its own, its seam with the neck welded
/// for the search) but for the ponytail's root, and the eyes and teeth inside it, components
/// of their own that no limb search reaches, go with it: a nod carries them. Weighed against
/// the 472 vertices the parts leave of the body, as they were before, the eyes stayed in place
/// (`fit::hanging`'s own test pins that rule).
#[test]
fn the_game_mans_head_carries_his_eyes_and_teeth() {
    let (mesh, rigged, crown, height) = rigged_game_man();
    let position = |v: u32| mesh.positions[v as usize];
    let (head, ponytail, _) = head_ponytail_and_limbs(&mesh, &rigged, crown, height);
    let components = components(&mesh);
    let head_mesh = components.iter().find(|c| c.binary_search(&crown).is_ok()).unwrap();
    let in_head = |v: &u32| head.vertices.binary_search(v).is_ok();
    let in_ponytail = |v: &u32| ponytail.vertices.binary_search(v).is_ok();
    let (by_head, by_ponytail) =
        (head_mesh.iter().filter(|v| in_head(v)).count(), head_mesh.iter().filter(|v| in_ponytail(v)).count());
    eprintln!(
        "bcn_epileptic: of the head's mesh's {} vertices, the head holds {by_head}, the ponytail {by_ponytail}",
        head_mesh.len()
    );
    assert!(by_head as f64 >= 0.8 * head_mesh.len() as f64, "{by_head} of {}", head_mesh.len());
    assert!((by_head + by_ponytail) as f64 >= 0.9 * head_mesh.len() as f64);
    let points = head_mesh.iter().map(|&v| position(v));
    let (lo, hi) = points.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
    let within = |v: &u32| position(*v).cmpge(lo).all() && position(*v).cmple(hi).all();
    let inside: Vec<&Vec<u32>> = components.iter().filter(|c| *c != head_mesh && c.iter().all(within)).collect();
    let mut sizes: Vec<usize> = inside.iter().map(|c| c.len()).collect();
    sizes.sort_unstable();
    assert_eq!(sizes, [20, 81, 81], "the eyes and teeth");
    for piece in inside {
        assert!(piece.iter().all(in_head), "a piece of {} inside the head", piece.len());
    }
}
