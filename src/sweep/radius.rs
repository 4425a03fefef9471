//! The radius function r(θ, t) of a sweep (§3): the tensor-product interpolating cubic spline
//! of the key radii ρ_ij — periodic C² in θ over the M uniform nodes θ_j = 2πj/M, natural in t
//! over the knots u_i.
//!
//! On knot interval k and angular interval j the function is one bicubic polynomial, a
//! [`RadiusPatch`], in the local parameters `s = (t − u_k)/(u_{k+1} − u_k)` and
//! `φ = (θ − θ_j)/(2π/M)`, both in [0, 1].

use std::f64::consts::TAU;
use std::sync::Arc;

use super::natural_spline::NaturalSplineSystem;
use super::periodic_spline::PeriodicSplineSystem;

/// r on one (knot interval, angular interval) cell: `r(s, φ) = Σ_p Σ_q c[p][q]·s^p·φ^q`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadiusPatch {
    /// Power-basis coefficients, indexed `[power of s][power of φ]`.
    pub c: [[f64; 4]; 4],
}

impl RadiusPatch {
    /// r at local parameters `(s, φ)`.
    pub fn value(&self, s: f64, phi: f64) -> f64 {
        let row = |p: usize| {
            let c = &self.c[p];
            c[0] + phi * (c[1] + phi * (c[2] + phi * c[3]))
        };
        row(0) + s * (row(1) + s * (row(2) + s * row(3)))
    }
}

/// The angular interval `j` and local parameter `φ ∈ [0, 1)` of angle `theta` (any real; it is
/// wrapped into [0, 2π)) on `samples` uniform nodes.
pub fn angular_cell(theta: f64, samples: usize) -> (usize, f64) {
    let x = theta.rem_euclid(TAU) / TAU * samples as f64;
    let j = (x.floor() as usize).min(samples - 1);
    (j, x - j as f64)
}

/// All radius patches of one sweep, knot interval by knot interval, times one scale factor:
/// r = scale · Σ c·s^p·φ^q, so that a uniform rescale of the radii (§5) costs no time.
#[derive(Clone, Debug, PartialEq)]
pub struct RadiusField {
    pub(super) samples: usize,
    /// The patches as built, shared with the fields scaled from them.
    pub(super) patches: Arc<Vec<RadiusPatch>>,
    /// The factor every coefficient is multiplied by when read (1 as built).
    pub(super) scale: f64,
}

impl RadiusField {
    /// Builds r from `radii[i][j]` = ρ_ij at `knots[i]` and θ_j. The caller guarantees at least
    /// two keys, increasing knots, and the same number M ≥ 3 of radii on every key.
    pub fn new(knots: &[f64], radii: &[&[f64]]) -> RadiusField {
        let samples = radii[0].len();
        let segments = knots.len() - 1;
        // Natural spline in t through each angular node: power coefficients a_p(k, j).
        let along = NaturalSplineSystem::new(knots);
        let (mut column, mut m) = (vec![0.0; knots.len()], vec![0.0; knots.len()]);
        let mut along_t = vec![[0.0; 4]; segments * samples];
        for j in 0..samples {
            for (value, key) in column.iter_mut().zip(radii) {
                *value = key[j];
            }
            along.second_derivatives_into(&column, &mut m);
            for k in 0..segments {
                along_t[k * samples + j] = along.piece(&column, &m, k).power_coefficients();
            }
        }
        // Periodic spline in θ through each power coefficient: the bicubic c[p][q].
        let around = PeriodicSplineSystem::new(samples, TAU / samples as f64);
        let (mut row, mut scratch, mut m) = (vec![0.0; samples], vec![0.0; samples], vec![0.0; samples]);
        let mut patches = vec![RadiusPatch { c: [[0.0; 4]; 4] }; segments * samples];
        for (cells, patch_row) in along_t.chunks(samples).zip(patches.chunks_mut(samples)) {
            for p in 0..4 {
                for (value, cell) in row.iter_mut().zip(cells) {
                    *value = cell[p];
                }
                around.second_derivatives_into(&row, &mut scratch, &mut m);
                for (j, patch) in patch_row.iter_mut().enumerate() {
                    patch.c[p] = around.piece(&row, &m, j).power_coefficients();
                }
            }
        }
        RadiusField { samples, patches: Arc::new(patches), scale: 1.0 }
    }

    /// r after the radii of key `key` changed by `delta` (ρ_key,j += delta\[j\]), on the
    /// knots `knots` the field was built on; returns the knot intervals it changed (the others
    /// are bit for bit as they were). The spline is linear in the radii: the change is the
    /// tensor product of the natural spline in t through the unit impulse at `key`, b_k(s), and
    /// the periodic spline in θ through `delta`, D_j(φ), added to the patches in place (copied
    /// first if shared). Equal up to rounding to the field built from the changed radii; the
    /// intervals where |b_k| < 10⁻¹⁷·max|b| (it decays by about 3.7 per knot) would change by
    /// under half an ulp and are left alone, so the cost is about 30·M, not n·M.
    pub fn add_to_key(&mut self, knots: &[f64], key: usize, delta: &[f64]) -> std::ops::Range<usize> {
        let samples = self.samples;
        let mut impulse = vec![0.0; knots.len()];
        impulse[key] = 1.0;
        let along = NaturalSplineSystem::new(knots);
        let mut m = vec![0.0; knots.len()];
        along.second_derivatives_into(&impulse, &mut m);
        let b: Vec<[f64; 4]> =
            (0..knots.len() - 1).map(|k| along.piece(&impulse, &m, k).power_coefficients()).collect();
        let size = |c: &[f64; 4]| c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let largest = b.iter().map(size).fold(0.0, f64::max);
        let first = b.iter().position(|c| size(c) >= 1e-17 * largest).unwrap_or(0);
        let last = b.iter().rposition(|c| size(c) >= 1e-17 * largest).unwrap_or(0);
        let around = PeriodicSplineSystem::new(samples, TAU / samples as f64);
        let (mut scratch, mut md) = (vec![0.0; samples], vec![0.0; samples]);
        around.second_derivatives_into(delta, &mut scratch, &mut md);
        let unscale = 1.0 / self.scale;
        let d: Vec<[f64; 4]> =
            (0..samples).map(|j| around.piece(delta, &md, j).power_coefficients().map(|x| x * unscale)).collect();
        let patches = Arc::make_mut(&mut self.patches);
        for (bk, row) in b[first..=last].iter().zip(patches[first * samples..(last + 1) * samples].chunks_mut(samples))
        {
            for (patch, dj) in row.iter_mut().zip(&d) {
                for (row, b) in patch.c.iter_mut().zip(bk) {
                    for (c, d) in row.iter_mut().zip(dj) {
                        *c += b * d;
                    }
                }
            }
        }
        first..last + 1
    }

    /// M, the number of radii per key.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// r scaled by `factor`: the field of every ρ_ij multiplied by `factor`, up to rounding (the
    /// spline is linear in the radii), in constant time: the patches are shared and the scale
    /// factor multiplied.
    pub fn scaled(&self, factor: f64) -> RadiusField {
        RadiusField { samples: self.samples, patches: Arc::clone(&self.patches), scale: self.scale * factor }
    }

    /// The patch on knot interval `segment` and angular interval `j`, its coefficients times
    /// the field's scale factor.
    pub fn patch(&self, segment: usize, j: usize) -> RadiusPatch {
        let patch = self.patches[segment * self.samples + j];
        if self.scale == 1.0 {
            patch
        } else {
            let scale = self.scale;
            RadiusPatch { c: patch.c.map(|row| row.map(|c| c * scale)) }
        }
    }

    /// r(θ, t) on knot interval `segment` at local parameter `s`.
    pub fn value(&self, segment: usize, s: f64, theta: f64) -> f64 {
        let (j, phi) = angular_cell(theta, self.samples);
        self.patch(segment, j).value(s, phi)
    }

    /// Cross-section area A = ½ ∫₀^{2π} r(θ, t)² dθ on knot interval `segment` at local
    /// parameter `s`.
    pub fn area(&self, segment: usize, s: f64) -> f64 {
        AreaPolynomial::new(self, segment).value(s)
    }
}

/// A(s) = ½ ∫₀^{2π} r(θ, s)² dθ on one knot interval as the degree-6 polynomial it is (r is
/// cubic in s), integrated in θ exactly: with r = Σ_p s^p Σ_q c\[p\]\[q\] φ^q on each angular
/// interval, ∫₀¹ φ^q φ^q′ dφ = 1/(q + q′ + 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaPolynomial {
    /// Power-basis coefficients in s.
    pub a: [f64; 7],
}

impl AreaPolynomial {
    /// The area polynomial of knot interval `segment` of `field`: with H the 4×4 matrix
    /// H\[q\]\[q′\] = 1/(q + q′ + 1) and c_p the row c\[p\] of a patch, the coefficient of s^(p+p′)
    /// gathers c_p·H·c_p′ over the angular intervals, times the field's scale squared.
    pub fn new(field: &RadiusField, segment: usize) -> AreaPolynomial {
        let samples = field.samples;
        let mut a = [0.0; 7];
        for patch in &field.patches[segment * samples..(segment + 1) * samples] {
            let c = &patch.c;
            // H·c_p, once per row.
            let hc = c.map(|row| HILBERT.map(|h| h[0] * row[0] + h[1] * row[1] + h[2] * row[2] + h[3] * row[3]));
            for p in 0..4 {
                a[2 * p] += dot(&c[p], &hc[p]);
                for p2 in p + 1..4 {
                    a[p + p2] += 2.0 * dot(&c[p], &hc[p2]);
                }
            }
        }
        let factor = 0.5 * TAU / samples as f64 * field.scale * field.scale;
        AreaPolynomial { a: a.map(|x| x * factor) }
    }

    /// A of the radii scaled by `factor`: A scaled by factor² (up to rounding).
    pub fn scaled(&self, factor: f64) -> AreaPolynomial {
        let square = factor * factor;
        AreaPolynomial { a: self.a.map(|x| x * square) }
    }

    /// A at local parameter `s`.
    pub fn value(&self, s: f64) -> f64 {
        self.a.iter().rev().fold(0.0, |acc, &c| acc * s + c)
    }
}

/// H\[q\]\[q′\] = ∫₀¹ φ^q φ^q′ dφ = 1/(q + q′ + 1), the Hilbert matrix of order 4.
const HILBERT: [[f64; 4]; 4] = [
    [1.0, 1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0],
    [1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0, 1.0 / 5.0],
    [1.0 / 3.0, 1.0 / 4.0, 1.0 / 5.0, 1.0 / 6.0],
    [1.0 / 4.0, 1.0 / 5.0, 1.0 / 6.0, 1.0 / 7.0],
];

fn dot(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn interpolates_every_key_radius() {
        let knots = [0.0, 0.3, 1.0];
        let radii: [&[f64]; 3] = [&[1.0, 2.0, 1.5, 0.5], &[0.7, 0.7, 0.9, 1.1], &[2.0, 1.0, 3.0, 2.5]];
        let field = RadiusField::new(&knots, &radii);
        for (i, key) in radii.iter().enumerate() {
            for (j, rho) in key.iter().enumerate() {
                let theta = TAU * j as f64 / 4.0;
                let (segment, s) = if i < 2 { (i, 0.0) } else { (1, 1.0) };
                assert!((field.value(segment, s, theta) - rho).abs() < 1e-14, "key {i}, node {j}");
            }
        }
    }

    #[test]
    fn constant_radius_has_circle_area() {
        let field = RadiusField::new(&[0.0, 1.0], &[&[2.0; 6], &[2.0; 6]]);
        assert!((field.area(0, 0.4) - PI * 4.0).abs() < 1e-13);
    }

    #[test]
    fn area_polynomial_matches_quadrature_of_r_squared() {
        let knots = [0.0, 0.4, 1.0];
        let radii: [&[f64]; 3] = [&[1.0, 2.0, 1.5, 0.5, 0.9], &[0.7, 0.7, 0.9, 1.1, 1.3], &[2.0, 1.0, 3.0, 2.5, 0.4]];
        let field = RadiusField::new(&knots, &radii);
        let rule = crate::sweep::quadrature::gauss_legendre_4();
        for segment in 0..2 {
            for s in [0.0, 0.3, 0.77, 1.0] {
                let step = TAU / 5.0;
                let expected: f64 = (0..5)
                    .map(|j| 0.5 * step * rule.integrate(0.0, 1.0, |phi| field.patch(segment, j).value(s, phi).powi(2)))
                    .sum();
                assert!((field.area(segment, s) - expected).abs() < 1e-13 * expected, "{segment} {s}");
            }
        }
    }

    #[test]
    fn adding_to_one_key_matches_the_field_built_afresh() {
        let knots: Vec<f64> = (0..120).map(|i| (i as f64 / 119.0).powf(1.3)).collect();
        let mut radii: Vec<Vec<f64>> =
            (0..120).map(|i| (0..7).map(|j| 1.0 + 0.1 * ((i * 7 + j) as f64).sin()).collect()).collect();
        fn rows(radii: &[Vec<f64>]) -> Vec<&[f64]> {
            radii.iter().map(Vec::as_slice).collect()
        }
        let mut field = RadiusField::new(&knots, &rows(&radii)).scaled(0.9);
        radii.iter_mut().flatten().for_each(|r| *r *= 0.9);
        let delta: Vec<f64> = (0..7).map(|j| 0.05 * (j as f64).cos()).collect();
        let changed = field.add_to_key(&knots, 60, &delta);
        radii[60].iter_mut().zip(&delta).for_each(|(r, d)| *r += d);
        let fresh = RadiusField::new(&knots, &rows(&radii));
        assert!(changed.start > 0 && changed.end < 119, "the change is local: {changed:?}");
        for segment in 0..119 {
            for j in 0..7 {
                let (a, b) = (field.patch(segment, j).c, fresh.patch(segment, j).c);
                for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
                    assert!((x - y).abs() < 1e-15, "interval {segment}, node {j}: {x} vs {y}");
                }
            }
        }
    }

    #[test]
    fn angular_cell_wraps_negative_and_large_angles() {
        let (j, phi) = angular_cell(-0.25 * TAU, 4);
        assert_eq!(j, 3);
        assert!(phi.abs() < 1e-12);
        let (j, phi) = angular_cell(2.5 * TAU, 4);
        assert_eq!(j, 2);
        assert!(phi.abs() < 1e-12);
    }
}
