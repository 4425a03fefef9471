//! The polynomial whose roots are the cross-section planes through a point (§3, binding).
//!
//! On knot interval k, f(t) = ⟨v − C(t), N(t)⟩ = g(s) / |q(s)|² where
//! `g(s) = ⟨v − C(s), n(s)⟩`, n(s) is the unnormalized normal (see
//! [`OrientationPiece::normal_numerator`](super::orientation::OrientationPiece::normal_numerator)),
//! quadratic for the linear rotation interpolation and of degree 6 for the cubic one, and C is
//! cubic, so g is a quintic or a nonic. Relative to the interval's start p_k, with w = v − p_k:
//!
//! ```text
//! g(s) = Σ_m (w·n_m − e_m)·s^m        (e_0 = 0)
//! ```
//!
//! where e_m are the coefficients of ⟨C(s) − p_k, n(s)⟩. Working relative to p_k avoids
//! cancellation far from the origin.

use glam::DVec3;

use super::Segment;

/// The highest degree of g: 9, for the cubic rotation interpolation.
pub const MAX_DEGREE: usize = 9;

/// Power-basis coefficients `[a0, …, a9]` of `g(s) = Σ a_i·s^i`; those past the degree are 0.
pub type PlaneCoefficients = [f64; MAX_DEGREE + 1];

/// The vertex-independent part of the plane polynomial of one knot interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanePolynomial {
    /// p_k, the interval's start center.
    pub origin: DVec3,
    /// n0 … n6 (n3 … n6 zero for the linear interpolation).
    pub normal: [DVec3; 7],
    /// e1 … e9 (e6 … e9 zero for the linear interpolation).
    pub curve_dot_normal: [f64; MAX_DEGREE],
    /// The degree of g: 5 (linear interpolation) or 9 (cubic).
    pub degree: usize,
}

impl PlanePolynomial {
    /// The plane polynomial of `segment`.
    pub fn new(segment: &Segment) -> PlanePolynomial {
        let c = segment.curve.power_coefficients();
        let normal = segment.orientation.normal_numerator();
        let curve_dot_normal = std::array::from_fn(|index| {
            let m = index + 1;
            (1..=3.min(m)).filter(|&i| m - i < 7).fold(0.0, |sum, i| sum + c[i].dot(normal[m - i]))
        });
        let degree = if segment.orientation.cubic { 9 } else { 5 };
        PlanePolynomial { origin: c[0], normal, curve_dot_normal, degree }
    }

    /// Power-basis coefficients of g for vertex v.
    pub fn for_vertex(&self, v: DVec3) -> PlaneCoefficients {
        let w = v - self.origin;
        // n_m is zero past m = 2 for the quintic and past m = 6 for the nonic.
        let normals = if self.degree == 5 { 3 } else { 7 };
        std::array::from_fn(|m| {
            let along = if m < normals { w.dot(self.normal[m]) } else { 0.0 };
            if m == 0 { along } else { along - self.curve_dot_normal[m - 1] }
        })
    }
}
