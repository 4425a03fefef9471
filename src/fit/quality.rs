//! How tightly a sweep fits a part: the distances d of the part's vertices from the sweep
//! surface (§3, Fig. 4), relative to the mean radius.

use glam::DVec3;

use crate::bind::{SweepBinder, VertexBinding};
use crate::sweep::Sweep;

/// The fit of a sweep to a part's vertices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitQuality {
    /// Vertices measured.
    pub vertices: usize,
    /// Vertices with no root of ⟨v − C(t), N(t)⟩ on [0, 1]: they lie beyond an end of the
    /// sweep and bind by end clamping. Zero for a finished fit.
    pub without_root: usize,
    /// The mean radius r(θ, t) of the sweep at the vertices' bindings, mesh units.
    pub mean_radius: f64,
    /// max |d| / mean radius.
    pub max_d: f64,
    /// RMS of d / mean radius.
    pub rms_d: f64,
}

/// A part's vertices bound to a sweep, with what the fit needs to judge and refine it.
#[derive(Clone, Debug)]
pub struct Measured {
    /// The fit as a whole.
    pub quality: FitQuality,
    /// Per knot interval, the RMS of d / mean radius over the vertices bound in it (0 for an
    /// interval no vertex binds in).
    pub interval_rms: Vec<f64>,
}

/// Binds `positions` to `sweep` and measures the fit.
pub fn measure(sweep: &Sweep, positions: &[DVec3]) -> Measured {
    let binder = SweepBinder::new(sweep);
    let knots = sweep.knots();
    let intervals = knots.len() - 1;
    let mut without_root = 0;
    let bindings: Vec<VertexBinding> = positions
        .iter()
        .map(|&v| {
            let (binding, rooted) = binder.bind_reporting_root(v);
            without_root += usize::from(!rooted);
            binding
        })
        .collect();
    let radius_sum: f64 = bindings.iter().map(|b| sweep.radius(b.theta, b.t)).sum();
    let mean_radius = radius_sum / bindings.len().max(1) as f64;
    let scale = if mean_radius > 0.0 { 1.0 / mean_radius } else { f64::INFINITY };
    let (mut sum_squares, mut max_d) = (0.0, 0.0f64);
    let mut interval_sums = vec![(0.0, 0usize); intervals];
    for b in &bindings {
        let d = (b.d * scale).abs();
        max_d = max_d.max(d);
        sum_squares += d * d;
        let interval = knots[1..intervals].partition_point(|&u| u <= b.t);
        interval_sums[interval].0 += d * d;
        interval_sums[interval].1 += 1;
    }
    let count = bindings.len().max(1) as f64;
    let quality =
        FitQuality { vertices: bindings.len(), without_root, mean_radius, max_d, rms_d: (sum_squares / count).sqrt() };
    let interval_rms =
        interval_sums.iter().map(|&(sum, n)| if n == 0 { 0.0 } else { (sum / n as f64).sqrt() }).collect();
    Measured { quality, interval_rms }
}
