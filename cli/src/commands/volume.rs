//! `sweepffd volume`: each sweep's volume by Eq. 1, as JSON on stdout.

use std::path::PathBuf;

use serde::Serialize;

use super::CliResult;
use super::args::RigArg;
use sweepffd::rig::Rig;

/// The arguments of `sweepffd volume`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub rig: RigArg,
    /// Measure this pose of the rig instead of its rest keys.
    #[arg(long)]
    pub pose: Option<PathBuf>,
}

#[derive(Serialize)]
struct Report<'a> {
    sweeps: Vec<SweepVolume<'a>>,
    total: f64,
}

#[derive(Serialize)]
struct SweepVolume<'a> {
    name: &'a str,
    volume: f64,
}

pub fn run(args: &Args) -> CliResult {
    let rig = Rig::load(&args.rig.rig)?;
    let sweeps = match &args.pose {
        Some(pose) => rig.load_pose(pose)?,
        None => rig.rest().to_vec(),
    };
    let volumes: Vec<SweepVolume> = rig
        .sweeps()
        .iter()
        .zip(&sweeps)
        .map(|(sweep, surface)| SweepVolume { name: &sweep.name, volume: surface.volume() })
        .collect();
    if let Some(bad) = volumes.iter().find(|v| !v.volume.is_finite()) {
        let file = args.pose.as_ref().unwrap_or(&args.rig.rig).display();
        return Err(format!("{file}: sweep {:?}: the volume (Eq. 1) is not a finite number", bad.name).into());
    }
    let total: f64 = volumes.iter().map(|v| v.volume).sum();
    if !total.is_finite() {
        return Err(format!(
            "{}: the total volume is not a finite number",
            args.pose.as_ref().unwrap_or(&args.rig.rig).display()
        )
        .into());
    }
    out!("{}", serde_json::to_string(&Report { sweeps: volumes, total })?);
    Ok(())
}
