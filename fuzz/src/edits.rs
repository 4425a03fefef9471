//! Target `edits`: an edits file applied to the scene's rig as `sweepffd pose` applies it.
//!
//! A leading digit picks the volume rule (`0` none, `1` total, `2` ratio, `3` mesh, with the
//! scene's tube as the mesh); without one the rule is none. The pose that would be written must
//! be one that `deform` accepts.

use sweepffd::edit::{BoundMesh, Posing, VolumeRule, parse_edits};
use sweepffd::rig::RigDocument;

use super::Outcome;
use super::scene::scene;

/// The name the edits input goes by in errors.
pub const EDITS_FILE: &str = "edits.json";

/// Applies the edits `data` (after an optional rule digit) to the scene's rig.
pub fn edits(data: &[u8]) -> Outcome {
    let (volume, data) = match data.first() {
        Some(digit @ b'0'..=b'9') => {
            let rules = [VolumeRule::None, VolumeRule::Total, VolumeRule::Ratio, VolumeRule::Mesh];
            (rules[usize::from(digit - b'0') % rules.len()], &data[1..])
        }
        _ => (VolumeRule::None, data),
    };
    let text = std::str::from_utf8(data)
        .map_err(|_| format!("cannot read {EDITS_FILE}: stream did not contain valid UTF-8"))?;
    let edits = parse_edits(text).map_err(|e| format!("{EDITS_FILE}: not a valid edits file: {e}"))?;
    let scene = scene();
    let mut posing = Posing::new(&scene.rig);
    posing.volume = volume;
    if volume == VolumeRule::Mesh {
        posing = posing.with_mesh(BoundMesh { mesh: &scene.mesh, bindings: &scene.bindings });
    }
    for (i, edit) in edits.iter().enumerate() {
        posing.apply(edit).map_err(|e| {
            format!("{EDITS_FILE}: edit {i} ({} on {:?}): {e}; nothing was written", edit.op(), edit.sweep())
        })?;
    }
    let written = scene.rig.pose_document(posing.keys()).to_json();
    let read_back = RigDocument::parse(&written).expect("a written pose parses");
    if let Err(e) = scene.rig.pose_from_document(&read_back, None) {
        panic!("the pose written after the edits is refused ({e}):\n{written}");
    }
    Ok(())
}
