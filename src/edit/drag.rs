//! Direct control of a surface point (§4, Fig. 8–9): drag a point of a sweep to a target by
//! editing the key cross-sections below it.
//!
//! With v the point, v′ the target and X_i the key below the point (the start of its knot
//! interval), the difference is split about X_i's center p_i: v′ is projected onto the sphere
//! around p_i through v, giving v″; the angular part turns v − p_i onto v″ − p_i (axis
//! (v − p_i) × (v″ − p_i), angle arccos of their normalized dot product) and the linear part is
//! v′ − v″. Both are applied to the k keys X_{i−k+1}..X_i from the lowest up — each taking its
//! share of what remains, the keys above it following by their local transforms — and the
//! whole repeats until v is within tolerance of v′.

use glam::{DQuat, DVec3};
#[cfg(feature = "json")]
use serde::{Deserialize, Serialize};

use super::EditError;
use super::controls::Controls;
use super::rigid::Motion;
use super::shapes::Shape;
use crate::bind::VertexBinding;
use crate::sweep::Key;
use crate::sweep::chord_length;

/// Which parts of the difference a drag applies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "json", serde(rename_all = "lowercase"))]
pub enum DragMode {
    /// Linear and angular parts (Fig. 9b).
    #[default]
    Both,
    /// The whole difference as a translation (Fig. 14b).
    Translate,
    /// The angular part alone (Fig. 14d): reaches targets on the sphere around the keys'
    /// centers through the point.
    Rotate,
}

/// How many keys below the point a drag edits by default.
pub const DEFAULT_DRAG_KEYS: usize = 2;

/// Drags the point bound by `point` (a surface point has d = h = 0) to `target` by editing up to
/// `k` keys below it; returns the rounds it took. Fails, naming the remaining distance, after
/// `controls.max_iterations` rounds.
pub fn drag_point(
    keys: &mut [Key],
    knots: &[f64],
    point: VertexBinding,
    target: DVec3,
    mode: DragMode,
    k: usize,
    controls: &Controls,
) -> Result<usize, EditError> {
    drag_point_kept(keys, knots, point, target, mode, k, controls, &mut Shape::default())
}

/// [`drag_point`] with the sweep's memo `shape`: each round moves keys rigidly, so it costs
/// time independent of the number of radii.
#[expect(clippy::too_many_arguments, reason = "drag_point's arguments and the memo")]
pub(super) fn drag_point_kept(
    keys: &mut [Key],
    knots: &[f64],
    point: VertexBinding,
    target: DVec3,
    mode: DragMode,
    k: usize,
    controls: &Controls,
    shape: &mut Shape,
) -> Result<usize, EditError> {
    let tolerance = controls.position_tolerance * chord_length(keys);
    let mut locate = |keys: &[Key]| -> Result<(DVec3, usize), EditError> {
        let sweep = shape.sweep(keys, knots).map_err(EditError::Degenerate)?;
        let VertexBinding { theta, t, d, h } = point;
        Ok((sweep.point(theta, t, d, h), sweep.locate(t).segment))
    };
    for iteration in 0..=controls.max_iterations {
        let (v, lower) = locate(keys)?;
        let remaining = v.distance(target);
        if remaining <= tolerance {
            return Ok(iteration);
        }
        if iteration == controls.max_iterations {
            return Err(EditError::NotConverged { iterations: iteration, remaining, angle: 0.0 });
        }
        let lowest = (lower + 1).saturating_sub(k.max(1));
        for m in lowest..=lower {
            let (v, _) = locate(keys)?;
            let share = 1.0 / (lower - m + 1) as f64;
            let motion = step(keys[m].center, v, target, mode, share);
            for key in &mut keys[m..] {
                motion.apply(key);
            }
        }
    }
    unreachable!("the loop returns on its last round")
}

/// The share `share` of the motion that brings `v` to `target` about pivot `p` in `mode`.
fn step(p: DVec3, v: DVec3, target: DVec3, mode: DragMode, share: f64) -> Motion {
    let (arm, reach) = (v - p, target - p);
    let turn = |to: DVec3| match (arm.try_normalize(), to.try_normalize()) {
        (Some(a), Some(b)) => DQuat::IDENTITY.slerp(DQuat::from_rotation_arc(a, b), share),
        _ => DQuat::IDENTITY,
    };
    match mode {
        DragMode::Translate => Motion::about(p, DQuat::IDENTITY, share * (target - v)),
        DragMode::Rotate => Motion::about(p, turn(reach), DVec3::ZERO),
        DragMode::Both => {
            let on_sphere = p + reach.normalize_or_zero() * arm.length();
            Motion::about(p, turn(on_sphere - p), share * (target - on_sphere))
        }
    }
}
