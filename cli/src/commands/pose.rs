//! `sweepffd pose`: apply a list of edits to a rest rig, with hierarchy propagation and a volume
//! rule, and write the pose file that `deform` takes.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::CliResult;
use super::args::RigArg;
use super::volume_rule::VolumeArg;
use sweepffd::atomic_file::write_atomically;
use sweepffd::edit::{BoundMesh, Posing, parse_edits};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;

/// The arguments of `sweepffd pose`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub rig: RigArg,
    /// The edits (JSON array), applied in order.
    #[arg(long)]
    pub edits: PathBuf,
    /// Where to write the pose (a rig file `deform` takes as --pose).
    #[arg(long)]
    pub out: PathBuf,
    /// Which volumes each edit keeps.
    #[arg(long, value_enum, default_value_t = VolumeArg::None)]
    pub volume: VolumeArg,
    /// The closed mesh whose enclosed volume `--volume mesh` keeps.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// Keep each edited sweep's length: after every edit its keys are moved along its new spine
    /// so that the chords between them have their rest lengths (default: edits stretch).
    #[arg(long)]
    pub keep_length: bool,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    let rig = Rig::load(&args.rig.rig)?;
    let text = sweepffd::limits::read_input_text(&args.edits)
        .map_err(|e| format!("cannot read {}: {e}", args.edits.display()))?;
    let edits = parse_edits(&text).map_err(|e| format!("{}: not a valid edits file: {e}", args.edits.display()))?;
    let mesh = match (&args.mesh, args.volume) {
        (Some(path), volume) => {
            let mesh = Mesh::load(path)?;
            if let (VolumeArg::Mesh, Some(open)) = (volume, mesh.open_edge()) {
                let [a, b] = open.vertices;
                return Err(format!(
                    "{}: --volume mesh needs a closed mesh, but the edge between vertices {a} and {b} borders {} \
                     face(s), not 2",
                    path.display(),
                    open.faces
                )
                .into());
            }
            Some((mesh, path))
        }
        (None, VolumeArg::Mesh) => return Err("--volume mesh needs --mesh".into()),
        (None, _) => None,
    };
    let bindings;
    let mut posing = Posing::new(&rig);
    posing.volume = args.volume.into();
    posing.keep_length = args.keep_length;
    if let Some((mesh, path)) = &mesh {
        let owners = rig.owners(mesh, &path.display().to_string())?;
        bindings = rig.bind_mesh(mesh, &owners, &|_| {});
        posing = posing.with_mesh(BoundMesh { mesh, bindings: &bindings });
    }
    for (i, edit) in edits.iter().enumerate() {
        posing.apply(edit).map_err(|e| {
            format!(
                "{}: edit {i} ({} on {:?}): {e}; nothing was written",
                args.edits.display(),
                edit.op(),
                edit.sweep()
            )
        })?;
    }
    let text = rig.pose_document(posing.keys()).try_to_json(&args.out)?;
    write_pose(&args.out, &text)?;
    // Folds are warnings, not errors: the pose is written, and the user told where it folds.
    for warning in posing.warnings().map_err(|e| format!("{}: {e}", args.out.display()))? {
        note!("warning: {}: {warning}", args.out.display());
    }
    if !quiet {
        out!("applied {} edits -> {}", edits.len(), args.out.display());
    }
    Ok(())
}

fn write_pose(path: &Path, text: &str) -> CliResult {
    write_atomically(path, |out| out.write_all(text.as_bytes()))
        .map_err(|e| format!("cannot write {}: {e}", path.display()).into())
}
