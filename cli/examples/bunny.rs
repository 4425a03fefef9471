//! Fig. 6 and Fig. 14 of the paper on the Stanford bunny: control sweeps fitted to both ears,
//! the ears bent and twisted, then direct point control of an ear tip with translation only
//! and with rotation only.
//!
//! `cargo run --release --example bunny [OUT_DIR]` (needs ../shared/meshes).

mod common;

use glam::{DQuat, DVec3};
use sweepffd::edit::{DragMode, Edit, KeyMode, Posing};
use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::formats::LoadedMesh;
use sweepffd::rig::{Rig, RigSweep, VertexSelection};

/// Which vertices make up a part, by position.
type PartTest = fn(DVec3) -> bool;

fn main() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else {
        println!("this example needs it; nothing to do");
        return;
    };
    let out = common::Output::new("bunny");
    let scan = LoadedMesh::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let mesh = &scan.mesh;
    let parts: [(&str, PartTest); 2] = [
        ("front_ear", |p| p.z < -0.012 && p.x < -0.055 && p.y > 0.13),
        ("back_ear", |p| p.x > -0.055 && p.x < 0.0 && p.y > 0.148 && p.z < 0.01),
    ];
    let mut sweeps = Vec::new();
    for (name, inside) in parts {
        let vertices = largest_connected(mesh, inside);
        let fitted = fit(mesh, &vertices, &FitOptions::default()).unwrap_or_else(|e| panic!("{e}"));
        let q = fitted.quality;
        println!(
            "fitted {name}: {} vertices, {} keys, |d| / mean radius max {:.1}%, RMS {:.2}%, falloff {:.4}",
            vertices.len(),
            fitted.keys.len(),
            100.0 * q.max_d,
            100.0 * q.rms_d,
            fitted.falloff
        );
        sweeps.push(RigSweep {
            name: name.into(),
            vertices: Some(VertexSelection::Indices(vertices)),
            keys: fitted.keys,
            knots: None,
            parent: None,
            // The default falloff: the ears fade into the head instead of tearing from it.
            falloff: fitted.falloff,
            rotation: Default::default(),
        });
    }
    let rig = Rig::new(sweeps).unwrap_or_else(|e| panic!("{e}"));
    let rest_keys: Vec<_> = rig.sweeps().iter().map(|s| s.keys.clone()).collect();
    out.rig("ears-rig.json", &rig, &rest_keys);
    out.picture("ears-fitted.png", mesh, &[(&mesh.positions, rig.rest())], (60.0, 35.0));

    // Fig. 6: bend both ears forward from their middle key and twist the back one.
    let mut posing = Posing::new(&rig);
    for (name, angle) in [("front_ear", 0.5), ("back_ear", -0.6)] {
        let s = rig.sweep_index(name).expect("fitted above");
        let middle = rig.sweeps()[s].keys.len() / 2;
        let axis = rig.sweeps()[s].keys[middle].rotation * DVec3::X;
        let edit = Edit::MoveKey {
            sweep: name.into(),
            key: middle,
            translate: [0.0; 3],
            rotate: DQuat::from_axis_angle(axis, angle).to_array(),
            mode: KeyMode::Local,
        };
        posing.apply(&edit).unwrap_or_else(|e| panic!("{e}"));
    }
    let back = rig.sweep_index("back_ear").expect("fitted above");
    let last = rig.sweeps()[back].keys.len() - 1;
    let twist_axis = rig.sweeps()[back].keys[last].rotation * DVec3::Z;
    let twist = Edit::MoveKey {
        sweep: "back_ear".into(),
        key: last,
        translate: [0.0; 3],
        rotate: DQuat::from_axis_angle(twist_axis, 0.8).to_array(),
        mode: KeyMode::Independent,
    };
    posing.apply(&twist).unwrap_or_else(|e| panic!("{e}"));
    let posed = posing.sweeps().unwrap_or_else(|e| panic!("{e}"));
    let bent = common::deform(&rig, mesh, &posed);
    println!(
        "bent and twisted the ears: largest vertex move {:.4}, largest edge stretch {:.2} (the ears stay attached)",
        common::largest_move(&mesh.positions, &bent),
        common::largest_edge_stretch(mesh, &bent)
    );
    out.mesh("ears-bent.obj", &scan, &bent);
    out.picture("ears-bent.png", mesh, &[(&mesh.positions, rig.rest()), (&bent, &posed)], (60.0, 35.0));

    // Fig. 14: drag the front ear's tip point (θ = 0, t = 0.95) to the same target, once by
    // translating keys only and once by rotating the key below it only. The target is where
    // the point goes when that key turns, so rotation alone can reach it.
    let front = rig.sweep_index("front_ear").expect("fitted above");
    let below = rig.rest()[front].knots().partition_point(|&u| u <= 0.95) - 1;
    let mut turned = Posing::new(&rig);
    let key = &rig.sweeps()[front].keys[below];
    let turn = Edit::MoveKey {
        sweep: "front_ear".into(),
        key: below,
        translate: [0.0; 3],
        rotate: DQuat::from_axis_angle(key.rotation * DVec3::Y, 0.3).to_array(),
        mode: KeyMode::Local,
    };
    turned.apply(&turn).unwrap_or_else(|e| panic!("{e}"));
    let target = turned.sweeps().unwrap_or_else(|e| panic!("{e}"))[front].surface_point(0.0, 0.95);
    for (mode, keys, file) in [(DragMode::Translate, 3, "drag-translate"), (DragMode::Rotate, 1, "drag-rotate")] {
        let mut posing = Posing::new(&rig);
        let drag = Edit::DragPoint {
            sweep: "front_ear".into(),
            theta: 0.0,
            t: 0.95,
            d: 0.0,
            h: 0.0,
            to: target.to_array(),
            mode,
            keys,
        };
        match posing.apply(&drag) {
            Ok(rounds) => {
                let posed = posing.sweeps().unwrap_or_else(|e| panic!("{e}"));
                let reached = posed[front].surface_point(0.0, 0.95).distance(target);
                println!("dragged the front ear's tip ({mode:?}): {rounds} rounds, {reached:.2e} from the target");
                let moved = common::deform(&rig, mesh, &posed);
                out.mesh(&format!("{file}.obj"), &scan, &moved);
                out.picture(
                    &format!("{file}.png"),
                    mesh,
                    &[(&mesh.positions, rig.rest()), (&moved, &posed)],
                    (60.0, 35.0),
                );
            }
            Err(e) => println!("dragging the front ear's tip ({mode:?}) could not reach the target: {e}"),
        }
    }
}
