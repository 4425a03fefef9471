//! Iteration limits and tolerances of the direct controls and the hierarchy rules.

/// How far the iterative controls go: at most `max_iterations` rounds, stopping when the
/// position error is below `position_tolerance` × the sweep's length (its keys' chord length)
/// and the orientation error below `angle_tolerance` radians.
///
/// The work of an edit is bounded by these caps: a drag rebuilds its sweep at most
/// `max_iterations` × (edited keys + 1) times, a cross-section move `max_iterations` ×
/// (targets + 1) times, and a volume rule runs at most 21 rounds of rescaling and downward
/// propagation, each volume (Eq. 1) taking at most 2⁸ quadrature leaves per knot interval.
/// A rebuild after a rigid move keeps the radius function and costs time linear in the keys;
/// one after a change of radii is linear in keys × radii, and a volume rule's uniform rescale
/// keeps the radius function with one more scale factor (see `shapes`), so that beyond one
/// pass over the rescaled radii the whole is linear in the rig's keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controls {
    /// Rounds before an edit is reported as not converging. Default 50.
    pub max_iterations: usize,
    /// Position tolerance relative to the sweep's length. Default 1e-6.
    pub position_tolerance: f64,
    /// Orientation tolerance in radians. Default 1e-6.
    pub angle_tolerance: f64,
}

impl Default for Controls {
    fn default() -> Controls {
        Controls { max_iterations: 50, position_tolerance: 1e-6, angle_tolerance: 1e-6 }
    }
}
