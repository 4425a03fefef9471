//! `sweepffd deform`: pose the rig, move the bound vertices (Eq. 2), write the mesh.

use std::path::PathBuf;
use std::time::Instant;

use glam::DVec3;

use super::CliResult;
use super::bind::{bind_with_progress, load_inputs};
use sweepffd::bind::UNOWNED;
use sweepffd::bind::file::BindingsFile;
use sweepffd::deform::deform_vertices;
use sweepffd::mesh::Format;

pub struct Args {
    pub mesh: PathBuf,
    pub rig: PathBuf,
    pub pose: PathBuf,
    pub out: PathBuf,
    pub bindings: Option<PathBuf>,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    // Refuse an unsupported output before any work is done.
    Format::of(&args.out)?;
    let inputs = load_inputs(&args.mesh, &args.rig)?;
    let posed = inputs.rig.load_pose(&args.pose)?;
    let start = Instant::now();
    let bindings = match &args.bindings {
        Some(path) => {
            let file = BindingsFile::load(path)?;
            file.check_matches(&inputs.rig, &inputs.mesh.positions, path)?;
            file.bindings
        }
        None => bind_with_progress(&inputs, quiet),
    };
    let bind_seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let mut positions = vec![DVec3::ZERO; inputs.mesh.positions.len()];
    deform_vertices(&posed, &bindings, &inputs.mesh.positions, &mut positions);
    let deform_seconds = start.elapsed().as_secs_f64();
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        let sweep = &inputs.rig.sweeps()[bindings[i].sweep as usize].name;
        return Err(format!("{}: vertex index {i} (sweep {sweep:?}) deforms to a non-finite position; nothing was written", args.pose.display()).into());
    }
    inputs.mesh.save(&args.out, &positions)?;
    if !quiet {
        let owned = bindings.iter().filter(|b| b.sweep != UNOWNED).count();
        let source = if args.bindings.is_some() {
            "loaded"
        } else {
            "bound"
        };
        println!(
            "deformed {owned} of {} vertices ({source} in {bind_seconds:.3} s, deformed in {deform_seconds:.3} s) -> {}",
            positions.len(),
            args.out.display()
        );
    }
    Ok(())
}
