//! A pose being edited: the current keys of every sweep, changed edit by edit with hierarchy
//! propagation and a volume rule; an edit that fails changes nothing.

use glam::{DQuat, DVec3};

use super::EditError;
use super::bend::bend;
use super::controls::Controls;
use super::drag::drag_point_kept;
use super::edits::Edit;
use super::hierarchy::propagate_kept;
use super::journal::Journal;
use super::keep_length::keep_chord_lengths;
use super::keys::{move_key, scale_radii};
use super::section::{SectionTarget, move_sections_kept};
use super::shapes::{Shape, Shapes};
use super::volume::{BoundMesh, Pending, VolumeRule, Volumes, apply_rule};
use crate::bind::VertexBinding;
use crate::rig::Rig;
use crate::sweep::{Key, Sweep};

/// The keys of every sweep of a rig, edited in place.
#[derive(Clone, Debug)]
pub struct Posing<'a> {
    rig: &'a Rig,
    keys: Vec<Vec<Key>>,
    /// Whether edits propagate through the hierarchy (§5). On by default; off shows the broken
    /// topology of Fig. 12.
    pub hierarchy: bool,
    /// The volume rule applied after each edit.
    pub volume: VolumeRule,
    /// Whether each edit keeps its sweep's length: the chords between its keys' centers are
    /// put back to the rest's after the edit ([`super::keep_chord_lengths`]), before the
    /// hierarchy and the volume rule. Off by default: an edit stretches the spine.
    pub keep_length: bool,
    /// Iteration limits and tolerances.
    pub controls: Controls,
    mesh: Option<BoundMesh<'a>>,
    /// The sweeps last built from (recent) keys, kept from edit to edit: a memo, so an edit
    /// rebuilds and measures only the sweeps it changes.
    shapes: Shapes,
    /// What the edit being applied changed, to undo it if it fails.
    journal: Journal,
}

impl<'a> Posing<'a> {
    /// Starts from the rest keys of `rig`.
    pub fn new(rig: &'a Rig) -> Posing<'a> {
        let keys = rig.sweeps().iter().map(|sweep| sweep.keys.clone()).collect();
        // The rig's rest sweeps are those of its rest keys.
        let shapes = rig.rest().iter().zip(rig.sweeps()).map(|(sweep, rest)| Shape::of(sweep, &rest.keys)).collect();
        Posing {
            rig,
            keys,
            hierarchy: true,
            volume: VolumeRule::None,
            keep_length: false,
            controls: Controls::default(),
            mesh: None,
            shapes,
            journal: Journal::default(),
        }
    }

    /// Continues from `keys`, a pose of the rig (e.g. loaded from a pose file, or saved before
    /// an edit to undo it): `Err(Invalid)` unless there is one key list per sweep, each as long
    /// as the sweep's rest keys.
    pub fn with_keys(mut self, keys: Vec<Vec<Key>>) -> Result<Posing<'a>, EditError> {
        let rest = self.rig.sweeps();
        if keys.len() != rest.len() {
            return Err(EditError::Invalid(format!("{} key lists for a rig of {} sweeps", keys.len(), rest.len())));
        }
        if let Some((sweep, keys)) = rest.iter().zip(&keys).find(|(sweep, keys)| sweep.keys.len() != keys.len()) {
            return Err(EditError::Invalid(format!(
                "sweep {:?} has {} keys at rest, the pose gives {}",
                sweep.name,
                sweep.keys.len(),
                keys.len()
            )));
        }
        self.keys = keys;
        self.shapes.iter_mut().for_each(Shape::forget);
        Ok(self)
    }

    /// Binds a closed mesh for [`VolumeRule::Mesh`].
    pub fn with_mesh(mut self, mesh: BoundMesh<'a>) -> Posing<'a> {
        self.mesh = Some(mesh);
        self
    }

    /// The current keys, sweep by sweep.
    pub fn keys(&self) -> &[Vec<Key>] {
        &self.keys
    }

    /// The current posed sweeps.
    pub fn sweeps(&self) -> Result<Vec<Sweep>, EditError> {
        self.keys
            .iter()
            .zip(self.rig.rest())
            .map(|(keys, rest)| rest.try_posed(keys).map_err(EditError::from))
            .collect()
    }

    /// The folds of the current pose that the rest rig does not have ([`super::pose_warnings`]).
    pub fn warnings(&self) -> Result<Vec<super::PoseWarning>, EditError> {
        Ok(super::pose_warnings(self.rig, &self.sweeps()?))
    }

    /// Applies `edit`, then the hierarchy and the volume rule. Returns the rounds the edit's own
    /// iteration took (0 for the direct edits). On error nothing changes.
    pub fn apply(&mut self, edit: &Edit) -> Result<usize, EditError> {
        let result = self.try_apply(edit);
        if result.is_err() {
            // The memos followed the edit's keys, which are dropped.
            self.shapes.iter_mut().for_each(Shape::forget);
        }
        result
    }

    /// Applies `edit` to the keys in place, journaled: on error the journal puts them back.
    fn try_apply(&mut self, edit: &Edit) -> Result<usize, EditError> {
        self.journal.begin(&self.keys);
        let result = self.edit_in_place(edit);
        if result.is_err() {
            self.journal.restore(&mut self.keys);
        }
        result
    }

    fn edit_in_place(&mut self, edit: &Edit) -> Result<usize, EditError> {
        let rig = self.rig;
        let sweep =
            rig.sweep_index(edit.sweep()).ok_or_else(|| EditError::UnknownSweep { sweep: edit.sweep().into() })?;
        let (keys, shapes, journal) = (&mut self.keys, &mut self.shapes, &mut self.journal);
        let before = match self.volume {
            VolumeRule::None => None,
            _ => Some(Volumes::measure_kept(rig, keys, self.mesh.as_ref(), shapes)?),
        };
        if let Edit::ScaleRadii { key, .. } = edit
            && *key < keys[sweep].len()
        {
            journal.save_key_radii(keys, sweep, *key);
        }
        let knots = rig.rest()[sweep].knots();
        let rounds = apply_edit(edit, &mut keys[sweep], knots, &self.controls, &mut shapes[sweep])?;
        if self.keep_length {
            keep_chord_lengths(&mut keys[sweep], &rig.sweeps()[sweep].keys);
        }
        shapes[sweep].sweep(&keys[sweep], knots)?;
        if self.hierarchy {
            propagate_kept(rig, keys, sweep, &self.controls, shapes)?;
        }
        let pending = match &before {
            Some(before) => apply_rule(self.volume, rig, keys, sweep, before, self.mesh.as_ref(), shapes, journal)?,
            None => Pending::none(keys.len()),
        };
        // Every sweep the edit reached is checked as rest keys are: finite, in range. The radii
        // of a kept sweep are those it was built from, checked then (or rescaled and checked);
        // the rule's pending rescales are checked as they are applied, last.
        for ((keys, rest), shape) in keys.iter().zip(rig.sweeps()).zip(shapes.iter()) {
            let checked = if shape.checked_radii() { Sweep::validate_frames(keys) } else { Sweep::validate(keys) };
            checked.map_err(|source| EditError::Sweep { sweep: rest.name.clone(), source })?;
        }
        pending.apply(rig, keys, shapes, journal)?;
        Ok(rounds)
    }
}

/// Applies one edit to the keys of its sweep.
fn apply_edit(
    edit: &Edit,
    keys: &mut [Key],
    knots: &[f64],
    controls: &Controls,
    shape: &mut Shape,
) -> Result<usize, EditError> {
    let key_in_range = |key: usize| {
        if key < keys.len() {
            Ok(key)
        } else {
            Err(EditError::KeyOutOfRange { sweep: edit.sweep().into(), key, count: keys.len() })
        }
    };
    match edit {
        Edit::MoveKey { key, translate, rotate, mode, .. } => {
            let key = key_in_range(*key)?;
            move_key(keys, key, vector(translate, "translate")?, rotation(rotate)?, *mode);
            Ok(0)
        }
        Edit::ScaleRadii { key, factor, theta_range, .. } => {
            let key = key_in_range(*key)?;
            if !(factor.is_finite() && *factor > 0.0) {
                return Err(EditError::Invalid(format!("\"factor\" must be a positive number, found {factor}")));
            }
            if theta_range.is_some_and(|r| !r.iter().all(|v| v.is_finite())) {
                return Err(EditError::Invalid("\"theta_range\" must hold two finite angles".into()));
            }
            let before = keys[key].radii.clone();
            scale_radii(&mut keys[key], *factor, theta_range.map(|[a, b]| (a, b)));
            shape.change_key_radii(keys, key, &before);
            Ok(0)
        }
        Edit::DragPoint { theta, t, d, h, to, mode, keys: k, .. } => {
            let t = parameter(*t)?;
            if ![theta, d, h].iter().all(|v| v.is_finite()) {
                return Err(EditError::Invalid("\"theta\", \"d\" and \"h\" must be finite".into()));
            }
            if *k == 0 {
                return Err(EditError::Invalid("\"keys\" must be at least 1".into()));
            }
            let point = VertexBinding { theta: *theta, t, d: *d, h: *h };
            drag_point_kept(keys, knots, point, vector(to, "to")?, *mode, *k, controls, shape)
        }
        Edit::MoveSection { t, translate, rotate, .. } => {
            let t = parameter(*t)?;
            let sweep = shape.sweep(keys, knots)?;
            let target = SectionTarget {
                t,
                center: sweep.center(t) + vector(translate, "translate")?,
                rotation: (rotation(rotate)? * sweep.orientation(t)).normalize(),
            };
            move_sections_kept(keys, knots, &[target], controls, shape)
        }
        Edit::Bend { t, span, axis, angle_deg, .. } => {
            let t = parameter(*t)?;
            if !(span.is_finite() && *span > 0.0) {
                return Err(EditError::Invalid(format!("\"span\" must be a positive width in t, found {span}")));
            }
            if !angle_deg.is_finite() {
                return Err(EditError::Invalid(format!("\"angle_deg\" must be a finite angle, found {angle_deg}")));
            }
            let axis = vector(axis, "axis")?
                .try_normalize()
                .ok_or_else(|| EditError::Invalid("\"axis\" must be a non-zero direction".into()))?;
            let turned_axis = shape.sweep(keys, knots)?.orientation(t) * axis;
            bend(keys, knots, t, *span, turned_axis, angle_deg.to_radians());
            Ok(0)
        }
    }
}

fn vector(v: &[f64; 3], name: &str) -> Result<DVec3, EditError> {
    let v = DVec3::from_array(*v);
    if v.is_finite() { Ok(v) } else { Err(EditError::Invalid(format!("\"{name}\" must be finite"))) }
}

fn rotation(q: &[f64; 4]) -> Result<DQuat, EditError> {
    let q = DQuat::from_array(*q);
    if !q.is_finite() || q.length_squared() == 0.0 {
        return Err(EditError::Invalid("\"rotate\" must be a finite, non-zero quaternion [x, y, z, w]".into()));
    }
    Ok(q.normalize())
}

fn parameter(t: f64) -> Result<f64, EditError> {
    if (0.0..=1.0).contains(&t) {
        Ok(t)
    } else {
        Err(EditError::Invalid(format!("\"t\" must lie in [0, 1], found {t}")))
    }
}
