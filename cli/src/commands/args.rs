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

/// `--rotation-interpolation`: how the sweeps a command writes interpolate their key rotations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum RotationArg {
    /// The paper's normalized linear interpolation (C⁰ frames at the keys).
    #[default]
    Linear,
    /// A normalized cubic spline of the key quaternions (C¹ frames across the keys).
    Cubic,
}

impl RotationArg {
    /// The rig file's field for it: absent for the default.
    pub fn field(self) -> Option<sweepffd::sweep::RotationInterpolation> {
        match self {
            RotationArg::Linear => None,
            RotationArg::Cubic => Some(sweepffd::sweep::RotationInterpolation::Cubic),
        }
    }
}
