//! Interactive editing on the Newell teapot rig (body the root, the spout a branch, the handle a
//! loop): one edit including hierarchy propagation and the `total` volume rule, on the CPU.
//!
//! `cargo bench --bench edit`. Needs `../shared/meshes/teapot_newell_parts.obj`; without it the
//! bench prints a notice and measures nothing.

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use glam::DQuat;
use sweepffd::edit::{Edit, Posing, VolumeRule};
use sweepffd::mesh::Mesh;

fn edits() -> [(&'static str, Edit); 4] {
    [
        (
            "drag_point handle (loop: moves the body, the spout follows)",
            Edit::DragPoint {
                sweep: "handle".into(),
                theta: 0.0,
                t: 0.5,
                d: 0.0,
                h: 0.0,
                to: [-1.85, 1.55, 0.1],
                mode: Default::default(),
                keys: 2,
            },
        ),
        (
            "drag_point body (the handle and spout follow)",
            Edit::DragPoint {
                sweep: "body".into(),
                theta: 0.0,
                t: 0.8,
                d: 0.0,
                h: 0.0,
                to: [1.6, 2.0, 0.2],
                mode: Default::default(),
                keys: 2,
            },
        ),
        (
            "move_section spout",
            Edit::MoveSection {
                sweep: "spout".into(),
                t: 0.7,
                translate: [0.0, 0.15, 0.05],
                rotate: DQuat::from_rotation_z(0.1).to_array(),
            },
        ),
        (
            "move_section handle (loop: moves the body)",
            Edit::MoveSection {
                sweep: "handle".into(),
                t: 0.5,
                translate: [-0.1, 0.05, 0.0],
                rotate: DQuat::from_rotation_z(0.05).to_array(),
            },
        ),
    ]
}

fn editing(c: &mut Criterion) {
    let Some(path) = common::shared_mesh("teapot_newell_parts.obj") else { return };
    let mesh = Mesh::load(&path).expect("the teapot loads");
    let rig = common::teapot_rig(&mesh);
    let mut group = c.benchmark_group("edit on the teapot, hierarchy + total volume rule");
    for (name, edit) in edits() {
        let mut posing = Posing::new(&rig);
        posing.volume = VolumeRule::Total;
        let rounds = posing.clone().apply(&edit).unwrap_or_else(|e| panic!("{name}: {e}"));
        println!("{name}: converges in {rounds} rounds");
        group.bench_function(name, |b| {
            b.iter_batched_ref(|| posing.clone(), |p| p.apply(&edit).unwrap(), BatchSize::SmallInput)
        });
    }
    group.finish();
}

criterion_group!(benches, editing);
criterion_main!(benches);
