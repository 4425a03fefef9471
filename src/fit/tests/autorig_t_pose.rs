//! `fit::autorig` on Mr. Fixit (`tests/meshes/mrfixit.obj`): a humanoid game character of one
//! welded surface in a T-pose, its arms along ±z ending in mittens with a thumb and fingers,
//! its sleeves' cuffs at the wrists.

use crate::common;

use sweepffd::fit::autorig::{AutorigOptions, RESCUED_SHARE, RiggedPart, autorig, link_looseness, target_of};
use sweepffd::fit::key_path::zigzags;
use sweepffd::fit::{FitOptions, fit};
use sweepffd::mesh::Mesh;

use common::autorig_report::print_parts;

use super::rigged_parts::chain_of;

fn mr_fixit() -> Mesh {
    common::kept_mesh("mrfixit.obj")
}

/// Each of the T-posed arms is a chain from the shoulder to the hand, its thumb and fingers
/// children of the arm, each link within its target at its own vertices; the arms alike (as
/// many keys, fits within 1.25 times of each other). As one sweep each arm is no tube (over
/// 50% by its sections), and its chain's loosest link, fitted with a ring of the palm, fits
/// between 0.5 and [`RESCUED_SHARE`] of that: the rule before (half of the one sweep) refused
/// both chains, and kept four fingertips of the mittens in place of the arms.
#[test]
fn mr_fixits_arms_are_chains_from_the_shoulder_with_their_fingers() {
    let mesh = mr_fixit();
    let rigged = autorig(&mesh, &AutorigOptions::default()).unwrap();
    print_parts("mrfixit", &mesh, &rigged);
    let position = |v: u32| mesh.positions[v as usize];
    let reach = |part: &RiggedPart| part.vertices.iter().map(|&v| position(v).z.abs()).fold(0.0, f64::max);
    let inner = |part: &RiggedPart| part.vertices.iter().map(|&v| position(v).z.abs()).fold(f64::INFINITY, f64::min);
    // The hands reach past |z| = 4.5; the torso lies within |z| < 1.3.
    let chain_reach = |root: &RiggedPart| chain_of(&rigged, root).iter().map(|l| reach(l)).fold(0.0, f64::max);
    let arms: Vec<&RiggedPart> = rigged.parts.iter().filter(|p| p.parent.is_none() && chain_reach(p) > 4.5).collect();
    assert_eq!(arms.len(), 2, "{:?}", rigged.parts.iter().map(|p| &p.name).collect::<Vec<_>>());
    for arm in &arms {
        let links = chain_of(&rigged, arm);
        assert_eq!(links.len(), 5, "{}: an arm, its thumb and three fingers", arm.name);
        assert!(links[1..].iter().all(|finger| finger.parent.as_ref() == Some(&arm.name)));
        assert!(inner(arm) < 1.6, "{}: starts at |z| {}, not at the shoulder", arm.name, inner(arm));
        for link in &links {
            let target = target_of(&link.fit);
            assert!(link.quality.rms_d <= target, "{}: {:?} over {target}", link.name, link.quality);
            assert!(!zigzags(&link.fit.keys), "{}", link.name);
            assert_eq!(link.quality.without_root, 0, "{}", link.name);
        }
        // The arm as one sweep, and the rule that keeps its chain.
        let mut all: Vec<u32> = links.iter().flat_map(|l| l.vertices.iter().copied()).collect();
        all.sort_unstable();
        all.dedup();
        let whole = fit(&mesh, &all, &FitOptions::default()).unwrap().sections_quality().rms_d;
        let worst = links.iter().map(|l| link_looseness(&l.fit)).fold(0.0, f64::max);
        eprintln!(
            "mrfixit {}: one sweep {:.1}%, the chain's loosest link {:.1}%",
            arm.name,
            100.0 * whole,
            100.0 * worst
        );
        assert!(whole > 0.5, "{}: one sweep {whole}", arm.name);
        assert!(worst > 0.5 * whole && worst <= RESCUED_SHARE * whole, "{}: {worst} against {whole}", arm.name);
    }
    let (a, b) = (arms[0], arms[1]);
    let side = |p: &RiggedPart| p.vertices.iter().map(|&v| position(v).z).sum::<f64>().signum();
    assert_eq!(side(a), -side(b), "one arm on either side");
    assert_eq!(a.fit.keys.len(), b.fit.keys.len());
    let (qa, qb) = (a.fit.quality.rms_d, b.fit.quality.rms_d);
    assert!(qa.max(qb) <= 1.25 * qa.min(qb), "{qa} and {qb}");
    // Both legs, from the hip to the sole.
    let bottom = mesh.positions.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    let legs = rigged.parts.iter().filter(|p| p.vertices.iter().any(|&v| position(v).y < bottom + 0.1));
    assert_eq!(legs.count(), 2);
}
