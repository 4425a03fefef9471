//! The quintic whose roots are the cross-section planes through a point (§3, binding).
//!
//! On knot interval k, f(t) = ⟨v − C(t), N(t)⟩ = g(s) / |q(s)|² where
//! `g(s) = ⟨v − C(s), n(s)⟩`, `n(s) = n0 + n1·s + n2·s²` is the unnormalized normal (see
//! [`OrientationPiece::normal_numerator`](super::orientation::OrientationPiece::normal_numerator))
//! and C is cubic, so g has degree 5. Relative to the interval's start p_k, with w = v − p_k:
//!
//! ```text
//! g(s) = w·n0 + (w·n1 − e1)·s + (w·n2 − e2)·s² − e3·s³ − e4·s⁴ − e5·s⁵
//! ```
//!
//! where e_i are the coefficients of ⟨C(s) − p_k, n(s)⟩. Working relative to p_k avoids
//! cancellation far from the origin.

use glam::DVec3;

use super::Segment;

/// The vertex-independent part of the plane quintic of one knot interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneQuintic {
    /// p_k, the interval's start center.
    pub origin: DVec3,
    /// n0, n1, n2.
    pub normal: [DVec3; 3],
    /// e1 … e5.
    pub curve_dot_normal: [f64; 5],
}

impl PlaneQuintic {
    /// The plane quintic of `segment`.
    pub fn new(segment: &Segment) -> PlaneQuintic {
        let [p, c1, c2, c3] = segment.curve.power_coefficients();
        let [n0, n1, n2] = segment.orientation.normal_numerator();
        PlaneQuintic {
            origin: p,
            normal: [n0, n1, n2],
            curve_dot_normal: [
                c1.dot(n0),
                c1.dot(n1) + c2.dot(n0),
                c1.dot(n2) + c2.dot(n1) + c3.dot(n0),
                c2.dot(n2) + c3.dot(n1),
                c3.dot(n2),
            ],
        }
    }

    /// Power-basis coefficients of g for vertex v.
    pub fn for_vertex(&self, v: DVec3) -> [f64; 6] {
        let w = v - self.origin;
        let [n0, n1, n2] = self.normal;
        let e = self.curve_dot_normal;
        [w.dot(n0), w.dot(n1) - e[0], w.dot(n2) - e[1], -e[2], -e[3], -e[4]]
    }
}
