//! The volume bounded by a sweep surface, Eq. 1: `V = ∫₀¹ A(t)·⟨N(t), C′(t)⟩ dt` with
//! `A(t) = ½ ∫₀^{2π} r(θ, t)² dθ` (valid while S has no self-intersection, as the paper notes).

use glam::DVec3;

use super::Sweep;
use super::quadrature::{integrate_adaptive, magnitude};
use super::radius::AreaPolynomial;

/// Relative accuracy the quadrature aims at; the contract is 1e-9.
const VOLUME_TOLERANCE: f64 = 1e-12;

impl Sweep {
    /// The volume of Eq. 1, in cubic mesh units, by adaptive Gauss–Legendre quadrature over each
    /// knot interval (A(t) itself is integrated exactly in θ, as a polynomial in t). Signed: a
    /// sweep whose normals point against its direction of travel has negative volume, and one
    /// whose normals lie across its direction of travel has a volume near zero.
    ///
    /// The accuracy is relative to ∫ A(t)·|C′(t)| dt, the volume the sweep would have with its
    /// normals along its travel, so a volume that cancels to near zero costs no more than any
    /// other: at most `super::quadrature::MAX_DEPTH` bisections per knot interval.
    pub fn volume(&self) -> f64 {
        self.volume_with_areas(&self.area_polynomials())
    }

    /// A(t) of Eq. 1 on each knot interval: it depends on the radii alone, so a sweep rebuilt
    /// by [`Sweep::try_with_axis`] has the same.
    pub fn area_polynomials(&self) -> Vec<AreaPolynomial> {
        (0..self.segments().len()).map(|k| AreaPolynomial::new(self.radius_field(), k)).collect()
    }

    /// [`Sweep::volume`] given `areas`, this sweep's [`Sweep::area_polynomials`]: the same
    /// value, in time independent of the number of radii.
    pub fn volume_with_areas(&self, areas: &[AreaPolynomial]) -> f64 {
        self.segments()
            .iter()
            .zip(areas)
            .map(|(segment, area)| {
                let h = segment.t1 - segment.t0;
                let mut integrand = |s: f64| {
                    let normal = segment.orientation.value(s) * DVec3::Z;
                    area.value(s) * normal.dot(segment.curve.derivative(s))
                };
                let scale = magnitude(0.0, 1.0, |s| area.value(s) * segment.curve.derivative(s).length());
                h * integrate_adaptive(0.0, 1.0, VOLUME_TOLERANCE, scale, &mut integrand)
            })
            .sum()
    }
}
