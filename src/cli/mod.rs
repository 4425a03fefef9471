//! Command-line parsing and dispatch. Each subcommand lives in its own file; errors are
//! printed as `error: …` on stderr with exit status 1.

mod bind;
mod deform;
mod demo;
mod progress;
mod volume;

use std::path::PathBuf;
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
    Bind {
        /// The mesh (.obj or .ply).
        #[arg(long)]
        mesh: PathBuf,
        /// The rest rig (JSON).
        #[arg(long)]
        rig: PathBuf,
        /// Where to write the bindings file.
        #[arg(long)]
        out: PathBuf,
    },
    /// Deform a mesh by a pose of its rig and write the deformed mesh.
    Deform {
        /// The mesh (.obj or .ply).
        #[arg(long)]
        mesh: PathBuf,
        /// The rest rig (JSON).
        #[arg(long)]
        rig: PathBuf,
        /// The pose: a rig file with the same sweeps and key counts.
        #[arg(long)]
        pose: PathBuf,
        /// Where to write the deformed mesh (.obj or .ply).
        #[arg(long)]
        out: PathBuf,
        /// Bindings saved by `sweepffd bind` for this mesh and rig (otherwise binds anew).
        #[arg(long)]
        bindings: Option<PathBuf>,
    },
    /// Print each sweep's volume (Eq. 1) as JSON.
    Volume {
        /// The rig (JSON).
        #[arg(long)]
        rig: PathBuf,
        /// Measure this pose of the rig instead of its rest keys.
        #[arg(long)]
        pose: Option<PathBuf>,
    },
    /// Build a tube and its rig, bend, twist and taper it, and write the meshes.
    Demo {
        /// Folder for the demo's files.
        #[arg(long, default_value = "sweepffd-demo")]
        out: PathBuf,
    },
}

/// Any error a subcommand reports; printed as its message.
type CliResult = Result<(), Box<dyn std::error::Error>>;

/// Parses the arguments, runs the subcommand and turns its outcome into an exit status.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let quiet = cli.quiet;
    let result = match cli.command {
        Command::Bind { mesh, rig, out } => bind::run(&mesh, &rig, &out, quiet),
        Command::Deform {
            mesh,
            rig,
            pose,
            out,
            bindings,
        } => deform::run(
            &deform::Args {
                mesh,
                rig,
                pose,
                out,
                bindings,
            },
            quiet,
        ),
        Command::Volume { rig, pose } => volume::run(&rig, pose.as_deref()),
        Command::Demo { out } => demo::run(&out, quiet),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
