//! Fig. 3 of the paper: fitting a control sweep to the armadillo's leg, from the rough
//! enclosing sweep to the tight one, with the fit quality and a picture at each step.
//!
//! `cargo run --release --example armadillo_leg [OUT_DIR]` (needs ../shared/meshes).

mod common;

use std::time::Instant;

use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::mesh::Mesh;
use sweepffd::rig::{Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Sweep;

fn main() {
    let Some(path) = common::shared_mesh("armadillo_50k.obj") else {
        println!("this example needs it; nothing to do");
        return;
    };
    let out = common::Output::new("armadillo_leg");
    let mesh = Mesh::load(&path).unwrap_or_else(|e| panic!("{e}"));
    // The leg on the −x side, from the hip (y = −8) to the ankle (y = −44).
    let leg = largest_connected(&mesh, |p| p.x < -5.0 && p.y < -8.0 && p.y > -44.0);
    let started = Instant::now();
    let fitted = fit(&mesh, &leg, &FitOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    println!("fitted the leg ({} vertices) in {:.3} s", leg.len(), started.elapsed().as_secs_f64());
    for (i, step) in fitted.steps.iter().enumerate() {
        let q = step.quality;
        println!(
            "  step {i}: {} ({} keys): |d| / mean radius max {:.1}%, RMS {:.2}%, {} vertices beyond the ends",
            step.label,
            step.keys.len(),
            100.0 * q.max_d,
            100.0 * q.rms_d,
            q.without_root
        );
        let sweep = Sweep::try_new(&step.keys, None).unwrap_or_else(|e| panic!("{e}"));
        out.picture(&format!("step{i}.png"), &mesh, &[(&mesh.positions, &[sweep])], (270.0, 5.0));
    }

    let rig = Rig::new(vec![RigSweep {
        name: "leg".into(),
        vertices: Some(VertexSelection::Indices(leg)),
        keys: fitted.keys.clone(),
        knots: None,
        parent: None,
        falloff: fitted.falloff,
        rotation: Default::default(),
    }])
    .unwrap_or_else(|e| panic!("{e}"));
    out.rig("leg-rig.json", &rig, &rig.sweeps().iter().map(|s| s.keys.clone()).collect::<Vec<_>>());
}
