//! The edits file of `sweepffd pose`: a JSON array of edits, applied in order.
//!
//! ```json
//! [{"op": "move_key", "sweep": "neck", "key": 2, "translate": [0, 0.5, 0], "rotate": [0, 0, 0.2588, 0.9659], "mode": "local"},
//!  {"op": "scale_radii", "sweep": "neck", "key": 1, "factor": 1.5, "theta_range": [0, 3.1416]},
//!  {"op": "drag_point", "sweep": "neck", "theta": 1.57, "t": 0.8, "to": [0.2, 1.0, 3.1], "mode": "both", "keys": 2},
//!  {"op": "move_section", "sweep": "neck", "t": 0.5, "translate": [0.1, 0, 0], "rotate": [0, 0, 0, 1]},
//!  {"op": "bend", "sweep": "neck", "t": 0.5, "span": 0.2, "axis": [1, 0, 0], "angle_deg": 60}]
//! ```

#[cfg(feature = "json")]
use serde::{Deserialize, Serialize};

use super::drag::DragMode;
use super::keys::KeyMode;

/// One edit of a pose.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(tag = "op", rename_all = "snake_case", deny_unknown_fields))]
pub enum Edit {
    /// Rotates key `key` by `rotate` about its center, then translates it by `translate` (world
    /// coordinates); `local`: the keys after it follow, `independent`: it moves alone.
    MoveKey {
        sweep: String,
        key: usize,
        #[cfg_attr(feature = "json", serde(default))]
        translate: [f64; 3],
        #[cfg_attr(feature = "json", serde(default = "identity"))]
        rotate: [f64; 4],
        #[cfg_attr(feature = "json", serde(default))]
        mode: KeyMode,
    },
    /// Scales the radii of key `key` by `factor`, or with `theta_range` [a, b] a smooth bump
    /// over that range of θ (radians).
    ScaleRadii {
        sweep: String,
        key: usize,
        factor: f64,
        #[cfg_attr(feature = "json", serde(default))]
        theta_range: Option<[f64; 2]>,
    },
    /// Drags the point (θ, t, d, h) to `to` by editing up to `keys` keys below it: the surface
    /// point S(θ, t) with d = h = 0 (the default), or a bound vertex with its binding's d and h.
    DragPoint {
        sweep: String,
        theta: f64,
        t: f64,
        #[cfg_attr(feature = "json", serde(default))]
        d: f64,
        #[cfg_attr(feature = "json", serde(default))]
        h: f64,
        to: [f64; 3],
        #[cfg_attr(feature = "json", serde(default))]
        mode: DragMode,
        #[cfg_attr(feature = "json", serde(default = "default_drag_keys"))]
        keys: usize,
    },
    /// Moves the cross-section at t by `translate` and turns it by `rotate` (about its center).
    MoveSection {
        sweep: String,
        t: f64,
        #[cfg_attr(feature = "json", serde(default))]
        translate: [f64; 3],
        #[cfg_attr(feature = "json", serde(default = "identity"))]
        rotate: [f64; 4],
    },
    /// Turns the sweep by `angle_deg` degrees about `axis` at t, spread smoothly over the span
    /// of width `span` in t centred on t ([`super::bend`]). The axis is in the frame of the
    /// cross-section at t: x and y in its plane, z along the spine, as a `move_key` rotation in
    /// `local` mode.
    Bend { sweep: String, t: f64, span: f64, axis: [f64; 3], angle_deg: f64 },
}

#[cfg(feature = "json")]
fn identity() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

#[cfg(feature = "json")]
fn default_drag_keys() -> usize {
    super::drag::DEFAULT_DRAG_KEYS
}

impl Edit {
    /// The name of the sweep the edit applies to.
    pub fn sweep(&self) -> &str {
        match self {
            Edit::MoveKey { sweep, .. }
            | Edit::ScaleRadii { sweep, .. }
            | Edit::DragPoint { sweep, .. }
            | Edit::MoveSection { sweep, .. }
            | Edit::Bend { sweep, .. } => sweep,
        }
    }

    /// The `op` name, as in the file.
    pub fn op(&self) -> &'static str {
        match self {
            Edit::MoveKey { .. } => "move_key",
            Edit::ScaleRadii { .. } => "scale_radii",
            Edit::DragPoint { .. } => "drag_point",
            Edit::MoveSection { .. } => "move_section",
            Edit::Bend { .. } => "bend",
        }
    }
}

#[cfg(feature = "json")]
/// The edits file's text (pretty JSON and a newline), or, since JSON would write a non-finite
/// number as `null`, the first edit holding one: `edit 3 (drag_point on "arm"): to[1] is inf,
/// not a finite number`.
pub fn edits_to_json(edits: &[Edit]) -> Result<String, String> {
    for (i, edit) in edits.iter().enumerate() {
        if let Some((field, value)) = edit.numbers().into_iter().find(|(_, v)| !v.is_finite()) {
            return Err(format!(
                "edit {i} ({} on {:?}): {field} is {value}, not a finite number",
                edit.op(),
                edit.sweep()
            ));
        }
    }
    let mut text = serde_json::to_string_pretty(edits).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}

#[cfg(feature = "json")]
impl Edit {
    /// Every number of the edit with its field name as in the file.
    fn numbers(&self) -> Vec<(String, f64)> {
        let named = |name: &str, values: &[f64]| -> Vec<(String, f64)> {
            values.iter().enumerate().map(|(i, v)| (format!("{name}[{i}]"), *v)).collect()
        };
        match self {
            Edit::MoveKey { translate, rotate, .. } | Edit::MoveSection { translate, rotate, .. } => {
                let mut numbers = named("translate", translate);
                numbers.extend(named("rotate", rotate));
                if let Edit::MoveSection { t, .. } = self {
                    numbers.push(("t".into(), *t));
                }
                numbers
            }
            Edit::ScaleRadii { factor, theta_range, .. } => {
                let mut numbers = vec![("factor".to_string(), *factor)];
                numbers.extend(theta_range.iter().flat_map(|range| named("theta_range", range)));
                numbers
            }
            Edit::DragPoint { theta, t, d, h, to, .. } => {
                let mut numbers = vec![("theta".into(), *theta), ("t".into(), *t), ("d".into(), *d), ("h".into(), *h)];
                numbers.extend(named("to", to));
                numbers
            }
            Edit::Bend { t, span, axis, angle_deg, .. } => {
                let mut numbers = vec![("t".into(), *t), ("span".into(), *span)];
                numbers.extend(named("axis", axis));
                numbers.push(("angle_deg".into(), *angle_deg));
                numbers
            }
        }
    }
}

#[cfg(feature = "json")]
/// Parses an edits file's text: a list of at most [`crate::limits::MAX_EDITS`] edits, refused
/// while read.
pub fn parse_edits(text: &str) -> Result<Vec<Edit>, serde_json::Error> {
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let edits = crate::rig::bounded::edits(&mut deserializer)?;
    deserializer.end()?;
    Ok(edits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_with_a_non_finite_number_are_not_written() {
        let drag = |to: [f64; 3]| Edit::DragPoint {
            sweep: "arm".into(),
            theta: 0.5,
            t: 0.5,
            d: 0.0,
            h: 0.0,
            to,
            mode: DragMode::default(),
            keys: super::super::drag::DEFAULT_DRAG_KEYS,
        };
        let scale = Edit::ScaleRadii { sweep: "arm".into(), key: 1, factor: 2.0, theta_range: None };
        let good = [scale.clone(), drag([1.0, 2.0, 3.0])];
        let text = edits_to_json(&good).unwrap();
        assert_eq!(parse_edits(&text).unwrap(), good, "what is written reads back");
        let bad = [scale, drag([1.0, f64::INFINITY, 3.0])];
        assert_eq!(
            edits_to_json(&bad).unwrap_err(),
            "edit 1 (drag_point on \"arm\"): to[1] is inf, not a finite number"
        );
        // serde_json alone would have written `null`.
        assert!(serde_json::to_string(&bad).unwrap().contains("null"));
    }
}
