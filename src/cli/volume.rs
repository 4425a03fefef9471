//! `sweepffd volume`: each sweep's volume by Eq. 1, as JSON on stdout.

use std::path::Path;

use serde::Serialize;

use super::CliResult;
use sweepffd::rig::Rig;

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

pub fn run(rig_path: &Path, pose: Option<&Path>) -> CliResult {
    let rig = Rig::load(rig_path)?;
    let sweeps = match pose {
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
        let file = pose.unwrap_or(rig_path).display();
        return Err(format!("{file}: sweep {:?}: the volume (Eq. 1) is not a finite number", bad.name).into());
    }
    let total: f64 = volumes.iter().map(|v| v.volume).sum();
    if !total.is_finite() {
        return Err(format!("{}: the total volume is not a finite number", pose.unwrap_or(rig_path).display()).into());
    }
    println!("{}", serde_json::to_string(&Report { sweeps: volumes, total })?);
    Ok(())
}
