//! Keep-length posing: every edit of a sequence of bends, twists, drags and cross-section moves
//! leaves the edited sweep's chord length at the rest's within 1e-6 relative; without it the
//! same edits stretch the sweep.

use glam::DQuat;
use sweepffd::edit::{DragMode, Edit, KeyMode, Posing, chord_length};
use sweepffd::synthetic::{Tube, tube_rig};

fn edits() -> Vec<Edit> {
    let tube = "tube".to_string();
    vec![
        Edit::Bend { sweep: tube.clone(), t: 0.4, span: 0.3, axis: [1.0, 0.0, 0.0], angle_deg: 70.0 },
        // A twist: key 3 turned about the spine.
        Edit::MoveKey {
            sweep: tube.clone(),
            key: 3,
            translate: [0.0; 3],
            rotate: DQuat::from_rotation_z(1.2).to_array(),
            mode: KeyMode::Local,
        },
        Edit::DragPoint {
            sweep: tube.clone(),
            theta: 0.0,
            t: 0.9,
            d: 0.0,
            h: 0.0,
            to: [1.5, 0.4, 3.5],
            mode: DragMode::Both,
            keys: 3,
        },
        Edit::MoveSection { sweep: tube.clone(), t: 0.6, translate: [0.3, -0.5, 0.4], rotate: [0.0, 0.0, 0.0, 1.0] },
        Edit::MoveKey {
            sweep: tube,
            key: 5,
            translate: [0.0, 0.0, 1.0],
            rotate: [0.0, 0.0, 0.0, 1.0],
            mode: KeyMode::Independent,
        },
    ]
}

#[test]
fn keep_length_holds_the_chord_length_through_bends_twists_and_drags() {
    let tube = Tube { rings: 40, around: 16, length: 4.0, radius: 0.3 };
    let rig = tube_rig(&tube, 8, 16);
    let rest = chord_length(&rig.sweeps()[0].keys);
    let mut kept = Posing::new(&rig);
    kept.keep_length = true;
    let mut stretched = Posing::new(&rig);
    let mut largest_change: f64 = 0.0;
    for (i, edit) in edits().iter().enumerate() {
        kept.apply(edit).unwrap();
        stretched.apply(edit).unwrap();
        let (length, free) = (chord_length(&kept.keys()[0]), chord_length(&stretched.keys()[0]));
        eprintln!("edit {i} ({}): chord length {length:.9} kept, {free:.6} stretched, rest {rest:.6}", edit.op());
        assert!(((length - rest) / rest).abs() <= 1e-6, "edit {i} ({}): {length} against {rest}", edit.op());
        largest_change = largest_change.max(((free - rest) / rest).abs());
    }
    assert!(largest_change > 0.05, "the edits stretch the tube without keep-length: {largest_change}");
}
