//! Editing sweeps (§4–5): key cross-section edits, direct control of a surface point and of an
//! arbitrary cross-section, hierarchies of sweeps and volume-preserving interaction. Rig-level
//! work in f64 on the CPU: it touches tens of keys, not millions of vertices; the vertices
//! follow through the bind and deform stages on either backend.
//!
//! Data flow: **rig** (edited into a pose here) → sweep → sweep coefficients → bind → deform →
//! normals → output.

mod bend;
mod controls;
mod drag;
mod edits;
mod error;
mod hierarchy;
mod journal;
mod keep_length;
mod keys;
mod posing;
mod rigid;
mod section;
mod shapes;
mod volume;
mod warnings;

pub use crate::sweep::chord_length;
pub use bend::{TAPER as BEND_TAPER, bend, bend_share};
pub use controls::Controls;
pub use drag::{DEFAULT_DRAG_KEYS, DragMode, drag_point};
pub use edits::Edit;
#[cfg(feature = "json")]
pub use edits::{edits_to_json, parse_edits};
pub use error::EditError;
pub use hierarchy::{propagate, propagate_down};
pub use keep_length::keep_chord_lengths;
pub use keys::{KeyMode, move_key, scale_radii};
pub use posing::Posing;
pub use rigid::{Motion, angle_between};
pub use section::{SectionTarget, move_sections};
pub use volume::{BoundMesh, VolumeRule, Volumes};
pub use warnings::{PoseWarning, WORSE, pose_warnings};
