//! Direct control of an arbitrary cross-section (§4, Fig. 10): move the cross-section at t to a
//! target position and orientation by editing the keys nearest to it.
//!
//! Each round takes the rigid motion from the current frame (C(t), R(t)) to the target and
//! applies it to the keys bracketing t (the one key when t is a knot); the cross-section follows
//! them closely (R(t) exactly, C(t) up to the spline's coupling to farther keys), so a few rounds
//! bring it within tolerance. Several sections are driven together, one after the other in each
//! round — the hierarchy uses that to keep both ends of a loop attached.

use glam::{DQuat, DVec3};

use super::EditError;
use super::controls::Controls;
use super::rigid::{Motion, angle_between};
use super::shapes::Shape;
use crate::sweep::Key;
use crate::sweep::chord_length;

/// Where the cross-section at `t` should go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionTarget {
    /// The cross-section's axis parameter.
    pub t: f64,
    /// Target C(t).
    pub center: DVec3,
    /// Target R(t).
    pub rotation: DQuat,
}

/// Drives the cross-sections at every target's t to its frame; returns the rounds it took.
/// Fails, naming the remaining distance and angle, after `controls.max_iterations` rounds.
pub fn move_sections(
    keys: &mut [Key],
    knots: &[f64],
    targets: &[SectionTarget],
    controls: &Controls,
) -> Result<usize, EditError> {
    move_sections_kept(keys, knots, targets, controls, &mut Shape::default())
}

/// [`move_sections`] with the sweep's memo `shape`: each round moves keys rigidly, so it costs
/// time independent of the number of radii.
pub(super) fn move_sections_kept(
    keys: &mut [Key],
    knots: &[f64],
    targets: &[SectionTarget],
    controls: &Controls,
    shape: &mut Shape,
) -> Result<usize, EditError> {
    let tolerance = controls.position_tolerance * chord_length(keys);
    for iteration in 0..=controls.max_iterations {
        let sweep = shape.sweep(keys, knots).map_err(EditError::Degenerate)?;
        let (remaining, angle) = targets.iter().fold((0.0f64, 0.0f64), |(distance, angle), target| {
            let frame = (sweep.center(target.t), sweep.orientation(target.t));
            (distance.max(frame.0.distance(target.center)), angle.max(angle_between(frame.1, target.rotation)))
        });
        if remaining <= tolerance && angle <= controls.angle_tolerance {
            return Ok(iteration);
        }
        if iteration == controls.max_iterations {
            return Err(EditError::NotConverged { iterations: iteration, remaining, angle });
        }
        for target in targets {
            let sweep = shape.sweep(keys, knots).map_err(EditError::Degenerate)?;
            let (center, rotation) = (sweep.center(target.t), sweep.orientation(target.t));
            let motion = Motion::about(center, target.rotation * rotation.inverse(), target.center - center);
            let at = sweep.locate(target.t);
            let bracket = if at.s == 0.0 {
                at.segment..at.segment + 1
            } else if at.s == 1.0 {
                at.segment + 1..at.segment + 2
            } else {
                at.segment..at.segment + 2
            };
            for key in &mut keys[bracket] {
                motion.apply(key);
            }
        }
    }
    unreachable!("the loop returns on its last round")
}
