//! `sweepffd export`: a mesh, its rig and poses as one glTF animation, each pose a morph target
//! played in order (`sweepffd::formats::save_morph_animation`), the mesh bound once.

use std::path::PathBuf;
use std::time::Instant;

use glam::DVec3;

use super::CliResult;
use super::args::{MeshArg, RigArg};
use super::backend::{Backend, resolve};
use super::bind::load_inputs;
use super::deform::{BoundMesh, non_finite, warn_of_folds};
use sweepffd::formats::{MorphPose, save_morph_animation};

/// The arguments of `sweepffd export`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub mesh: MeshArg,
    #[command(flatten)]
    pub rig: RigArg,
    /// The poses, in the order the animation plays them (each a morph target named by its
    /// file's stem).
    #[arg(long, num_args = 1.., required = true)]
    pub poses: Vec<PathBuf>,
    /// Seconds from one pose to the next.
    #[arg(long, default_value_t = 1.0)]
    pub seconds_per_pose: f64,
    /// Where to write the animation (.glb, or .gltf with its buffer embedded).
    #[arg(long)]
    pub out: PathBuf,
    /// Where to bind and deform, as for `deform`.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    pub backend: Backend,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    if !(args.seconds_per_pose.is_finite() && args.seconds_per_pose > 0.0) {
        return Err(format!("--seconds-per-pose must be positive and finite, not {}", args.seconds_per_pose).into());
    }
    if !args.out.extension().is_some_and(|e| e.eq_ignore_ascii_case("glb") || e.eq_ignore_ascii_case("gltf")) {
        return Err(format!("{}: an animation is written as .glb or .gltf", args.out.display()).into());
    }
    let inputs = load_inputs(&args.mesh.mesh, &args.rig.rig)?;
    let device = resolve(args.backend, quiet)?;
    let start = Instant::now();
    let mut bound = BoundMesh::new(&inputs, &device, None, quiet)?;
    let mut deformed: Vec<Vec<DVec3>> = Vec::with_capacity(args.poses.len());
    for path in &args.poses {
        let posed = inputs.rig.load_pose(path)?;
        warn_of_folds(&inputs, &posed, path);
        let (positions, owners) = bound.deform(&posed)?;
        if let Some(error) = non_finite(&inputs, &positions, &owners, path) {
            return Err(format!("{error}; nothing was written").into());
        }
        deformed.push(positions);
    }
    let names: Vec<String> = args
        .poses
        .iter()
        .map(|p| p.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned()))
        .collect();
    let poses: Vec<MorphPose> =
        names.iter().zip(&deformed).map(|(name, positions)| MorphPose { name, positions }).collect();
    save_morph_animation(&args.out, &inputs.file, &poses, args.seconds_per_pose)?;
    if !quiet {
        out!(
            "exported {} poses of {} vertices as morph targets, {} s apart, in {:.3} s -> {}",
            poses.len(),
            inputs.file.mesh.positions.len(),
            args.seconds_per_pose,
            start.elapsed().as_secs_f64(),
            args.out.display()
        );
    }
    Ok(())
}
