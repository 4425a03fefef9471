//! Fig. 16 of the paper: a chair's legs joined by virtual sweeps, so that moving one leg
//! moves the legs it is joined to. Fitted to `chair.off` from ../shared/meshes when present,
//! else to a procedural chair (a seat on four round legs), so the example runs anywhere.
//!
//! `cargo run --release --example chair [OUT_DIR]`

mod common;

use std::f64::consts::PI;

use glam::{DQuat, DVec3};
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::{Faces, Mesh};
use sweepffd::rig::{LinkKind, ParentLink, Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Key;
use sweepffd::synthetic::Tube;

fn main() {
    let out = common::Output::new("chair");
    let file = match common::shared_mesh("chair.off") {
        Some(path) => LoadedMesh::load(&path).unwrap_or_else(|e| panic!("{e}")),
        None => {
            println!("using a procedural chair instead");
            LoadedMesh::from(procedural_chair())
        }
    };
    let mesh = &file.mesh;
    let (lo, hi) = mesh.bounds();
    let size = hi - lo;
    // The legs: the four largest connected pieces of the chair's lower third, in order
    // around its vertical axis.
    let low = |p: DVec3| (p.y - lo.y) / size.y < 0.3;
    let bits = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut taken = std::collections::HashSet::new();
    let mut pieces: Vec<Vec<u32>> = Vec::new();
    for _ in 0..4 {
        let piece = largest_connected(mesh, |p| low(p) && !taken.contains(&bits(p)));
        taken.extend(piece.iter().map(|&v| bits(mesh.positions[v as usize])));
        pieces.push(piece);
    }
    let middle = (lo + hi) * 0.5;
    let angle = |piece: &[u32]| {
        let c = piece.iter().map(|&v| mesh.positions[v as usize]).sum::<DVec3>() / piece.len() as f64 - middle;
        c.z.atan2(c.x)
    };
    pieces.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
    let mut legs = Vec::new();
    for (name, vertices, top_first) in [("leg_a", false), ("leg_b", true), ("leg_c", true), ("leg_d", false)]
        .into_iter()
        .zip(pieces)
        .map(|((name, top_first), vertices)| (name, vertices, top_first))
    {
        let fitted = fit(mesh, &vertices, &FitOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        println!(
            "fitted {name}: {} vertices, {} keys, RMS |d| {:.2}% of the mean radius",
            vertices.len(),
            fitted.keys.len(),
            100.0 * fitted.quality.rms_d
        );
        // A leg hung from a bar starts at its top, where the bar binds it.
        let keys = oriented(fitted.keys, top_first);
        legs.push((name, vertices, keys));
    }
    let top = |keys: &[Key]| keys.iter().map(|k| k.center).max_by(|a, b| a.y.total_cmp(&b.y)).expect("keys");
    let bar = |from: DVec3, to: DVec3| -> Vec<Key> {
        let direction = (to - from).normalize();
        let rotation = DQuat::from_rotation_arc(DVec3::Z, direction);
        let length = from.distance(to) * 1.3;
        (0..3).map(|i| Key::circle(from + direction * (length * i as f64 / 2.0), rotation, 0.01 * size.y, 8)).collect()
    };
    // The bars start a little below the top of the leg they hang from, inside its sweep.
    let below_top = |keys: &[Key]| top(keys) - DVec3::Y * 0.02 * size.y;
    let front = bar(below_top(&legs[0].2), top(&legs[1].2));
    let side = bar(below_top(&legs[1].2), top(&legs[2].2));
    let sweep = |name: &str, vertices: Option<Vec<u32>>, keys: Vec<Key>, parent: Option<&str>| RigSweep {
        name: name.into(),
        vertices: vertices.map(VertexSelection::Indices),
        keys,
        knots: None,
        parent: parent.map(|p| ParentLink { sweep: p.into(), kind: LinkKind::Branch }),
        falloff: 0.0,
        rotation: Default::default(),
    };
    let [a, b, c, d] = legs.try_into().unwrap_or_else(|_| unreachable!("four legs"));
    let rig = Rig::new(vec![
        sweep(a.0, Some(a.1), a.2, None),
        sweep("front", None, front, Some("leg_a")),
        sweep(b.0, Some(b.1), b.2, Some("front")),
        sweep("side", None, side, Some("leg_b")),
        sweep(c.0, Some(c.1), c.2, Some("side")),
        sweep(d.0, Some(d.1), d.2, None),
    ])
    .unwrap_or_else(|e| panic!("{e}"));
    out.rig("chair-rig.json", &rig, &rig.sweeps().iter().map(|s| s.keys.clone()).collect::<Vec<_>>());

    // Move leg A: legs B and C follow through the virtual sweeps; leg D, joined to nothing,
    // stays.
    let mut posing = Posing::new(&rig);
    let shift = DVec3::new(-0.08 * size.x, 0.0, -0.05 * size.z);
    let leg_a_top = rig.sweeps()[0].keys.len() - 1;
    let edit = Edit::MoveKey {
        sweep: "leg_a".into(),
        key: leg_a_top,
        translate: shift.to_array(),
        rotate: DQuat::IDENTITY.to_array(),
        mode: KeyMode::Local,
    };
    posing.apply(&edit).unwrap_or_else(|e| panic!("{e}"));
    for (s, sweep) in rig.sweeps().iter().enumerate() {
        let moved = posing.keys()[s][0].center - sweep.keys[0].center;
        println!("  {} moved by {:.4}", sweep.name, moved.length());
    }
    let posed = posing.sweeps().unwrap_or_else(|e| panic!("{e}"));
    let deformed = common::deform(&rig, mesh, &posed);
    out.mesh("chair-moved.obj", &file, &deformed);
    out.rig("chair-pose.json", &rig, posing.keys());
    out.picture("chair.png", mesh, &[(&mesh.positions, rig.rest()), (&deformed, &posed)], (30.0, 15.0));
}

/// The keys from the bottom up, or from the top down when `top_first`; a reversed key is
/// turned half a turn about its x axis so its normal still points along the sweep.
fn oriented(mut keys: Vec<Key>, top_first: bool) -> Vec<Key> {
    let starts_at_top = keys[0].center.y > keys[keys.len() - 1].center.y;
    if starts_at_top != top_first {
        keys.reverse();
        for key in &mut keys {
            key.rotation *= DQuat::from_rotation_x(PI);
        }
    }
    keys
}

/// A seat (a box 1 × 0.08 × 1 at height 0.5) on four round legs of radius 0.05.
fn procedural_chair() -> Mesh {
    let mut positions = Vec::new();
    let mut faces = Faces::new();
    let leg = Tube { rings: 24, around: 16, length: 0.5, radius: 0.05 }.mesh();
    let stand = DQuat::from_rotation_arc(DVec3::Z, DVec3::Y);
    for (x, z) in [(0.1, 0.1), (0.9, 0.1), (0.9, 0.9), (0.1, 0.9)] {
        let base = positions.len() as u32;
        positions.extend(leg.positions.iter().map(|&p| stand * p + DVec3::new(x, 0.0, z)));
        for face in leg.faces.iter() {
            faces.push(&face.iter().map(|&v| v + base).collect::<Vec<_>>());
        }
    }
    let base = positions.len() as u32;
    for &(x, y, z) in &[(0.0, 0.5, 0.0), (1.0, 0.5, 0.0), (1.0, 0.5, 1.0), (0.0, 0.5, 1.0)] {
        positions.push(DVec3::new(x, y, z));
    }
    for &(x, y, z) in &[(0.0, 0.58, 0.0), (1.0, 0.58, 0.0), (1.0, 0.58, 1.0), (0.0, 0.58, 1.0)] {
        positions.push(DVec3::new(x, y, z));
    }
    for quad in [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]] {
        faces.push(&quad.map(|v| v + base));
    }
    Mesh::from_parts(positions, faces, Vec::new()).expect("the procedural chair is valid")
}
