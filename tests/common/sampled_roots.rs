//! The binding function f(t) = ⟨v − C(t), N(t)⟩ sampled densely, as an oracle for the roots that
//! binding finds through its polynomials.

use glam::DVec3;
use sweepffd::sweep::Sweep;

/// Samples of f over [0, 1] for the dense search for roots.
pub const SAMPLES: usize = 2048;

/// f(t) = ⟨v − C(t), N(t)⟩ on `sweep`.
pub fn f(sweep: &Sweep, v: DVec3, t: f64) -> f64 {
    (v - sweep.center(t)).dot(sweep.normal(t))
}

/// The distance from v to C at the nearest root of f that dense sampling brackets, each
/// bracketed root refined by bisection on f itself (not through the binding polynomial).
pub fn nearest_sampled_root(sweep: &Sweep, v: DVec3) -> Option<f64> {
    let mut nearest: Option<f64> = None;
    let mut previous = (0.0, f(sweep, v, 0.0));
    for i in 1..=SAMPLES {
        let t = i as f64 / SAMPLES as f64;
        let value = f(sweep, v, t);
        if (previous.1 >= 0.0) != (value >= 0.0) {
            let (mut lo, mut hi, positive_at_lo) = (previous.0, t, previous.1 >= 0.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if (f(sweep, v, mid) >= 0.0) == positive_at_lo { lo = mid } else { hi = mid }
            }
            let distance = sweep.center(0.5 * (lo + hi)).distance(v);
            nearest = Some(nearest.map_or(distance, |n| n.min(distance)));
        }
        previous = (t, value);
    }
    nearest
}
