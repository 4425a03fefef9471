//! Range checks of a bindings file's records, so that a damaged or hand-made file is refused on
//! load instead of deforming into huge or non-finite positions (or into different positions on
//! the CPU and the GPU).
//!
//! Without the rig ([`params`], [`sweep`]): θ ∈ [0, 2π], t ∈ [0, 1], d and h finite, sweeps in
//! range. θ = 2π itself is the same angle as 0 on every path (the radius is periodic), and
//! bindings made on the GPU can hold it: their θ = (j + φ)·2π/M is 2π at j = M − 1, φ = 1. With the rig and mesh ([`offset_bound`]): |d| and |h| at most
//! B = 2·(L + R), where L is the diagonal of the box that holds the mesh's vertices and every
//! rest sweep's center curve C(t), and R bounds the rest radii |r(θ, t)|. A binding made by
//! `sweepffd bind` has |h| ≤ |v − C(t)| ≤ L and |d| ≤ |v − C(t)| + |r(θ, t)| ≤ L + R, since v
//! is a mesh vertex and C(t) lies on a rest sweep; the factor 2 leaves room for round-off.

use std::f64::consts::TAU;

use glam::DVec3;

use crate::bind::{UNOWNED, VertexBinding};
use crate::sweep::Sweep;
use crate::sweep::cubic::CubicPiece;

/// A number as a message shows it: plainly, or in exponent form when very large or small.
pub fn number(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-6..1e16).contains(&x.abs()) { format!("{x:e}") } else { format!("{x}") }
}

/// Why `params` cannot be a binding (θ, t, d, h) of a vertex to a sweep, if they cannot.
pub fn params(params: &VertexBinding) -> Result<(), String> {
    let VertexBinding { t, theta, d, h } = *params;
    if !(0.0..=1.0).contains(&t) {
        return Err(format!("t = {} is outside [0, 1]", number(t)));
    }
    if !(0.0..=TAU).contains(&theta) {
        return Err(format!("θ = {} is outside [0, 2π]", number(theta)));
    }
    for (name, value) in [("d", d), ("h", h)] {
        if !value.is_finite() {
            return Err(format!("{name} = {} is not finite", number(value)));
        }
    }
    Ok(())
}

/// Why `sweep` does not name one of `sweep_count` sweeps (nor [`UNOWNED`]), if it does not.
pub fn sweep(sweep: u32, sweep_count: u32, what: &str) -> Result<(), String> {
    if sweep == UNOWNED || sweep < sweep_count {
        return Ok(());
    }
    let plural = if sweep_count == 1 { "" } else { "s" };
    Err(format!("{what} {sweep} is out of range: the rig has {sweep_count} sweep{plural}"))
}

/// B, the largest |d| and |h| a binding of `positions` to the `rest` sweeps may have (see the
/// module docs). Computed from the spline pieces' coefficients, so it bounds the center curves
/// and radii everywhere, not only at the keys.
pub fn offset_bound(rest: &[Sweep], positions: &[DVec3]) -> f64 {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for p in positions {
        (lo, hi) = (lo.min(*p), hi.max(*p));
    }
    let mut radius = 0.0f64;
    for sweep in rest {
        for segment in sweep.segments() {
            for (axis, piece) in segment.curve.axes.iter().enumerate() {
                let (a, b) = piece_range(piece);
                lo[axis] = lo[axis].min(a);
                hi[axis] = hi[axis].max(b);
            }
        }
        let field = sweep.radius_field();
        for segment in 0..sweep.segments().len() {
            for j in 0..field.samples() {
                // On [0, 1]², |Σ c_pq s^p φ^q| ≤ Σ |c_pq|.
                radius = radius.max(field.patch(segment, j).c.iter().flatten().map(|c| c.abs()).sum());
            }
        }
    }
    let diagonal = if lo.cmple(hi).all() { (hi - lo).length() } else { 0.0 };
    2.0 * (diagonal + radius)
}

/// An interval holding a cubic piece's values on s ∈ [0, 1]: its chord's plus the cubic terms,
/// each at most h²/6 · 2/(3√3) · |m| (the largest |s³ − s| on [0, 1] is 2/(3√3) < 0.385).
fn piece_range(piece: &CubicPiece) -> (f64, f64) {
    let wiggle = piece.h * piece.h / 6.0 * 0.385 * (piece.m0.abs() + piece.m1.abs());
    (piece.y0.min(piece.y1) - wiggle, piece.y0.max(piece.y1) + wiggle)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::{Tube, tube_rig};

    const AT_REST: VertexBinding = VertexBinding { t: 0.5, theta: 1.0, d: 0.1, h: 0.0 };

    #[test]
    fn numbers_print_plainly_unless_huge_or_tiny() {
        assert_eq!(number(6.5), "6.5");
        assert_eq!(number(0.0), "0");
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(-2.5e-9), "-2.5e-9");
        assert_eq!(number(f64::NAN), "NaN");
        assert_eq!(number(f64::NEG_INFINITY), "-inf");
    }

    #[test]
    fn theta_beyond_two_pi_is_refused() {
        assert_eq!(params(&AT_REST), Ok(()));
        assert_eq!(params(&VertexBinding { theta: TAU, ..AT_REST }), Ok(()));
        let refused = |theta: f64| params(&VertexBinding { theta, ..AT_REST }).unwrap_err();
        assert_eq!(refused(6.5), "θ = 6.5 is outside [0, 2π]");
        assert_eq!(refused(1e300), "θ = 1e300 is outside [0, 2π]");
        assert_eq!(refused(-0.5), "θ = -0.5 is outside [0, 2π]");
        assert_eq!(refused(f64::NAN), "θ = NaN is outside [0, 2π]");
    }

    #[test]
    fn t_outside_the_unit_interval_and_non_finite_offsets_are_refused() {
        assert_eq!(params(&VertexBinding { t: 1.5, ..AT_REST }).unwrap_err(), "t = 1.5 is outside [0, 1]");
        assert_eq!(params(&VertexBinding { d: f64::INFINITY, ..AT_REST }).unwrap_err(), "d = inf is not finite");
        assert_eq!(params(&VertexBinding { h: f64::NAN, ..AT_REST }).unwrap_err(), "h = NaN is not finite");
    }

    #[test]
    fn sweeps_past_the_rig_are_refused() {
        assert_eq!(sweep(0, 1, "sweep"), Ok(()));
        assert_eq!(sweep(UNOWNED, 1, "sweep"), Ok(()));
        assert_eq!(sweep(1, 1, "sweep").unwrap_err(), "sweep 1 is out of range: the rig has 1 sweep");
        assert_eq!(sweep(7, 2, "second sweep").unwrap_err(), "second sweep 7 is out of range: the rig has 2 sweeps");
    }

    #[test]
    fn the_bound_holds_every_binding_of_a_tube_and_is_of_its_size() {
        let tube = Tube { rings: 6, around: 16, length: 4.0, radius: 0.5 };
        let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 5, 8));
        let bound = offset_bound(rig.rest(), &mesh.positions);
        // The box is 1 × 1 × 4 (diagonal √18), the radius 0.5: B = 2·(√18 + 0.5) up to the
        // cubic terms of a straight spline, which vanish.
        assert!((bound - 2.0 * (18f64.sqrt() + 0.5)).abs() < 1e-9, "{bound}");
        let owners = vec![0; mesh.positions.len()];
        let bindings = crate::bind::bind_vertices(rig.rest(), &owners, &mesh.positions, &|_| {});
        for b in &bindings {
            assert!(b.params.d.abs() <= bound && b.params.h.abs() <= bound, "{b:?}");
        }
    }
}
