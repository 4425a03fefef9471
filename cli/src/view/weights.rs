//! The weight paint (K): each vertex coloured by the share w of its own sweep's deformation it
//! follows, so that a user sees where the deformation fades (see [`sweepffd::bind::falloff`]).
//! w = 1 (owned, outside every band) is red, w = 0 (unowned, or a band's edge that keeps its rest
//! position) blue, and the band runs through teal, yellow (w = ½) and orange between.
//!
//! The colours are computed on the CPU when the weights change (a new rig, a new falloff width)
//! and uploaded once; drawing them costs nothing per frame.

use sweepffd::bind::UNOWNED;
use sweepffd::bind::falloff::BandWeight;

/// The ramp's stops: (w, linear RGB), w increasing from 0 to 1. Linear between stops.
pub const WEIGHT_RAMP: [(f32, [f32; 3]); 5] = [
    (0.0, [0.03, 0.12, 0.60]),
    (0.25, [0.02, 0.45, 0.50]),
    (0.5, [0.90, 0.80, 0.05]),
    (0.75, [0.90, 0.32, 0.02]),
    (1.0, [0.55, 0.05, 0.03]),
];

/// The weight w of every vertex: 1 for an owned vertex outside the bands, its band weight in a
/// band, 0 for an unowned one. `bands` are sorted by vertex.
pub fn vertex_weights(owners: &[u32], bands: &[BandWeight]) -> Vec<f32> {
    let mut weights: Vec<f32> = owners.iter().map(|&o| if o == UNOWNED { 0.0 } else { 1.0 }).collect();
    for band in bands {
        weights[band.vertex as usize] = band.weight as f32;
    }
    weights
}

/// The linear RGB of the ramp at `w` (clamped to [0, 1]).
pub fn ramp(w: f32) -> [f32; 3] {
    let w = w.clamp(0.0, 1.0);
    let upper = WEIGHT_RAMP.iter().position(|&(at, _)| at >= w).unwrap_or(WEIGHT_RAMP.len() - 1).max(1);
    let ((w0, c0), (w1, c1)) = (WEIGHT_RAMP[upper - 1], WEIGHT_RAMP[upper]);
    let t = (w - w0) / (w1 - w0);
    std::array::from_fn(|i| (1.0 - t) * c0[i] + t * c1[i])
}

/// One linear RGBA colour per vertex, 8 bits a channel (the mesh pipeline's per-vertex colour).
pub fn weight_colours(owners: &[u32], bands: &[BandWeight]) -> Vec<[u8; 4]> {
    let unorm8 = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    vertex_weights(owners, bands)
        .into_iter()
        .map(|w| {
            let [r, g, b] = ramp(w);
            [unorm8(r), unorm8(g), unorm8(b), 255]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_hits_its_stops_and_interpolates_between() {
        for (w, colour) in WEIGHT_RAMP {
            assert_eq!(ramp(w), colour, "w = {w}");
        }
        let between = ramp(0.625);
        let expected: Vec<f32> = (0..3).map(|i| 0.5 * (WEIGHT_RAMP[2].1[i] + WEIGHT_RAMP[3].1[i])).collect();
        assert!(between.iter().zip(&expected).all(|(a, b)| (a - b).abs() < 1e-6), "{between:?}");
        assert_eq!(ramp(-1.0), WEIGHT_RAMP[0].1);
        assert_eq!(ramp(2.0), WEIGHT_RAMP[4].1);
    }

    #[test]
    fn owned_vertices_weigh_one_unowned_zero_and_band_vertices_their_weight() {
        let owners = [0, 0, UNOWNED, 1, 1];
        let bands = [
            BandWeight { vertex: 1, weight: 0.25, neighbour: UNOWNED },
            BandWeight { vertex: 3, weight: 0.5, neighbour: 0 },
        ];
        assert_eq!(vertex_weights(&owners, &bands), vec![1.0, 0.25, 0.0, 0.5, 1.0]);
        let colours = weight_colours(&owners, &bands);
        assert_eq!(colours[2], [8, 31, 153, 255], "w = 0: blue");
        assert_eq!(colours[3], [230, 204, 13, 255], "w = ½: yellow");
        assert_eq!(colours[0], [140, 13, 8, 255], "w = 1: red");
    }
}
