//! The rig file format (JSON), as read and written. A pose file has the same shape; only its
//! keys matter.
//!
//! ```json
//! {"format": "sweepffd-rig", "version": 1,
//!  "sweeps": [{"name": "neck",
//!              "vertices": {"groups": ["neck"]},
//!              "keys": [{"center": [0, 0, 0], "rotation": [0, 0, 0, 1], "radii": [1, 1, 1, 1]},
//!                       {"center": [0, 0, 2], "rotation": [0, 0, 0, 1], "radii": [1, 1, 1, 1]}]}]}
//! ```

use glam::{DQuat, DVec3};
#[cfg(feature = "json")]
use serde::{Deserialize, Serialize};

#[cfg(feature = "json")]
use super::bounded;
use crate::sweep::{Key, RotationInterpolation};

/// The value of the `format` field.
pub const FORMAT: &str = "sweepffd-rig";
/// The value of the `version` field this release reads and writes.
pub const VERSION: u32 = 1;

/// A whole rig or pose file.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(deny_unknown_fields))]
pub struct RigDocument {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u32,
    /// The rotation interpolation of every sweep that does not name its own; absent: linear.
    #[cfg_attr(feature = "json", serde(default, skip_serializing_if = "Option::is_none"))]
    pub rotation_interpolation: Option<RotationInterpolation>,
    /// The sweeps, in order; a vertex binds to the sweep that owns it. At most
    /// [`crate::limits::MAX_SWEEPS`], refused while read.
    #[cfg_attr(feature = "json", serde(deserialize_with = "bounded::sweeps"))]
    pub sweeps: Vec<SweepDocument>,
}

/// One sweep of a rig file.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(deny_unknown_fields))]
pub struct SweepDocument {
    /// Unique within the rig; poses match sweeps by name.
    pub name: String,
    /// Which vertices the sweep owns; absent: none.
    #[cfg_attr(feature = "json", serde(default, skip_serializing_if = "Option::is_none"))]
    pub vertices: Option<VertexSelection>,
    /// The key cross-sections, at least two, at most [`crate::limits::MAX_KEYS_PER_SWEEP`].
    #[cfg_attr(feature = "json", serde(deserialize_with = "bounded::keys"))]
    pub keys: Vec<KeyDocument>,
    /// Knots u_i, one per key, from 0 to 1, increasing; absent: chord length of the centers.
    #[cfg_attr(
        feature = "json",
        serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "bounded::knots")
    )]
    pub knots: Option<Vec<f64>>,
    /// The sweep this one hangs from in the hierarchy (§5); absent: a root.
    #[cfg_attr(feature = "json", serde(default, skip_serializing_if = "Option::is_none"))]
    pub parent: Option<ParentLink>,
    /// Falloff width W in mesh units (≥ 0); absent or 0: a hard boundary.
    #[cfg_attr(feature = "json", serde(default, skip_serializing_if = "Option::is_none"))]
    pub falloff: Option<f64>,
    /// How R(t) interpolates the keys' rotations, `"linear"` (the paper's) or `"cubic"` (C¹
    /// across the keys); absent: the rig's `rotation_interpolation`, else linear.
    #[cfg_attr(feature = "json", serde(default, skip_serializing_if = "Option::is_none"))]
    pub rotation_interpolation: Option<RotationInterpolation>,
}

/// `"parent": {"sweep": "body", "kind": "branch"}`: a sweep's place in the hierarchy (§5).
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(deny_unknown_fields))]
pub struct ParentLink {
    /// The parent sweep's name.
    pub sweep: String,
    /// How the child's keys are bound to the parent.
    pub kind: LinkKind,
}

/// How a child sweep's keys are bound to cross-sections of its parent (§5, Fig. 11).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(rename_all = "lowercase"))]
pub enum LinkKind {
    /// The first key is bound (the teapot's spout).
    Branch,
    /// The first and the last key are bound (the teapot's handle).
    Loop,
}

/// The vertices a sweep owns: `"all"`, `{"groups": [...]}` or `{"indices": [...]}`.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(rename_all = "lowercase"))]
pub enum VertexSelection {
    /// Every vertex of the mesh.
    All,
    /// The vertices of the faces of these OBJ groups (or objects).
    Groups(Vec<String>),
    /// These zero-based vertex indices, in file order.
    Indices(#[cfg_attr(feature = "json", serde(deserialize_with = "bounded::indices"))] Vec<u32>),
}

/// One key cross-section in a rig file.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(deny_unknown_fields))]
pub struct KeyDocument {
    /// Center p_i.
    pub center: [f64; 3],
    /// Orientation q_i as `[x, y, z, w]`; normalized on load.
    pub rotation: [f64; 4],
    /// Radii ρ_ij at θ_j = 2πj/M; at most [`crate::limits::MAX_RADII_PER_KEY`].
    #[cfg_attr(feature = "json", serde(deserialize_with = "bounded::radii"))]
    pub radii: Vec<f64>,
}

impl From<&KeyDocument> for Key {
    fn from(key: &KeyDocument) -> Key {
        Key {
            center: DVec3::from_array(key.center),
            rotation: DQuat::from_array(key.rotation),
            radii: key.radii.clone(),
        }
    }
}

impl From<&Key> for KeyDocument {
    fn from(key: &Key) -> KeyDocument {
        KeyDocument { center: key.center.to_array(), rotation: key.rotation.to_array(), radii: key.radii.clone() }
    }
}

impl RigDocument {
    #[cfg(feature = "json")]
    /// Parses a rig or pose file's text (format and version are checked by the rig loader).
    pub fn parse(text: &str) -> Result<RigDocument, serde_json::Error> {
        serde_json::from_str(text)
    }

    #[cfg(feature = "json")]
    /// The file's text: pretty JSON, one key per line. JSON has no infinities: a non-finite
    /// number would be written as `null`, so a writer of user data calls
    /// [`RigDocument::try_to_json`] instead.
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).expect("a rig document always serializes");
        text.push('\n');
        text
    }

    #[cfg(feature = "json")]
    /// [`RigDocument::to_json`], or an error naming `file` (the file to be written), the sweep,
    /// the key and the field of the first number that is not finite.
    pub fn try_to_json(&self, file: &std::path::Path) -> Result<String, super::RigError> {
        self.check_finite().map_err(|kind| super::RigError::new(Some(file.to_path_buf()), kind))?;
        Ok(self.to_json())
    }

    #[cfg(feature = "json")]
    /// Fails on the first number of a key, a knot or a falloff that is not finite.
    fn check_finite(&self) -> Result<(), super::RigErrorKind> {
        for sweep in &self.sweeps {
            let bad = |place: String, value: f64| super::RigErrorKind::NonFiniteOutput {
                sweep: sweep.name.clone(),
                place,
                value,
            };
            for (k, key) in sweep.keys.iter().enumerate() {
                let fields = [("center", &key.center[..]), ("rotation", &key.rotation[..]), ("radii", &key.radii[..])];
                for (name, values) in fields {
                    if let Some((i, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                        return Err(bad(format!("key {k}: {name}[{i}]"), value));
                    }
                }
            }
            let knots = sweep.knots.iter().flatten();
            if let Some((i, &value)) = knots.enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(bad(format!("knot {i}"), value));
            }
            if let Some(value) = sweep.falloff.filter(|f| !f.is_finite()) {
                return Err(bad("falloff".into(), value));
            }
        }
        Ok(())
    }
}
