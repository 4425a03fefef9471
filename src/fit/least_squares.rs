//! Key radii fitted to the part's vertices by least squares: the radii ρ_ij that minimise the
//! measure the fit is judged by, Σ_v d_v² (§3, Fig. 4; [`super::quality`]), for the fitted
//! centers and frames.
//!
//! A vertex v binds where ⟨v − C(t), N(t)⟩ = 0, which depends on the centers and frames only,
//! so its (θ_v, t_v) and its distance y_v = |v − C(t_v)| from the axis in its cross-section
//! do not change with the radii, and d_v = y_v − r(θ_v, t_v). The radius function is the
//! tensor-product interpolating spline of the key radii (natural in t, periodic in θ;
//! [`crate::sweep::radius`]), linear in them:
//!
//! r(θ, t) = Σ_i Σ_j a_i(t) b_j(θ) ρ_ij,
//!
//! with a_i the natural cardinal spline of key i over the knots and b_j the periodic cardinal
//! spline of node θ_j. So Σ d_v² is a linear least-squares problem in ρ. The cardinal splines
//! decay by about 2 − √3 per node away from their own; each vertex's row keeps the [`WINDOW`]
//! nearest keys and nodes on either side, and the truncated system is solved for a correction
//! to the exact residuals d_v, [`ROUNDS`] times (iterative refinement), by conjugate gradients
//! on the normal equations with a ridge towards the section radii ρ⁰ (weight [`RIDGE`] times
//! the mean diagonal), so that a radius no vertex sees (a ray through a gap between toes)
//! keeps its sampled value. Where asked, the squares of the radii's second differences, around
//! each key and along the keys at each node, are added with a weight (a fraction of the mean
//! diagonal, [`SMOOTHING`] where radii bulged between a coarse part's samples), so that the
//! radii follow the surface between the samples rather than bend through each. Radii stay at
//! least 0.

use glam::DVec3;

use crate::bind::SweepBinder;
use crate::sweep::radius::{RadiusField, angular_cell};
use crate::sweep::{Key, Sweep};

/// Keys and angular nodes kept on either side of a vertex's cell.
pub const WINDOW: usize = 3;
/// Refinement rounds of the truncated system against the exact residuals.
pub const ROUNDS: usize = 2;
/// The ridge weight towards the section radii, a fraction of the normal matrix's mean diagonal.
pub const RIDGE: f64 = 1e-3;
/// The weight of the radii's second differences, around each key and along the keys at each
/// node, where they are smoothed: a fraction of the normal matrix's mean diagonal.
pub const SMOOTHING: f64 = 0.01;
/// Conjugate-gradient iterations per round.
const ITERATIONS: usize = 60;

/// The truncated system's rows, one per vertex, their entries in one list: row i's are
/// `entries[offsets[i]..offsets[i + 1]]`, each (unknown index i·M + j, weight a_i b_j).
struct Rows {
    entries: Vec<(usize, f64)>,
    offsets: Vec<usize>,
}

impl Rows {
    fn iter(&self) -> impl Iterator<Item = &[(usize, f64)]> {
        self.offsets.windows(2).map(|w| &self.entries[w[0]..w[1]])
    }

    /// out += AᵀA x, row by row.
    fn apply(&self, x: &[f64], out: &mut [f64]) {
        for row in self.iter() {
            let ax: f64 = row.iter().map(|&(k, w)| w * x[k]).sum();
            for &(k, w) in row {
                out[k] += w * ax;
            }
        }
    }
}

/// Keys, and angular nodes, apart by at most this much share a row of the truncated system.
const REACH: usize = 2 * WINDOW - 1;
/// Keys, and nodes, within [`REACH`] of an unknown's own.
const SIDE: usize = 2 * REACH + 1;
/// Entries of AᵀA per unknown: the keys and nodes within [`REACH`] of its own.
const STENCIL: usize = SIDE * SIDE;

/// AᵀA of the truncated system, formed: for unknown i·M + j, its entry with each unknown
/// (i + di)·M + (j + dj) mod M, |di|, |dj| ≤ [`REACH`] (a row's keys and nodes lie within
/// that of each other). Formed where the rows hold more entries than it does (a part of
/// thousands of vertices: 3,860 rows of 36 entries against 736 unknowns of 121), a product
/// with it costs less than one row by row, twice over each row; the conjugate gradients then
/// take the same steps up to rounding.
struct Normal {
    n: usize,
    m: usize,
    /// Unknown by unknown, [`STENCIL`] entries, (di, dj) at (di + REACH)·[`SIDE`] + dj + REACH.
    entries: Vec<f64>,
}

impl Normal {
    /// Whether forming AᵀA of `rows` (n keys of m radii) makes products with it cheaper.
    fn worth_forming(rows: &Rows, n: usize, m: usize) -> bool {
        rows.entries.len() > n * m * STENCIL
    }

    /// AᵀA of `rows`, each of which holds its keys in order and, for each, the same
    /// min(2·[`WINDOW`], m) nodes in order around the circle (as [`fitted_radii`] builds them):
    /// entry e of a row is key e / L and node e % L of its own, so two entries' keys and nodes
    /// lie (e′ / L − e / L) and (e′ % L − e % L) apart.
    fn of(rows: &Rows, n: usize, m: usize) -> Normal {
        let nodes = (2 * WINDOW).min(m);
        let mut entries = vec![0.0; n * m * STENCIL];
        // Where entry e's (di, dj) from an entry of key 0 and node 0 of its row lies.
        let mut offsets: Vec<usize> = Vec::new();
        for row in rows.iter() {
            offsets.clear();
            offsets.extend((0..row.len()).map(|e| (e / nodes) * SIDE + e % nodes));
            let span = offsets.last().map_or(0, |last| last + 1);
            for (&(p, wp), &from) in row.iter().zip(&offsets) {
                // (di, dj) = (0, 0) is at REACH·SIDE + REACH; entry e′ lies `offsets[e′]` past
                // the slot of (−key, −node) of entry e.
                let base = p * STENCIL + REACH * SIDE + REACH - from;
                let slots = &mut entries[base..base + span];
                for (&(_, wq), &to) in row.iter().zip(&offsets) {
                    slots[to] += wp * wq;
                }
            }
        }
        Normal { n, m, entries }
    }

    /// out += AᵀA x.
    fn apply(&self, x: &[f64], out: &mut [f64]) {
        let (n, m) = (self.n, self.m);
        let mut nodes = [0usize; SIDE];
        for j in 0..m {
            for (dj, node) in nodes.iter_mut().enumerate() {
                *node = (j + 2 * m + dj - REACH) % m;
            }
            for i in 0..n {
                let k = i * m + j;
                let stencil = &self.entries[k * STENCIL..(k + 1) * STENCIL];
                let mut sum = 0.0;
                for di in i.saturating_sub(REACH)..(i + REACH + 1).min(n) {
                    let weights = &stencil[(di + REACH - i) * SIDE..][..SIDE];
                    let x_row = &x[di * m..(di + 1) * m];
                    sum += weights.iter().zip(&nodes).map(|(w, &node)| w * x_row[node]).sum::<f64>();
                }
                out[k] += sum;
            }
        }
    }
}

/// Where a vertex binds: its distance from the axis y_v, and (θ_v, t_v).
struct Bound {
    y: f64,
    theta: f64,
    t: f64,
}

/// The radii of `keys` (whose sweep is `sweep`) fitted to `positions` (see the module docs),
/// their second differences weighted by `smoothing` (a fraction of the normal matrix's mean
/// diagonal; 0 for none, [`SMOOTHING`] where radii bulge between the samples); `None` when
/// there are no vertices.
pub fn fitted_radii(sweep: &Sweep, keys: &[Key], positions: &[DVec3], smoothing: f64) -> Option<Vec<Vec<f64>>> {
    fitted_radii_forming(sweep, keys, positions, smoothing, true)
}

/// [`fitted_radii`]; AᵀA is formed ([`Normal`]) only where `may_form` and it is worth it.
fn fitted_radii_forming(
    sweep: &Sweep,
    keys: &[Key],
    positions: &[DVec3],
    smoothing: f64,
    may_form: bool,
) -> Option<Vec<Vec<f64>>> {
    if positions.is_empty() {
        return None;
    }
    let knots = sweep.knots().to_vec();
    let (n, m) = (keys.len(), keys[0].radii.len());
    // a_i: the field of key i's unit radii, three nodes around (the fewest a field takes; a
    // constant row interpolates to itself), so that memory grows with n² rather than n²·M.
    let along: Vec<RadiusField> = (0..n)
        .map(|i| {
            let rows: Vec<[f64; 3]> = (0..n).map(|k| [f64::from(u8::from(k == i)); 3]).collect();
            RadiusField::new(&knots, &rows.iter().map(<[f64; 3]>::as_slice).collect::<Vec<_>>())
        })
        .collect();
    // b_j: the periodic cardinal spline of node 0 on uniform nodes, shifted: b_j's patch on
    // cell c is b_0's on cell c − j, so one field serves every node (M rather than M² patches).
    let node: Vec<f64> = (0..m).map(|q| f64::from(u8::from(q == 0))).collect();
    let around = RadiusField::new(&[0.0, 1.0], &[&node, &node]);
    let basis = |j: usize, (cell, phi): (usize, f64)| around.patch(0, (cell + m - j) % m).value(0.0, phi);
    let binder = SweepBinder::new(sweep);
    let intervals = knots.len() - 1;
    let mut rows = Rows { entries: Vec::new(), offsets: vec![0] };
    let bound: Vec<Bound> = positions
        .iter()
        .map(|&v| {
            let b = binder.bind(v);
            let segment = knots[1..intervals].partition_point(|&u| u <= b.t);
            let s = ((b.t - knots[segment]) / (knots[segment + 1] - knots[segment])).clamp(0.0, 1.0);
            let cell = ((b.theta / std::f64::consts::TAU * m as f64).floor() as usize).min(m - 1);
            let keys_near = segment.saturating_sub(WINDOW - 1)..(segment + 1 + WINDOW).min(n);
            let angle = angular_cell(b.theta, m);
            for i in keys_near {
                let a = along[i].value(segment, s, 0.0);
                for offset in 0..2 * WINDOW {
                    let j = (cell + m + offset + 1 - WINDOW) % m;
                    if offset >= m {
                        break;
                    }
                    rows.entries.push((i * m + j, a * basis(j, angle)));
                }
            }
            rows.offsets.push(rows.entries.len());
            Bound { y: b.d + sweep.radius(b.theta, b.t), theta: b.theta, t: b.t }
        })
        .collect();
    let prior: Vec<f64> = keys.iter().flat_map(|k| k.radii.iter().copied()).collect();
    let mut rho = prior.clone();
    let mut diagonal = vec![0.0; n * m];
    for &(k, w) in &rows.entries {
        diagonal[k] += w * w;
    }
    let mean_diagonal = diagonal.iter().sum::<f64>() / diagonal.len() as f64;
    let ridge = RIDGE * mean_diagonal;
    let curvature = Curvature { n, m, weight: smoothing * mean_diagonal };
    curvature.add_diagonal(&mut diagonal);
    let normal = (may_form && Normal::worth_forming(&rows, n, m)).then(|| Normal::of(&rows, n, m));
    for _ in 0..ROUNDS {
        let current = Sweep::try_new(&with_radii(keys, &rho, m), Some(&knots)).ok()?;
        let residual: Vec<f64> = bound.iter().map(|b| b.y - current.radius(b.theta, b.t)).collect();
        // (AᵀA + λI) Δ = Aᵀe − λ(ρ − ρ⁰)
        let mut rhs = vec![0.0; n * m];
        for (row, e) in rows.iter().zip(&residual) {
            for &(k, w) in row {
                rhs[k] += w * e;
            }
        }
        for k in 0..n * m {
            rhs[k] -= ridge * (rho[k] - prior[k]);
        }
        let mut bent = vec![0.0; n * m];
        curvature.apply(&rho, &mut bent);
        for k in 0..n * m {
            rhs[k] -= bent[k];
        }
        let delta = match &normal {
            Some(normal) => conjugate_gradients(|x, out| normal.apply(x, out), ridge, &curvature, &diagonal, &rhs),
            None => conjugate_gradients(|x, out| rows.apply(x, out), ridge, &curvature, &diagonal, &rhs),
        };
        for (r, d) in rho.iter_mut().zip(delta) {
            *r = (*r + d).max(0.0);
        }
    }
    Some(rho.chunks(m).map(<[f64]>::to_vec).collect())
}

/// `keys` with the radii `rho` (key by key, `m` each).
pub fn with_radii(keys: &[Key], rho: &[f64], m: usize) -> Vec<Key> {
    keys.iter().zip(rho.chunks(m)).map(|(k, r)| Key { radii: r.to_vec(), ..k.clone() }).collect()
}

/// Solves (AᵀA + λI + μDᵀD) x = b, `normal` adding AᵀA x to its second argument and μDᵀD
/// being `curvature`, by Jacobi-preconditioned conjugate gradients from x = 0.
fn conjugate_gradients(
    normal: impl Fn(&[f64], &mut [f64]),
    ridge: f64,
    curvature: &Curvature,
    diagonal: &[f64],
    b: &[f64],
) -> Vec<f64> {
    let apply = |x: &[f64]| {
        let mut out: Vec<f64> = x.iter().map(|v| ridge * v).collect();
        curvature.apply(x, &mut out);
        normal(x, &mut out);
        out
    };
    let precondition = |r: &[f64]| r.iter().zip(diagonal).map(|(r, d)| r / (d + ridge)).collect::<Vec<f64>>();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
    let mut x = vec![0.0; b.len()];
    let mut r = b.to_vec();
    let mut z = precondition(&r);
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let tolerance = 1e-20 * dot(b, b).max(f64::MIN_POSITIVE);
    for _ in 0..ITERATIONS {
        if dot(&r, &r) <= tolerance {
            break;
        }
        let ap = apply(&p);
        let alpha = rz / dot(&p, &ap);
        for k in 0..x.len() {
            x[k] += alpha * p[k];
            r[k] -= alpha * ap[k];
        }
        z = precondition(&r);
        let next = dot(&r, &z);
        for k in 0..p.len() {
            p[k] = z[k] + (next / rz) * p[k];
        }
        rz = next;
    }
    x
}

/// μ (D_θᵀD_θ + D_tᵀD_t): the second differences of the radii around each key (periodic)
/// and along the keys at each node (by key, not by knot), weighted by μ.
struct Curvature {
    n: usize,
    m: usize,
    weight: f64,
}

impl Curvature {
    /// Calls `each` with the unknowns of each second difference, x_a − 2x_b + x_c.
    fn differences(&self, mut each: impl FnMut([usize; 3])) {
        let (n, m) = (self.n, self.m);
        if m >= 3 {
            for i in 0..n {
                for j in 0..m {
                    each([i * m + (j + m - 1) % m, i * m + j, i * m + (j + 1) % m]);
                }
            }
        }
        for i in 1..n.saturating_sub(1) {
            for j in 0..m {
                each([(i - 1) * m + j, i * m + j, (i + 1) * m + j]);
            }
        }
    }

    /// out += μ DᵀD x.
    fn apply(&self, x: &[f64], out: &mut [f64]) {
        if self.weight == 0.0 {
            return;
        }
        let w = self.weight;
        self.differences(|[a, b, c]| {
            let d = x[a] - 2.0 * x[b] + x[c];
            out[a] += w * d;
            out[b] -= 2.0 * w * d;
            out[c] += w * d;
        });
    }

    /// diagonal += the diagonal of μ DᵀD.
    fn add_diagonal(&self, diagonal: &mut [f64]) {
        if self.weight == 0.0 {
            return;
        }
        let w = self.weight;
        self.differences(|[a, b, c]| {
            diagonal[a] += w;
            diagonal[b] += 4.0 * w;
            diagonal[c] += w;
        });
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use glam::DQuat;

    use super::*;

    /// Five keys along z whose radii vary around and along the sweep.
    fn keys(bump: f64) -> Vec<Key> {
        (0..5)
            .map(|i| Key {
                center: DVec3::new(0.0, 0.0, i as f64),
                rotation: DQuat::IDENTITY,
                radii: (0..12)
                    .map(|j| 1.0 + 0.1 * i as f64 + 0.2 * (TAU * j as f64 / 12.0 + i as f64).cos() + bump)
                    .collect(),
            })
            .collect()
    }

    #[test]
    fn radii_off_by_a_tenth_are_fitted_back_to_the_surface_they_came_from() {
        let truth = Sweep::try_new(&keys(0.0), None).unwrap();
        let points: Vec<DVec3> = (0..40)
            .flat_map(|b| (0..60).map(move |a| (TAU * a as f64 / 60.0, 0.01 + 0.98 * b as f64 / 39.0)))
            .map(|(theta, t)| truth.surface_point(theta, t))
            .collect();
        let guess = keys(0.1);
        let sweep = Sweep::try_new(&guess, None).unwrap();
        let fitted = fitted_radii(&sweep, &guess, &points, 0.0).unwrap();
        let worst = fitted
            .iter()
            .flatten()
            .zip(keys(0.0).iter().flat_map(|k| k.radii.clone()))
            .map(|(f, t)| (f - t).abs())
            .fold(0.0, f64::max);
        assert!(worst < 2e-3, "worst radius off by {worst}");
        assert!(fitted_radii(&sweep, &guess, &[], 0.0).is_none());
    }

    #[test]
    fn the_curvature_term_is_the_weighted_sum_of_squared_second_differences() {
        let (n, m, weight) = (5, 8, 0.7);
        let curvature = Curvature { n, m, weight };
        let x: Vec<f64> = (0..n * m).map(|k| (1.3 * k as f64).sin() + 0.1 * k as f64).collect();
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..m {
                let around = x[i * m + (j + m - 1) % m] - 2.0 * x[i * m + j] + x[i * m + (j + 1) % m];
                sum += around * around;
                if i > 0 && i + 1 < n {
                    let along = x[(i - 1) * m + j] - 2.0 * x[i * m + j] + x[(i + 1) * m + j];
                    sum += along * along;
                }
            }
        }
        let mut applied = vec![0.0; n * m];
        curvature.apply(&x, &mut applied);
        let quadratic: f64 = x.iter().zip(&applied).map(|(x, a)| x * a).sum();
        assert!((quadratic - weight * sum).abs() <= 1e-12 * weight * sum, "{quadratic} against {}", weight * sum);
        // Its diagonal is the operator's, unknown by unknown; a constant field is not bent.
        let mut diagonal = vec![0.0; n * m];
        curvature.add_diagonal(&mut diagonal);
        for k in 0..n * m {
            let mut unit = vec![0.0; n * m];
            unit[k] = 1.0;
            let mut column = vec![0.0; n * m];
            curvature.apply(&unit, &mut column);
            assert!((column[k] - diagonal[k]).abs() < 1e-12, "unknown {k}");
        }
        let mut bent = vec![0.0; n * m];
        curvature.apply(&vec![2.5; n * m], &mut bent);
        assert!(bent.iter().all(|b| b.abs() < 1e-12));
    }

    /// Radii seen by a few samples only: fitted plainly, those the samples see move and their
    /// neighbours keep the guess's (a bump per sample); smoothed, the correction spreads.
    #[test]
    fn smoothed_radii_follow_the_surface_between_a_few_samples() {
        let truth = Sweep::try_new(&keys(0.0), None).unwrap();
        let guess = keys(0.1);
        let sweep = Sweep::try_new(&guess, None).unwrap();
        let on_truth = |count: usize, turn: f64| -> Vec<DVec3> {
            (0..count)
                .map(|k| (TAU * (k as f64 * 0.618_034 + turn).fract(), 0.05 + 0.9 * (k as f64 + 0.5) / count as f64))
                .map(|(theta, t)| truth.surface_point(theta, t))
                .collect()
        };
        let (samples, between) = (on_truth(24, 0.0), on_truth(400, 0.3));
        let off_between = |smoothing: f64| {
            let radii = fitted_radii(&sweep, &guess, &samples, smoothing).unwrap();
            let fitted = Sweep::try_new(&with_radii(&guess, &radii.concat(), 12), None).unwrap();
            let binder = SweepBinder::new(&fitted);
            let squares: f64 = between.iter().map(|&p| binder.bind(p).d.powi(2)).sum();
            (squares / between.len() as f64).sqrt()
        };
        let (plain, smoothed) = (off_between(0.0), off_between(SMOOTHING));
        eprintln!("RMS d between the samples: plain {plain:.5}, smoothed {smoothed:.5}");
        assert!(smoothed < 0.7 * plain, "plain {plain}, smoothed {smoothed}");
    }

    /// Rows of the truncated system's shape for `count` vertices on a sweep of `n` keys of `m`
    /// radii: each vertex's keys and nodes around its knot interval and angular cell, with
    /// made-up weights.
    fn made_up_rows(count: usize, n: usize, m: usize) -> Rows {
        let mut rows = Rows { entries: Vec::new(), offsets: vec![0] };
        for v in 0..count {
            let f = |k: f64| (v as f64 * k).fract();
            let segment = (f(0.618_034) * (n - 1) as f64) as usize;
            let cell = (f(0.754_878) * m as f64) as usize;
            for i in segment.saturating_sub(WINDOW - 1)..(segment + 1 + WINDOW).min(n) {
                for offset in 0..(2 * WINDOW).min(m) {
                    let j = (cell + m + offset + 1 - WINDOW) % m;
                    rows.entries.push((i * m + j, 0.1 + f(0.3 + 0.1 * (i + offset) as f64)));
                }
            }
            rows.offsets.push(rows.entries.len());
        }
        rows
    }

    #[test]
    fn the_formed_normal_matrix_multiplies_as_the_rows_do() {
        for (n, m) in [(2, 3), (5, 4), (7, 5), (6, 7), (12, 11), (24, 32)] {
            let rows = made_up_rows(3000, n, m);
            let normal = Normal::of(&rows, n, m);
            let x: Vec<f64> = (0..n * m).map(|k| (0.7 * k as f64).sin() + 0.3).collect();
            let (mut by_rows, mut formed) = (vec![0.0; n * m], vec![0.0; n * m]);
            rows.apply(&x, &mut by_rows);
            normal.apply(&x, &mut formed);
            let scale = by_rows.iter().map(|v| v.abs()).fold(0.0, f64::max);
            let worst = by_rows.iter().zip(&formed).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(worst <= 1e-12 * scale, "{n} keys of {m} radii: off by {worst} of {scale}");
        }
        // Formed only where the rows hold more entries than it: 3,000 vertices on 24 keys of
        // 32 radii, not 300.
        assert!(Normal::worth_forming(&made_up_rows(3000, 24, 32), 24, 32));
        assert!(!Normal::worth_forming(&made_up_rows(300, 24, 32), 24, 32));
    }

    #[test]
    fn radii_fitted_with_the_normal_matrix_formed_are_those_fitted_row_by_row() {
        // 4,000 samples on 5 keys of 12 radii: the normal matrix is formed.
        let truth = Sweep::try_new(&keys(0.0), None).unwrap();
        let points: Vec<DVec3> = (0..4000)
            .map(|k| (TAU * (k as f64 * 0.618_034).fract(), 0.02 + 0.96 * (k as f64 * 0.754_878).fract()))
            .map(|(theta, t)| truth.surface_point(theta, t))
            .collect();
        let guess = keys(0.1);
        let sweep = Sweep::try_new(&guess, None).unwrap();
        let fitted = fitted_radii(&sweep, &guess, &points, SMOOTHING).unwrap();
        let by_rows = fitted_radii_forming(&sweep, &guess, &points, SMOOTHING, false).unwrap();
        let worst = fitted.iter().flatten().zip(by_rows.iter().flatten()).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-9, "radii differ by {worst}");
    }
}
