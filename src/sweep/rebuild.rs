//! Rebuilding a sweep in place from new keys at fixed knots, for posing every frame without
//! allocating (see [`crate::rig::Rig::pose_into`]).
//!
//! Data flow: rig → **sweep** → sweep coefficients → bind → deform → normals → output.
//!
//! A posed sweep keeps the rest knots u_i and the rest radius count M, so the two linear
//! systems behind its splines — the natural spline in t on the knots (C(t) and the t-direction
//! of r(θ, t)) and the periodic spline in θ on M uniform nodes — are the same every frame:
//! [`SweepSystems`] factorizes them once. [`Sweep::rebuild_valid`] then refills a sweep's
//! knots, segments and radius patches in place, with the same operations in the same order as
//! [`Sweep::try_new`] (so the result is bit for bit the same), using a [`RebuildScratch`] for
//! the right-hand sides. Once the vectors have their sizes nothing is allocated.

use std::f64::consts::TAU;
use std::sync::Arc;

use glam::DQuat;

use super::cubic::CubicPiece;
use super::curve::CurvePiece;
use super::natural_spline::NaturalSplineSystem;
use super::orientation::{self, OrientationPiece, RotationInterpolation};
use super::periodic_spline::PeriodicSplineSystem;
use super::radius::{RadiusField, RadiusPatch};
use super::{Key, Segment, Sweep};

/// The factorized spline systems of a sweep's fixed structure: the natural spline on its knots
/// u_0 … u_n and the periodic spline on its M angular nodes θ_j = 2πj/M (§3).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SweepSystems {
    /// The natural spline in t on the knots.
    along: NaturalSplineSystem,
    /// The periodic spline in θ on M nodes at spacing 2π/M.
    around: PeriodicSplineSystem,
}

impl SweepSystems {
    /// The systems of `sweep`'s knots and radius count, as [`Sweep::try_new`] factorizes them.
    pub(crate) fn of(sweep: &Sweep) -> SweepSystems {
        let samples = sweep.radius_samples();
        SweepSystems {
            along: NaturalSplineSystem::new(&sweep.knots),
            around: PeriodicSplineSystem::new(samples, TAU / samples as f64),
        }
    }
}

/// Right-hand sides and solutions of the spline systems while a sweep is rebuilt: one column
/// of values along the keys, one row along the M angular nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct RebuildScratch {
    /// Values at the knots (a center coordinate, or the radii ρ_ij of one node j).
    column: Vec<f64>,
    /// Second derivatives at the knots.
    column_m: Vec<f64>,
    /// The normalized key rotations.
    rotations: Vec<DQuat>,
    /// Values at the angular nodes (one power coefficient of r along t, node by node).
    row: Vec<f64>,
    /// The periodic solver's work row.
    row_work: Vec<f64>,
    /// Second derivatives at the angular nodes.
    row_m: Vec<f64>,
}

impl RebuildScratch {
    /// Scratch sized for sweeps of up to `keys` keys and `samples` radii a key, so that
    /// rebuilding them allocates nothing.
    pub(crate) fn with_capacity(keys: usize, samples: usize) -> RebuildScratch {
        RebuildScratch {
            column: Vec::with_capacity(keys),
            column_m: Vec::with_capacity(keys),
            rotations: Vec::with_capacity(keys),
            row: Vec::with_capacity(samples),
            row_work: Vec::with_capacity(samples),
            row_m: Vec::with_capacity(samples),
        }
    }
}

/// `v` holding `len` values (their content left to the caller), allocating only if it is
/// shorter than that.
fn sized(v: &mut Vec<f64>, len: usize) -> &mut [f64] {
    v.resize(len, 0.0);
    v
}

impl Sweep {
    /// A copy of this sweep that shares nothing with it (a [`Sweep::clone`] shares the radius
    /// function r(θ, t)), so that [`Sweep::rebuild_valid`] can refill it in place.
    pub(crate) fn detached(&self) -> Sweep {
        let radius = RadiusField {
            samples: self.radius.samples,
            patches: Arc::new((*self.radius.patches).clone()),
            scale: self.radius.scale,
        };
        Sweep {
            knots: self.knots.clone(),
            segments: self.segments.clone(),
            radius: Arc::new(radius),
            rotation: self.rotation,
        }
    }

    /// Makes this sweep the one [`Sweep::try_new_with`]`(keys, Some(knots), rotation)` builds
    /// (its own rotation interpolation kept), bit for bit,
    /// reusing its vectors: allocation-free when it already has `keys.len()` keys and their
    /// radius count and its radius function is not shared (see [`Sweep::detached`]).
    ///
    /// The caller has validated `keys` and `knots` as `try_new` does; `systems` are those of
    /// `knots` and the keys' radius count ([`SweepSystems::of`] a sweep with them).
    pub(crate) fn rebuild_valid(
        &mut self,
        keys: &[Key],
        knots: &[f64],
        systems: &SweepSystems,
        scratch: &mut RebuildScratch,
    ) {
        self.knots.clear();
        self.knots.extend_from_slice(knots);
        rebuild_axis(&mut self.segments, keys, knots, self.rotation, &systems.along, scratch);
        match Arc::get_mut(&mut self.radius) {
            Some(field) => rebuild_radius(field, keys, systems, scratch),
            None => {
                let mut field = RadiusField { samples: 0, patches: Arc::new(Vec::new()), scale: 1.0 };
                rebuild_radius(&mut field, keys, systems, scratch);
                self.radius = Arc::new(field);
            }
        }
    }
}

/// The knot intervals of C(t) and R(t) through `keys` (see `axis_segments`): per coordinate,
/// the natural spline through the centers' coordinate; per interval, the sign-aligned ends of
/// the normalized rotations.
fn rebuild_axis(
    segments: &mut Vec<Segment>,
    keys: &[Key],
    knots: &[f64],
    rotation: RotationInterpolation,
    along: &NaturalSplineSystem,
    scratch: &mut RebuildScratch,
) {
    let n = keys.len() - 1;
    let flat = CubicPiece { y0: 0.0, y1: 0.0, m0: 0.0, m1: 0.0, h: 1.0 };
    let still = OrientationPiece::new(DQuat::IDENTITY, DQuat::IDENTITY);
    segments.truncate(n);
    while segments.len() < n {
        segments.push(Segment { t0: 0.0, t1: 1.0, curve: CurvePiece { axes: [flat; 3] }, orientation: still });
    }
    let values = sized(&mut scratch.column, keys.len());
    let m = sized(&mut scratch.column_m, keys.len());
    for axis in 0..3 {
        for (value, key) in values.iter_mut().zip(keys) {
            *value = key.center[axis];
        }
        along.second_derivatives_into(values, m);
        for (k, segment) in segments.iter_mut().enumerate() {
            segment.curve.axes[axis] = along.piece(values, m, k);
        }
    }
    scratch.rotations.clear();
    scratch.rotations.extend(keys.iter().map(|key| key.rotation.normalize()));
    let rotations = &scratch.rotations;
    orientation::for_each_piece(
        rotation,
        knots,
        |i| rotations[i],
        |k, piece| {
            let segment = &mut segments[k];
            segment.t0 = knots[k];
            segment.t1 = knots[k + 1];
            segment.orientation = piece;
        },
    );
}

/// r(θ, t) through the keys' radii, as [`RadiusField::new`] computes it: the natural spline in
/// t through each angular node, then the periodic spline in θ through each of its power
/// coefficients. The t-direction coefficients a_p(k, j) wait in row 3 of each patch, which is
/// read (into the row scratch) before it is overwritten by the bicubic c\[3\]\[q\].
fn rebuild_radius(field: &mut RadiusField, keys: &[Key], systems: &SweepSystems, scratch: &mut RebuildScratch) {
    let samples = keys[0].radii.len();
    let segments = keys.len() - 1;
    field.samples = samples;
    field.scale = 1.0;
    // Unique after `Sweep::detached`, so no copy is made here.
    let patches = Arc::make_mut(&mut field.patches);
    patches.resize(segments * samples, RadiusPatch { c: [[0.0; 4]; 4] });
    let column = sized(&mut scratch.column, keys.len());
    let m = sized(&mut scratch.column_m, keys.len());
    for j in 0..samples {
        for (value, key) in column.iter_mut().zip(keys) {
            *value = key.radii[j];
        }
        systems.along.second_derivatives_into(column, m);
        for k in 0..segments {
            patches[k * samples + j].c[3] = systems.along.piece(column, m, k).power_coefficients();
        }
    }
    let row = sized(&mut scratch.row, samples);
    let work = sized(&mut scratch.row_work, samples);
    let m = sized(&mut scratch.row_m, samples);
    for patch_row in patches.chunks_mut(samples) {
        for p in 0..4 {
            for (value, patch) in row.iter_mut().zip(patch_row.iter()) {
                *value = patch.c[3][p];
            }
            systems.around.second_derivatives_into(row, work, m);
            for (j, patch) in patch_row.iter_mut().enumerate() {
                patch.c[p] = systems.around.piece(row, m, j).power_coefficients();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    fn keys(radii: usize, shift: f64) -> Vec<Key> {
        (0..5)
            .map(|i| {
                let t = i as f64;
                Key {
                    center: DVec3::new(0.3 * t * t + shift, t, -0.2 * t),
                    rotation: DQuat::from_rotation_x(0.3 * t + shift) * DQuat::from_rotation_z(-0.5 * t) * 2.0,
                    radii: (0..radii).map(|j| 1.0 + 0.1 * ((i * 7 + j * 3) % 5) as f64 + shift).collect(),
                }
            })
            .collect()
    }

    #[test]
    fn rebuild_is_bit_identical_to_try_new() {
        let rest = Sweep::try_new(&keys(6, 0.0), None).unwrap();
        let systems = SweepSystems::of(&rest);
        let mut sweep = rest.detached();
        let mut scratch = RebuildScratch::default();
        for shift in [0.25, -0.5, 1.5] {
            let posed = keys(6, shift);
            sweep.rebuild_valid(&posed, rest.knots(), &systems, &mut scratch);
            let expected = Sweep::try_new(&posed, Some(rest.knots())).unwrap();
            assert_eq!(format!("{sweep:?}"), format!("{expected:?}"), "shift {shift}");
        }
    }

    #[test]
    fn rebuild_keeps_the_cubic_rotation_interpolation_bit_for_bit() {
        let cubic = RotationInterpolation::Cubic;
        let rest = Sweep::try_new_with(&keys(6, 0.0), None, cubic).unwrap();
        let mut sweep = rest.detached();
        let mut scratch = RebuildScratch::default();
        for shift in [0.25, -0.5] {
            let posed = keys(6, shift);
            sweep.rebuild_valid(&posed, rest.knots(), &SweepSystems::of(&rest), &mut scratch);
            assert_eq!(sweep, Sweep::try_new_with(&posed, Some(rest.knots()), cubic).unwrap(), "shift {shift}");
        }
        assert_ne!(sweep, Sweep::try_new(&keys(6, -0.5), Some(rest.knots())).unwrap(), "the linear sweep differs");
    }

    #[test]
    fn rebuild_into_a_sweep_of_another_shape_resizes_it() {
        let rest = Sweep::try_new(&keys(6, 0.0), None).unwrap();
        let other = Sweep::try_new(&keys(4, 0.0)[..2], None).unwrap();
        let mut sweep = other.clone(); // shares its radius function with `other`
        sweep.rebuild_valid(&keys(6, 0.5), rest.knots(), &SweepSystems::of(&rest), &mut RebuildScratch::default());
        assert_eq!(sweep, Sweep::try_new(&keys(6, 0.5), Some(rest.knots())).unwrap());
        assert_eq!(other.radius_samples(), 4, "the shared radius function is left alone");
    }
}
