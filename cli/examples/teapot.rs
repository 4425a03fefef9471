//! Fig. 1, 12, 13 and 15 of the paper on the Utah teapot: a body/spout/handle hierarchy (the
//! spout a branch of the body, the handle a loop), a body edit and a handle edit carried
//! through the hierarchy, the broken teapot when the hierarchy is off, the total and ratio
//! volume rules, and a local radius edit.
//!
//! `cargo run --release --example teapot [OUT_DIR]` (needs ../shared/meshes).

mod common;
#[path = "../../tests/common/teapot.rs"]
mod rigs;

use glam::{DQuat, DVec3};
use sweepffd::edit::{DragMode, Edit, KeyMode, Posing, VolumeRule};
use sweepffd::formats::LoadedMesh;
use sweepffd::rig::Rig;

const VIEW: (f32, f32) = (20.0, 20.0);

fn main() {
    let Some(path) = common::shared_mesh("teapot_newell_parts.obj") else {
        println!("this example needs it; nothing to do");
        return;
    };
    let out = common::Output::new("teapot");
    let file = LoadedMesh::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let mesh = &file.mesh;
    let rig = rigs::teapot_rig(mesh);
    out.rig("teapot-rig.json", &rig, &rig.sweeps().iter().map(|s| s.keys.clone()).collect::<Vec<_>>());
    out.picture("rest.png", mesh, &[(&mesh.positions, rig.rest())], VIEW);

    // Fig. 1b: bend and widen the body; the spout and handle ride along.
    let body_edit = [
        Edit::ScaleRadii { sweep: "body".into(), key: 3, factor: 1.25, theta_range: None },
        Edit::MoveKey {
            sweep: "body".into(),
            key: 4,
            translate: [0.3, 0.0, 0.0],
            rotate: DQuat::from_rotation_z(-0.25).to_array(),
            mode: KeyMode::Local,
        },
    ];
    let with_hierarchy = pose(&out, &rig, &file, "body-edit", &body_edit, true, VolumeRule::None);
    // Fig. 12: the same edit with the hierarchy off tears the spout and handle off the body.
    let without = pose(&out, &rig, &file, "body-edit-no-hierarchy", &body_edit, false, VolumeRule::None);
    println!(
        "  the hierarchy keeps the parts together: detached by {:.3} without it",
        common::largest_move(&with_hierarchy, &without)
    );

    // Fig. 1c: drag a point of the handle; the body bends to keep it attached.
    let handle_point = rig.rest()[2].surface_point(0.0, 0.5);
    let drag = [Edit::DragPoint {
        sweep: "handle".into(),
        theta: 0.0,
        t: 0.5,
        d: 0.0,
        h: 0.0,
        to: (handle_point + DVec3::new(-0.15, 0.1, 0.0)).to_array(),
        mode: DragMode::Both,
        keys: 2,
    }];
    pose(&out, &rig, &file, "handle-edit", &drag, true, VolumeRule::None);

    // Fig. 13: squeeze the body under each volume rule.
    let squeeze: Vec<Edit> =
        (3..4).map(|key| Edit::ScaleRadii { sweep: "body".into(), key, factor: 0.95, theta_range: None }).collect();
    for rule in [VolumeRule::None, VolumeRule::Total, VolumeRule::Ratio] {
        let name = format!("squeeze-{}", format!("{rule:?}").to_lowercase());
        pose(&out, &rig, &file, &name, &squeeze, true, rule);
    }

    // Fig. 15: a local radius edit, a bump over a range of θ on one body key.
    let bump = [Edit::ScaleRadii { sweep: "body".into(), key: 3, factor: 1.4, theta_range: Some([0.5, 2.0]) }];
    pose(&out, &rig, &file, "local-radius-edit", &bump, true, VolumeRule::None);
}

/// Applies `edits` with the hierarchy on or off and the volume rule `rule`, prints the sweeps'
/// volumes, and writes the deformed mesh, the pose and a rest/pose picture named `name`.
fn pose(
    out: &common::Output,
    rig: &Rig,
    file: &LoadedMesh,
    name: &str,
    edits: &[Edit],
    hierarchy: bool,
    rule: VolumeRule,
) -> Vec<DVec3> {
    let mesh = &file.mesh;
    let mut posing = Posing::new(rig);
    posing.hierarchy = hierarchy;
    posing.volume = rule;
    for edit in edits {
        posing.apply(edit).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    let posed = posing.sweeps().unwrap_or_else(|e| panic!("{e}"));
    let volumes: Vec<String> = rig
        .sweeps()
        .iter()
        .zip(rig.rest().iter().zip(&posed))
        .map(|(s, (rest, posed))| format!("{} {:.3} -> {:.3}", s.name, rest.volume(), posed.volume()))
        .collect();
    println!(
        "{name} (hierarchy {}, volume rule {rule:?}): {}",
        if hierarchy { "on" } else { "off" },
        volumes.join(", ")
    );
    let deformed = common::deform(rig, mesh, &posed);
    out.mesh(&format!("{name}.obj"), file, &deformed);
    out.rig(&format!("{name}-pose.json"), rig, posing.keys());
    out.picture(&format!("{name}.png"), mesh, &[(&mesh.positions, rig.rest()), (&deformed, &posed)], VIEW);
    deformed
}
