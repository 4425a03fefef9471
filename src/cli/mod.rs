//! Command-line parsing and dispatch. Each subcommand lives in its own file; errors are
//! printed as `error: …` on stderr with exit status 1, while clap reports errors in the
//! arguments themselves (an unknown flag, a value that does not parse) with exit status 2.
//! SIGINT and SIGTERM end the process with status 130 and 143 ([`signals`]).

mod backend;
mod bench;
mod bind;
mod deform;
mod demo;
mod fit;
mod info;
mod pose;
mod progress;
mod render;
mod signals;
#[cfg(feature = "viewer")]
mod view;
mod volume;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use backend::Backend;
use sweepffd::edit::VolumeRule;
use sweepffd::fit::FitOptions;
use sweepffd::rig::LinkKind;

/// How a fitted sweep hangs from its parent (§5).
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum LinkKindArg {
    /// The first key is bound to the parent.
    Branch,
    /// The first and last keys are bound to the parent.
    Loop,
}

impl From<LinkKindArg> for LinkKind {
    fn from(kind: LinkKindArg) -> LinkKind {
        match kind {
            LinkKindArg::Branch => LinkKind::Branch,
            LinkKindArg::Loop => LinkKind::Loop,
        }
    }
}

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
        /// The mesh (.obj, .ply, .off, .gltf or .glb).
        #[arg(long)]
        mesh: PathBuf,
        /// The rest rig (JSON).
        #[arg(long)]
        rig: PathBuf,
        /// Where to write the bindings file.
        #[arg(long)]
        out: PathBuf,
        /// Where to bind: the GPU kernels, the CPU, or the GPU when one is available.
        #[arg(long, value_enum, default_value_t = Backend::Auto)]
        backend: Backend,
    },
    /// Deform a mesh by a pose of its rig and write the deformed mesh.
    Deform {
        /// The mesh (.obj, .ply, .off, .gltf or .glb).
        #[arg(long)]
        mesh: PathBuf,
        /// The rest rig (JSON).
        #[arg(long)]
        rig: PathBuf,
        /// The pose: a rig file with the same sweeps and key counts.
        #[arg(long)]
        pose: PathBuf,
        /// Where to write the deformed mesh (.obj, .ply, .off, .gltf or .glb).
        #[arg(long)]
        out: PathBuf,
        /// Bindings saved by `sweepffd bind` for this mesh and rig (otherwise binds anew).
        #[arg(long)]
        bindings: Option<PathBuf>,
        /// Where to bind and deform: the GPU kernels, the CPU, or the GPU when one is available.
        #[arg(long, value_enum, default_value_t = Backend::Auto)]
        backend: Backend,
    },
    /// Apply edits to a rig (with its hierarchy and a volume rule) and write the pose.
    Pose {
        /// The rest rig (JSON).
        #[arg(long)]
        rig: PathBuf,
        /// The edits (JSON array), applied in order.
        #[arg(long)]
        edits: PathBuf,
        /// Where to write the pose (a rig file `deform` takes as --pose).
        #[arg(long)]
        out: PathBuf,
        /// Which volumes each edit keeps.
        #[arg(long, value_enum, default_value_t = VolumeRule::None)]
        volume: VolumeRule,
        /// The closed mesh whose enclosed volume `--volume mesh` keeps.
        #[arg(long)]
        mesh: Option<PathBuf>,
    },
    /// Fit a control sweep to a part of a mesh (§3) and write it into a rig.
    Fit {
        /// The mesh (.obj or .ply).
        #[arg(long)]
        mesh: PathBuf,
        /// A face group of the mesh that makes up the part; repeat for several.
        #[arg(long = "group")]
        groups: Vec<String>,
        /// A file of the part's zero-based vertex indices (JSON array, or separated by spaces or commas).
        #[arg(long)]
        indices: Option<PathBuf>,
        /// First guess at the axis, a polyline "x0,y0,z0;x1,y1,z1;..." (default: the part's principal axis).
        #[arg(long, allow_hyphen_values = true)]
        axis: Option<String>,
        /// Keys placed along the axis before any is inserted.
        #[arg(long, default_value_t = 6)]
        keys: usize,
        /// Radii M sampled per key.
        #[arg(long, default_value_t = 32)]
        radii: usize,
        /// The most keys insertion may reach.
        #[arg(long, default_value_t = 24)]
        max_keys: usize,
        /// A knot interval whose RMS |d| exceeds this fraction of the mean radius gets a key inserted.
        #[arg(long, default_value_t = 0.05)]
        tolerance: f64,
        /// Falloff width W in mesh units over which the sweep's deformation fades at the part's boundary; 0: a hard boundary (default: 0.3 of the part's length).
        #[arg(long, allow_negative_numbers = true)]
        falloff: Option<f64>,
        /// The sweep's name (default: the groups joined by "+", or the indices file's stem).
        #[arg(long)]
        name: Option<String>,
        /// Hang the sweep from this sweep of the rig (--append-to) in the hierarchy.
        #[arg(long)]
        parent: Option<String>,
        /// How the sweep hangs from --parent.
        #[arg(long, value_enum, default_value_t = LinkKindArg::Branch)]
        kind: LinkKindArg,
        /// Where to write the rig.
        #[arg(long)]
        out: PathBuf,
        /// Add the sweep to this rig's sweeps instead of starting a new rig (may equal --out).
        #[arg(long)]
        append_to: Option<PathBuf>,
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
    /// Print the GPU adapter, its backend and the limits the kernels are planned for.
    Info,
    /// Measure binding and deformation throughput against copy and skinning baselines.
    Bench {
        /// Vertices of the synthetic tube to measure, 770 to 33554432 (ignored with --mesh and
        /// --rig); rounded down to a whole tube, 256·k + 2 vertices, with a note.
        #[arg(long, default_value_t = 1_000_000)]
        vertices: usize,
        /// Measure this mesh instead of a synthetic tube (needs --rig).
        #[arg(long)]
        mesh: Option<PathBuf>,
        /// The rest rig of --mesh.
        #[arg(long)]
        rig: Option<PathBuf>,
        /// Where to measure.
        #[arg(long, value_enum, default_value_t = Backend::Auto)]
        backend: Backend,
        /// Timed runs per figure (each figure is their median), 1 to 10000.
        #[arg(long, default_value_t = 10)]
        runs: usize,
        /// Print one JSON line.
        #[arg(long)]
        json: bool,
    },
    /// Draw a PNG of a mesh (rest or posed), optionally with its control sweeps.
    Render {
        /// The mesh (.obj or .ply).
        #[arg(long)]
        mesh: PathBuf,
        /// The rest rig (JSON); needed by --pose and --show-sweeps.
        #[arg(long)]
        rig: Option<PathBuf>,
        /// Draw the mesh deformed by this pose of the rig (bound and deformed on the CPU).
        #[arg(long)]
        pose: Option<PathBuf>,
        /// Draw the control sweeps as translucent surfaces with a dark ring at each key.
        #[arg(long)]
        show_sweeps: bool,
        /// Picture size WIDTHxHEIGHT in pixels (each panel's with --compare).
        #[arg(long, default_value = "800x600", value_parser = render::parse_size)]
        size: (u32, u32),
        /// Camera AZIMUTH,ELEVATION in degrees: azimuth around +Y from +Z towards +X, elevation
        /// above the XZ plane (Y is up).
        #[arg(long, default_value = "30,20", value_parser = render::parse_view, allow_hyphen_values = true)]
        view: sweepffd::render::ViewAngles,
        /// Draw rest (left) and pose (right) side by side, one camera, picture width 2×WIDTH.
        #[arg(long)]
        compare: bool,
        /// Where to write the picture (.png).
        #[arg(long)]
        out: PathBuf,
    },
    /// Open a window to edit a mesh through its sweeps in real time (see the README's controls).
    #[cfg(feature = "viewer")]
    View {
        /// The mesh (.obj, .ply, .off, .gltf or .glb).
        #[arg(long)]
        mesh: PathBuf,
        /// The rest rig (JSON); without it, fit sweeps to parts picked in the window.
        #[arg(long)]
        rig: Option<PathBuf>,
        /// Start from this pose of the rig.
        #[arg(long)]
        pose: Option<PathBuf>,
        /// Levels of midpoint subdivision of the mesh (each about quadruples the vertices; the
        /// rig's vertex indices are carried along).
        #[arg(long, conflicts_with = "subdivide_to")]
        subdivide: Option<usize>,
        /// Subdivide the mesh to exactly this many vertices (midpoint levels, then centroid splits).
        #[arg(long)]
        subdivide_to: Option<usize>,
        /// The volume rule to start with.
        #[arg(long, value_enum, default_value_t = VolumeRule::None)]
        volume: VolumeRule,
        /// Window size WIDTHxHEIGHT in pixels.
        #[arg(long, default_value = "1280x800", value_parser = render::parse_size)]
        size: (u32, u32),
        /// Where Ctrl+S saves the pose (the panel can change it).
        #[arg(long, default_value = "pose.json")]
        save_pose: PathBuf,
        /// Replay this script of input events and screenshots, print a JSON report, and exit.
        #[arg(long)]
        script: Option<PathBuf>,
        /// Also write the script's report to this file.
        #[arg(long, requires = "script")]
        report: Option<PathBuf>,
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
    if let Err(error) = signals::install() {
        eprintln!("error: cannot install the SIGINT and SIGTERM handler: {error}");
        return ExitCode::FAILURE;
    }
    let result = match cli.command {
        Command::Bind { mesh, rig, out, backend } => bind::run(&mesh, &rig, &out, backend, quiet),
        Command::Deform { mesh, rig, pose, out, bindings, backend } => {
            deform::run(&deform::Args { mesh, rig, pose, out, bindings, backend }, quiet)
        }
        Command::Pose { rig, edits, out, volume, mesh } => {
            pose::run(&pose::Args { rig, edits, out, volume, mesh }, quiet)
        }
        Command::Fit {
            mesh,
            groups,
            indices,
            axis,
            keys,
            radii,
            max_keys,
            tolerance,
            falloff,
            name,
            parent,
            kind,
            out,
            append_to,
        } => {
            let options = FitOptions { axis: None, keys, radii, max_keys, tolerance, falloff };
            let kind = kind.into();
            fit::run(&fit::Args { mesh, groups, indices, axis, options, name, parent, kind, out, append_to }, quiet)
        }
        Command::Volume { rig, pose } => volume::run(&rig, pose.as_deref()),
        Command::Info => info::run(),
        Command::Bench { vertices, mesh, rig, backend, runs, json } => {
            bench::run(&bench::Args { vertices, mesh, rig, backend, runs, json }, quiet)
        }
        Command::Render { mesh, rig, pose, show_sweeps, size, view, compare, out } => {
            render::run(&render::Args { mesh, rig, pose, show_sweeps, size, view, compare, out }, quiet)
        }
        #[cfg(feature = "viewer")]
        Command::View { mesh, rig, pose, subdivide, subdivide_to, volume, size, save_pose, script, report } => {
            let subdivide = match (subdivide, subdivide_to) {
                (Some(levels), _) => sweepffd::view::Subdivide::Levels(levels),
                (None, Some(vertices)) => sweepffd::view::Subdivide::Vertices(vertices),
                (None, None) => sweepffd::view::Subdivide::No,
            };
            let options =
                sweepffd::view::ViewOptions { mesh, rig, pose, subdivide, volume, script, size, pose_out: save_pose };
            view::run_view(view::Args { options, report })
        }
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
