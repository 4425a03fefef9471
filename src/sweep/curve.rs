//! The center curve C(t) of a sweep: the C² natural cubic spline through the key centers p_i
//! at the knots u_i (§3; the paper's cubic B-spline with chord-length parametrization).

use glam::DVec3;

use super::cubic::CubicPiece;
use super::natural_spline::NaturalSplineSystem;

/// One cubic piece of C(t) per knot interval, a [`CubicPiece`] per coordinate.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePiece {
    /// The x, y and z pieces.
    pub axes: [CubicPiece; 3],
}

impl CurvePiece {
    /// C at local parameter `s ∈ [0, 1]`; exactly the key centers at `s = 0` and `s = 1`.
    pub fn value(&self, s: f64) -> DVec3 {
        let [x, y, z] = &self.axes;
        DVec3::new(x.value(s), y.value(s), z.value(s))
    }

    /// dC/dt at local parameter `s`.
    pub fn derivative(&self, s: f64) -> DVec3 {
        let [x, y, z] = &self.axes;
        DVec3::new(x.derivative(s), y.derivative(s), z.derivative(s))
    }

    /// d²C/dt² at local parameter `s`.
    pub fn second_derivative(&self, s: f64) -> DVec3 {
        let [x, y, z] = &self.axes;
        DVec3::new(x.second_derivative(s), y.second_derivative(s), z.second_derivative(s))
    }

    /// Power-basis coefficients `[a0, a1, a2, a3]` with `C(s) = a0 + a1·s + a2·s² + a3·s³`;
    /// `a0` is the piece's start center.
    pub fn power_coefficients(&self) -> [DVec3; 4] {
        let [x, y, z] = self.axes.map(|axis| axis.power_coefficients());
        std::array::from_fn(|i| DVec3::new(x[i], y[i], z[i]))
    }
}

/// The pieces of the natural spline through `centers` at `knots`: one factorization of the
/// knots' system, solved for x, y and z.
pub fn center_curve(knots: &[f64], centers: &[DVec3]) -> Vec<CurvePiece> {
    let system = NaturalSplineSystem::new(knots);
    let mut m = vec![0.0; knots.len()];
    let mut axis = |pick: fn(&DVec3) -> f64| {
        let values: Vec<f64> = centers.iter().map(pick).collect();
        system.second_derivatives_into(&values, &mut m);
        (values, m.clone())
    };
    let (x, y, z) = (axis(|p| p.x), axis(|p| p.y), axis(|p| p.z));
    (0..knots.len() - 1)
        .map(|i| CurvePiece { axes: [&x, &y, &z].map(|(values, m)| system.piece(values, m, i)) })
        .collect()
}
