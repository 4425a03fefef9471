//! Iteration limits and tolerances of the direct controls and the hierarchy rules.

/// How far the iterative controls go: at most `max_iterations` rounds, stopping when the
/// position error is below `position_tolerance` × the sweep's length (its keys' chord length)
/// and the orientation error below `angle_tolerance` radians.
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
