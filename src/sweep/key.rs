//! Key cross-sections X_i (§3): the data a sweep interpolates.

use glam::{DQuat, DVec3};

/// One key cross-section X_i of a sweep.
///
/// The cross-section lives in the plane through `center` whose normal N is the local z axis of
/// `rotation`; θ = 0 lies along the local x axis and θ turns counter-clockwise about z. The
/// radii ρ_ij are the distances from the center to the cross-section's boundary at
/// θ_j = 2πj/M, j = 0..M−1.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    /// Center p_i of the cross-section, in mesh units.
    pub center: DVec3,
    /// Orientation q_i of the cross-section's frame; normalized when a sweep is built, so any
    /// non-zero quaternion is accepted.
    pub rotation: DQuat,
    /// Radii ρ_ij at θ_j = 2πj/M; at least three, none negative.
    pub radii: Vec<f64>,
}

impl Key {
    /// A circular key of radius `radius` with `samples` radii.
    pub fn circle(center: DVec3, rotation: DQuat, radius: f64, samples: usize) -> Key {
        Key { center, rotation, radii: vec![radius; samples] }
    }
}

/// The chord length L = Σ |p_i − p_{i−1}| of `keys`' centers: a sweep's length for tolerances,
/// falloff widths and likeness.
pub fn chord_length(keys: &[Key]) -> f64 {
    keys.windows(2).map(|pair| pair[0].center.distance(pair[1].center)).sum()
}
