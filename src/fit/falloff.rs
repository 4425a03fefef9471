//! The falloff width W a fitted sweep gets: the band, measured along the surface from the
//! part's boundary, over which its deformation fades into the rest of the mesh (rig field
//! `falloff`, see [`crate::bind::falloff`]).

use crate::sweep::{Key, chord_length};

/// The default falloff width as a fraction of the part's length, the chord length
/// L = Σ_i |p_i − p_{i−1}| of the fitted key centers: W = 0.3 L.
pub const DEFAULT_FALLOFF_FRACTION: f64 = 0.3;

/// W: `requested` where given (0 is a hard boundary), else [`DEFAULT_FALLOFF_FRACTION`] × the
/// chord length of the centers of `keys` (0 for fewer than two keys).
pub fn falloff_width(requested: Option<f64>, keys: &[Key]) -> f64 {
    requested.unwrap_or_else(|| DEFAULT_FALLOFF_FRACTION * chord_length(keys))
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};

    use super::*;

    #[test]
    fn the_default_width_is_a_fraction_of_the_chord_length() {
        let keys: Vec<Key> = [DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0), DVec3::new(3.0, 4.0, 2.0)]
            .into_iter()
            .map(|center| Key::circle(center, DQuat::IDENTITY, 1.0, 4))
            .collect();
        assert!((falloff_width(None, &keys) - DEFAULT_FALLOFF_FRACTION * 7.0).abs() < 1e-12);
        assert_eq!(falloff_width(Some(0.0), &keys), 0.0);
        assert_eq!(falloff_width(Some(1.25), &keys), 1.25);
        assert_eq!(falloff_width(None, &keys[..1]), 0.0);
    }
}
