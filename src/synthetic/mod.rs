//! Procedural meshes, rigs and poses: the demo's scene, and inputs of any size for tests and
//! benchmarks that must not depend on files.

mod tube;

pub use crate::rig::BendTwistTaper;
pub use tube::{Tube, attached_tube_rig, split_tube_rig, straight_sweep, tube_rig};
