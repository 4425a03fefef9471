//! The file arguments several commands share, declared once so that their flags and help read
//! the same everywhere: the mesh, its rest rig and a pose of it.

use std::path::PathBuf;

/// `--mesh`: the mesh a command reads.
#[derive(Debug, clap::Args)]
pub struct MeshArg {
    /// The mesh (.obj, .ply, .off, .gltf or .glb).
    #[arg(long)]
    pub mesh: PathBuf,
}

/// `--rig`: a rest rig.
#[derive(Debug, clap::Args)]
pub struct RigArg {
    /// The rest rig (JSON).
    #[arg(long)]
    pub rig: PathBuf,
}

/// `--pose`: a pose of the rest rig.
#[derive(Debug, clap::Args)]
pub struct PoseArg {
    /// The pose: a rig file with the same sweeps and key counts as the rest rig.
    #[arg(long)]
    pub pose: PathBuf,
}
