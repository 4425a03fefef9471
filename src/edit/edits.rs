//! The edits file of `sweepffd pose`: a JSON array of edits, applied in order.
//!
//! ```json
//! [{"op": "move_key", "sweep": "neck", "key": 2, "translate": [0, 0.5, 0], "rotate": [0, 0, 0.2588, 0.9659], "mode": "local"},
//!  {"op": "scale_radii", "sweep": "neck", "key": 1, "factor": 1.5, "theta_range": [0, 3.1416]},
//!  {"op": "drag_point", "sweep": "neck", "theta": 1.57, "t": 0.8, "to": [0.2, 1.0, 3.1], "mode": "both", "keys": 2},
//!  {"op": "move_section", "sweep": "neck", "t": 0.5, "translate": [0.1, 0, 0], "rotate": [0, 0, 0, 1]}]
//! ```

use serde::{Deserialize, Serialize};

use super::drag::{DEFAULT_DRAG_KEYS, DragMode};
use super::keys::KeyMode;

/// One edit of a pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "op", rename_all = "snake_case", deny_unknown_fields)]
pub enum Edit {
    /// Rotates key `key` by `rotate` about its center, then translates it by `translate` (world
    /// coordinates); `local`: the keys after it follow, `independent`: it moves alone.
    MoveKey {
        sweep: String,
        key: usize,
        #[serde(default)]
        translate: [f64; 3],
        #[serde(default = "identity")]
        rotate: [f64; 4],
        #[serde(default)]
        mode: KeyMode,
    },
    /// Scales the radii of key `key` by `factor`, or with `theta_range` [a, b] a smooth bump
    /// over that range of θ (radians).
    ScaleRadii {
        sweep: String,
        key: usize,
        factor: f64,
        #[serde(default)]
        theta_range: Option<[f64; 2]>,
    },
    /// Drags the point (θ, t, d, h) to `to` by editing up to `keys` keys below it: the surface
    /// point S(θ, t) with d = h = 0 (the default), or a bound vertex with its binding's d and h.
    DragPoint {
        sweep: String,
        theta: f64,
        t: f64,
        #[serde(default)]
        d: f64,
        #[serde(default)]
        h: f64,
        to: [f64; 3],
        #[serde(default)]
        mode: DragMode,
        #[serde(default = "default_drag_keys")]
        keys: usize,
    },
    /// Moves the cross-section at t by `translate` and turns it by `rotate` (about its center).
    MoveSection {
        sweep: String,
        t: f64,
        #[serde(default)]
        translate: [f64; 3],
        #[serde(default = "identity")]
        rotate: [f64; 4],
    },
}

fn identity() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

fn default_drag_keys() -> usize {
    DEFAULT_DRAG_KEYS
}

impl Edit {
    /// The name of the sweep the edit applies to.
    pub fn sweep(&self) -> &str {
        match self {
            Edit::MoveKey { sweep, .. }
            | Edit::ScaleRadii { sweep, .. }
            | Edit::DragPoint { sweep, .. }
            | Edit::MoveSection { sweep, .. } => sweep,
        }
    }

    /// The `op` name, as in the file.
    pub fn op(&self) -> &'static str {
        match self {
            Edit::MoveKey { .. } => "move_key",
            Edit::ScaleRadii { .. } => "scale_radii",
            Edit::DragPoint { .. } => "drag_point",
            Edit::MoveSection { .. } => "move_section",
        }
    }
}

/// Parses an edits file's text: a list of at most [`crate::limits::MAX_EDITS`] edits, refused
/// while read.
pub fn parse_edits(text: &str) -> Result<Vec<Edit>, serde_json::Error> {
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let edits = crate::rig::bounded::edits(&mut deserializer)?;
    deserializer.end()?;
    Ok(edits)
}
