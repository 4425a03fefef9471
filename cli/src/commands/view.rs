//! `sweepffd view`: the interactive viewer ([`crate::view`]); with `--script`, a replayed
//! session whose report (frame times, screenshots) is printed as JSON.

use std::io::Write;
use std::path::PathBuf;

use super::CliResult;
use super::args::MeshArg;
use super::render;
use super::volume_rule::VolumeArg;
use crate::view::{Subdivide, ViewOptions, run};
use sweepffd::atomic_file::write_atomically;

/// The arguments of `sweepffd view`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub mesh: MeshArg,
    /// The rest rig (JSON); without it, fit sweeps to parts picked in the window.
    #[arg(long)]
    pub rig: Option<PathBuf>,
    /// Start from this pose of the rig.
    #[arg(long)]
    pub pose: Option<PathBuf>,
    /// Levels of midpoint subdivision of the mesh (each about quadruples the vertices; the
    /// rig's vertex indices are carried along).
    #[arg(long, conflicts_with = "subdivide_to")]
    pub subdivide: Option<usize>,
    /// Subdivide the mesh to exactly this many vertices (midpoint levels, then centroid splits).
    #[arg(long)]
    pub subdivide_to: Option<usize>,
    /// The volume rule to start with.
    #[arg(long, value_enum, default_value_t = VolumeArg::None)]
    pub volume: VolumeArg,
    /// Window size WIDTHxHEIGHT in pixels.
    #[arg(long, default_value = "1280x800", value_parser = render::parse_size)]
    pub size: (u32, u32),
    /// Where Ctrl+S saves the pose (the panel can change it).
    #[arg(long, default_value = "pose.json")]
    pub save_pose: PathBuf,
    /// Replay this script of input events and screenshots, print a JSON report, and exit.
    #[arg(long)]
    pub script: Option<PathBuf>,
    /// Also write the script's report to this file.
    #[arg(long, requires = "script")]
    pub report: Option<PathBuf>,
}

impl Args {
    /// The viewer's options.
    fn options(&self) -> ViewOptions {
        let subdivide = match (self.subdivide, self.subdivide_to) {
            (Some(levels), _) => Subdivide::Levels(levels),
            (None, Some(vertices)) => Subdivide::Vertices(vertices),
            (None, None) => Subdivide::No,
        };
        ViewOptions {
            mesh: self.mesh.mesh.clone(),
            rig: self.rig.clone(),
            pose: self.pose.clone(),
            subdivide,
            volume: self.volume.into(),
            script: self.script.clone(),
            size: self.size,
            pose_out: self.save_pose.clone(),
        }
    }
}

pub fn run_view(args: &Args) -> CliResult {
    let Some(report) = run(args.options())? else { return Ok(()) };
    let json = serde_json::to_string_pretty(&report)?;
    out!("{json}");
    if let Some(path) = &args.report {
        write_atomically(path, |out| writeln!(out, "{json}"))
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    if !report.errors.is_empty() {
        return Err(format!("the script met {} errors: {}", report.errors.len(), report.errors.join("; ")).into());
    }
    Ok(())
}
