//! `--volume none|total|ratio|mesh`: the command line's names for [`VolumeRule`], which the
//! library keeps free of clap.

use sweepffd::edit::VolumeRule;

/// Which volumes each edit keeps (§5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum VolumeArg {
    /// Volumes follow the edit.
    #[default]
    None,
    /// The sum of the sweeps' volumes is kept (Fig. 13a).
    Total,
    /// Each child keeps its volume ratio to its parent (Fig. 13b).
    Ratio,
    /// The enclosed volume of the deformed closed mesh is kept.
    Mesh,
}

impl From<VolumeArg> for VolumeRule {
    fn from(rule: VolumeArg) -> VolumeRule {
        match rule {
            VolumeArg::None => VolumeRule::None,
            VolumeArg::Total => VolumeRule::Total,
            VolumeArg::Ratio => VolumeRule::Ratio,
            VolumeArg::Mesh => VolumeRule::Mesh,
        }
    }
}
