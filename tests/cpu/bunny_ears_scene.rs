//! The engine scene of issue 13's figure: the Stanford bunny subdivided to 1M vertices with its
//! two ears fitted as sweeps (about 3 % of the vertices), written for `sweepffd bench --mesh
//! --rig`, which then measures the frame on the bound vertices only. An ignored test, run by
//! hand:
//!
//! ```text
//! SWEEPFFD_SCENE_DIR=DIR cargo test --release --test bunny_ears_scene -- --ignored --nocapture
//! sweepffd bench --mesh DIR/bunny_1m.obj --rig DIR/ears.json --json
//! ```

use crate::common;

use std::path::PathBuf;

use glam::DVec3;
use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::rig::{FORMAT, RigDocument, VERSION, VertexSelection};

fn front_ear(p: DVec3) -> bool {
    p.z < -0.012 && p.x < -0.055 && p.y > 0.13
}

fn back_ear(p: DVec3) -> bool {
    p.x > -0.055 && p.x < 0.0 && p.y > 0.148 && p.z < 0.01
}

#[test]
#[ignore = "writes the 1M-vertex bunny scene for the bench; set SWEEPFFD_SCENE_DIR"]
fn write_the_million_vertex_bunny_with_fitted_ears() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let dir = PathBuf::from(std::env::var("SWEEPFFD_SCENE_DIR").expect("SWEEPFFD_SCENE_DIR names the output folder"));
    let bunny = Mesh::load(&path).unwrap();
    let (mesh, steps) = bunny.subdivided_to(1_000_000).unwrap();
    let mut sweeps = Vec::new();
    for (name, inside) in [("front_ear", front_ear as fn(DVec3) -> bool), ("back_ear", back_ear)] {
        // Fitted on the scan, owning the ear's vertices carried through the subdivisions.
        let ear = largest_connected(&bunny, inside);
        let fitted = fit(&bunny, &ear, &FitOptions::default()).unwrap();
        let owned = steps.iter().fold(ear, |owned, step| step.carry(&owned));
        println!(
            "{name}: {} keys, RMS |d| {:.3}, {} of {} vertices",
            fitted.keys.len(),
            fitted.quality.rms_d,
            owned.len(),
            mesh.positions.len()
        );
        sweeps.push(fitted.sweep_document(name.into(), VertexSelection::Indices(owned), None));
    }
    let rig = RigDocument { format: FORMAT.into(), version: VERSION, rotation_interpolation: None, sweeps };
    std::fs::write(dir.join("ears.json"), rig.to_json()).unwrap();
    let file = LoadedMesh::from(mesh);
    file.save(&dir.join("bunny_1m.obj"), &file.mesh.positions).unwrap();
}
