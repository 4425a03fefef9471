//! Command-line parsing and dispatch. Each subcommand lives in its own file; errors are
//! printed as `error: …` on stderr with exit status 1, while clap reports errors in the
//! arguments themselves (an unknown flag, a value that does not parse) with exit status 2.
//! SIGINT and SIGTERM end the process with status 130 and 143 ([`signals`]).

mod args;
mod autorig;
mod backend;
mod batch;
mod bench;
mod bind;
mod deform;
mod demo;
mod export;
mod fit;
mod flags;
mod info;
mod pose;
mod progress;
mod render;
mod signals;
#[cfg(feature = "viewer")]
mod view;
mod volume;
mod volume_rule;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Sweep-based freeform deformation of 3D meshes (Yoon & Kim).
#[derive(Debug, Parser)]
#[command(name = "sweepffd", version, about, long_about = None)]
struct Cli {
    /// Print no progress bars and no summaries (results and errors still print).
    #[arg(long, short, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Bind every owned vertex of a mesh to its sweep and save the bindings.
    Bind(bind::Args),
    /// Deform a mesh by a pose of its rig and write the deformed mesh.
    Deform(deform::Args),
    /// Run the deform jobs of a manifest (one shard of them), binding each mesh and rig once.
    Batch(batch::Args),
    /// Write a mesh and poses of its rig as one glTF animation (a morph target per pose).
    Export(export::Args),
    /// Apply edits to a rig (with its hierarchy and a volume rule) and write the pose.
    Pose(pose::Args),
    /// Fit a control sweep to a part of a mesh (§3) and write it into a rig.
    Fit(fit::Args),
    /// Find a mesh's protrusions, fit one control sweep to each and write the rig.
    Autorig(autorig::Args),
    /// Print each sweep's volume (Eq. 1) as JSON.
    Volume(volume::Args),
    /// Print the GPU adapter, its backend and the limits the kernels are planned for.
    Info,
    /// Measure binding and deformation throughput against copy and skinning baselines.
    Bench(bench::Args),
    /// Draw a PNG of a mesh (rest or posed), optionally with its control sweeps.
    Render(render::Args),
    /// Open a window to edit a mesh through its sweeps in real time (see the README's controls).
    #[cfg(feature = "viewer")]
    View(view::Args),
    /// Build a tube and its rig, bend, twist and taper it, and write the meshes.
    Demo(demo::Args),
}

/// Any error a subcommand reports; printed as its message.
type CliResult = Result<(), Box<dyn std::error::Error>>;

/// Parses the arguments, runs the subcommand and turns its outcome into an exit status.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let quiet = cli.quiet;
    if let Err(error) = signals::install() {
        note!("error: cannot install the SIGINT and SIGTERM handler: {error}");
        return ExitCode::FAILURE;
    }
    let result = match &cli.command {
        Command::Bind(args) => bind::run(args, quiet),
        Command::Deform(args) => deform::run(args, quiet),
        Command::Batch(args) => batch::run(args, quiet),
        Command::Export(args) => export::run(args, quiet),
        Command::Pose(args) => pose::run(args, quiet),
        Command::Fit(args) => fit::run(args, quiet),
        Command::Autorig(args) => autorig::run(args, quiet),
        Command::Volume(args) => volume::run(args),
        Command::Info => info::run(),
        Command::Bench(args) => bench::run(args, quiet),
        Command::Render(args) => render::run(args, quiet),
        #[cfg(feature = "viewer")]
        Command::View(args) => view::run_view(args),
        Command::Demo(args) => demo::run(args, quiet),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            note!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
