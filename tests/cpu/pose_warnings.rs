//! Warnings before a sweep folds, on the demo's tube (`sweepffd demo`: 5 keys along 4 units, radius
//! 0.5): a tight turn folds its cross-sections on the inside of the bend (r·κ ≥ 1), named with its
//! sweep and t range; a gentle bend of the same tube gives no warning.

use glam::DQuat;
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::rig::Rig;
use sweepffd::sweep::FoldKind;
use sweepffd::synthetic::{Tube, tube_rig};

fn demo_rig() -> Rig {
    tube_rig(&Tube { rings: 160, around: 96, length: 4.0, radius: 0.5 }, 5, 16)
}

fn turn(key: usize, degrees: f64) -> Edit {
    Edit::MoveKey {
        sweep: "tube".into(),
        key,
        translate: [0.0; 3],
        rotate: DQuat::from_rotation_x(degrees.to_radians()).to_array(),
        mode: KeyMode::Local,
    }
}

#[test]
fn a_tight_turn_of_the_demo_tube_warns_of_crossing_sections_and_a_gentle_bend_does_not() {
    let rig = demo_rig();
    // Key 2 (t = 0.5) turned 130°: the interval before it turns by as much over one unit of
    // length (r·κ ≈ 0.5 · 2.3, and past 90° the planes face back across the spine): its
    // sections cross, key 2 steps back behind key 1's plane, its frame turns past 90°.
    let mut tight = Posing::new(&rig);
    tight.apply(&turn(2, 130.0)).unwrap();
    let warnings = tight.warnings().unwrap();
    for warning in &warnings {
        eprintln!("tight: {warning}");
    }
    let crossing: Vec<_> = warnings.iter().filter(|w| w.fold.kind == FoldKind::SectionsCross).collect();
    assert!(!crossing.is_empty(), "{warnings:?}");
    assert!(warnings.iter().any(|w| w.fold.kind == FoldKind::FrameFlips && w.fold.t == [0.25, 0.5]));
    assert!(warnings.iter().any(|w| w.fold.kind == FoldKind::KeysStepBack && w.fold.t == [0.25, 0.5]));
    for warning in &crossing {
        assert_eq!(warning.sweep, "tube");
        let [t0, t1] = warning.fold.t;
        assert!(t0 >= 0.25 - 1e-12 && t1 <= 0.75 + 1e-12, "the fold lies beside key 2: {warning}");
        assert!(warning.fold.amount >= 1.0);
    }
    // The rest rig and a gentle bend (60° over half the tube) do not fold.
    assert!(Posing::new(&rig).warnings().unwrap().is_empty());
    let mut gentle = Posing::new(&rig);
    gentle
        .apply(&Edit::Bend { sweep: "tube".into(), t: 0.5, span: 0.5, axis: [1.0, 0.0, 0.0], angle_deg: 60.0 })
        .unwrap();
    assert_eq!(gentle.warnings().unwrap(), vec![]);
    // Turned 60° alone, key 2 bends one interval by r·κ ≈ 0.5 (no warning); 150° folds it.
    let mut moderate = Posing::new(&rig);
    moderate.apply(&turn(2, 60.0)).unwrap();
    assert_eq!(moderate.warnings().unwrap(), vec![]);
}
