//! The sweep surface model in f64 (§3): the geometry every other stage is computed from.
//!
//! Data flow: rig → **sweep** → sweep coefficients → bind → deform → normals → output.
//!
//! A [`Sweep`] interpolates key cross-sections X_i ([`Key`]) at knots u_i:
//!
//! ```text
//! S(θ, t) = C(t) + R(t)·(r(θ, t)·cos θ, r(θ, t)·sin θ, 0)
//! ```
//!
//! with C the natural cubic spline through the centers (`curve`), R the normalized linear
//! interpolation of the key quaternions or, chosen per sweep, a normalized cubic spline of them
//! that is C¹ across the keys (`orientation`, [`RotationInterpolation`]) and r the
//! tensor-product spline of the radii (`radius`). Its volume is Eq. 1 ([`Sweep::volume`]).

mod error;
mod folds;
mod key;

internal_mod! {
    cubic;
    curve;
    knots;
    natural_spline;
    orientation;
    periodic_spline;
    plane_polynomial;
    quadrature;
    radius;
}
mod rebuild;
mod reshape;
mod volume;

use std::sync::Arc;

use glam::{DQuat, DVec3};

pub use error::SweepError;
pub use folds::{FLIP_DEGREES, Fold, FoldKind, SAMPLES_PER_INTERVAL};
pub use key::Key;
pub use key::chord_length;
pub use orientation::RotationInterpolation;
pub(crate) use rebuild::{RebuildScratch, SweepSystems};

use curve::{CurvePiece, center_curve};
use orientation::OrientationPiece;
use radius::RadiusField;

/// A position on a sweep's axis by knot interval: `t = u_k + s·(u_{k+1} − u_k)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisPoint {
    /// Knot interval k, from 0 to n − 1.
    pub segment: usize,
    /// Local parameter s ∈ [0, 1] within the interval.
    pub s: f64,
}

/// One knot interval [u_k, u_{k+1}] of a sweep: its piece of C and its orientation ends.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// u_k.
    pub t0: f64,
    /// u_{k+1}.
    pub t1: f64,
    /// C(t) on this interval.
    pub curve: CurvePiece,
    /// R(t) on this interval.
    pub orientation: OrientationPiece,
}

/// A control sweep surface built from n + 1 ≥ 2 key cross-sections (§3).
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    knots: Vec<f64>,
    segments: Vec<Segment>,
    /// Shared with the sweeps rebuilt from it by [`Sweep::try_with_axis`], whose keys have the
    /// same radii.
    radius: Arc<RadiusField>,
    /// How R(t) interpolates the keys; every sweep rebuilt from this one keeps it.
    rotation: RotationInterpolation,
}

impl Sweep {
    /// Builds the sweep through `keys` at `knots`, or at the chord-length knots of the key
    /// centers when `knots` is `None` (see `knots`).
    ///
    /// Fails, naming the key, on fewer than 2 keys, fewer than 3 radii or a radius count that
    /// differs from key 0's, a non-finite number, a coordinate or radius beyond
    /// [`MAX_RIG_COORDINATE`](crate::limits::MAX_RIG_COORDINATE), a zero quaternion or one
    /// whose squared length under- or overflows, a negative radius, consecutive centers closer
    /// than [`MIN_KNOT_SPACING`](crate::limits::MIN_KNOT_SPACING) of the chord length (when
    /// knots are computed) or invalid explicit knots. The radius count is at most
    /// [`MAX_RADII_PER_KEY`](crate::limits::MAX_RADII_PER_KEY) and the key count at most
    /// [`MAX_KEYS_PER_SWEEP`](crate::limits::MAX_KEYS_PER_SWEEP).
    pub fn try_new(keys: &[Key], knots: Option<&[f64]>) -> Result<Sweep, SweepError> {
        Sweep::try_new_with(keys, knots, RotationInterpolation::Linear)
    }

    /// [`Sweep::try_new`] with R(t) interpolating the key rotations as `rotation` says.
    pub fn try_new_with(
        keys: &[Key],
        knots: Option<&[f64]>,
        rotation: RotationInterpolation,
    ) -> Result<Sweep, SweepError> {
        validate_keys(keys)?;
        let knots = match knots {
            Some(knots) => {
                knots::validate_knots(knots, keys.len())?;
                knots.to_vec()
            }
            None => {
                let centers: Vec<DVec3> = keys.iter().map(|key| key.center).collect();
                knots::chord_length_knots(&centers)?
            }
        };
        Ok(Sweep::from_valid(keys, knots, rotation))
    }

    /// The sweep through `keys` at this sweep's knots with this sweep's rotation
    /// interpolation: a pose of it ([`Sweep::try_new_with`]).
    pub fn try_posed(&self, keys: &[Key]) -> Result<Sweep, SweepError> {
        Sweep::try_new_with(keys, Some(&self.knots), self.rotation)
    }

    /// How R(t) interpolates the key rotations.
    pub fn rotation_interpolation(&self) -> RotationInterpolation {
        self.rotation
    }

    /// Checks `keys` as [`Sweep::try_new`] does, without building the sweep (knots aside).
    pub fn validate(keys: &[Key]) -> Result<(), SweepError> {
        validate_keys(keys)
    }

    /// Checks the count, centers and rotations of `keys` as [`Sweep::try_new`] does, not their
    /// radii: for keys moved rigidly from keys already checked.
    pub fn validate_frames(keys: &[Key]) -> Result<(), SweepError> {
        validate_count(keys)?;
        keys.iter().enumerate().try_for_each(|(index, key)| validate_frame(index, key))
    }

    fn from_valid(keys: &[Key], knots: Vec<f64>, rotation: RotationInterpolation) -> Sweep {
        let segments = axis_segments(keys, &knots, rotation);
        let radii: Vec<&[f64]> = keys.iter().map(|key| key.radii.as_slice()).collect();
        let radius = Arc::new(RadiusField::new(&knots, &radii));
        Sweep { knots, segments, radius, rotation }
    }

    /// The same surface in the coordinates p' = (p − `origin`) / `scale`: centers moved and
    /// scaled, radii scaled, frames and knots unchanged (Eq. 2 is covariant under translation
    /// and uniform scale). With `scale` a power of two the scaling is exact; only the
    /// subtraction of `origin` rounds. See [`crate::frame::Frame`].
    pub fn in_frame(&self, origin: DVec3, scale: f64) -> Sweep {
        let moved = |piece: &cubic::CubicPiece, origin: f64| cubic::CubicPiece {
            y0: (piece.y0 - origin) / scale,
            y1: (piece.y1 - origin) / scale,
            m0: piece.m0 / scale,
            m1: piece.m1 / scale,
            h: piece.h,
        };
        let segments = self
            .segments
            .iter()
            .map(|segment| {
                let [x, y, z] = &segment.curve.axes;
                let axes = [moved(x, origin.x), moved(y, origin.y), moved(z, origin.z)];
                Segment { curve: curve::CurvePiece { axes }, ..segment.clone() }
            })
            .collect();
        Sweep {
            knots: self.knots.clone(),
            segments,
            radius: Arc::new(self.radius.scaled(1.0 / scale)),
            rotation: self.rotation,
        }
    }

    /// The knots u_0 = 0 < … < u_n = 1.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The n knot intervals.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// r(θ, t) as bicubic patches.
    pub fn radius_field(&self) -> &RadiusField {
        &self.radius
    }

    /// M, the number of radii per key.
    pub fn radius_samples(&self) -> usize {
        self.radius.samples()
    }

    /// The knot interval and local parameter of `t`, clamped to [0, 1]. A knot u_k with
    /// 0 < k < n belongs to interval k (s = 0); t = 1 belongs to the last interval (s = 1).
    pub fn locate(&self, t: f64) -> AxisPoint {
        let t = t.clamp(0.0, 1.0);
        let last = self.segments.len() - 1;
        let segment = (self.knots.partition_point(|&u| u <= t).max(1) - 1).min(last);
        let Segment { t0, t1, .. } = self.segments[segment];
        AxisPoint { segment, s: ((t - t0) / (t1 - t0)).clamp(0.0, 1.0) }
    }

    /// The center C(t); exactly p_i at t = u_i.
    pub fn center(&self, t: f64) -> DVec3 {
        let at = self.locate(t);
        self.segments[at.segment].curve.value(at.s)
    }

    /// C′(t) = dC/dt.
    pub fn center_derivative(&self, t: f64) -> DVec3 {
        let at = self.locate(t);
        self.segments[at.segment].curve.derivative(at.s)
    }

    /// C″(t) = d²C/dt²; zero at t = 0 and t = 1 (natural end conditions).
    pub fn center_second_derivative(&self, t: f64) -> DVec3 {
        let at = self.locate(t);
        self.segments[at.segment].curve.second_derivative(at.s)
    }

    /// R(t) as a unit quaternion; R(u_i) is the rotation of q_i.
    pub fn orientation(&self, t: f64) -> DQuat {
        let at = self.locate(t);
        self.segments[at.segment].orientation.value(at.s)
    }

    /// N(t) = R(t)·e_z, the unit normal of the cross-section plane at t.
    pub fn normal(&self, t: f64) -> DVec3 {
        self.orientation(t) * DVec3::Z
    }

    /// r(θ, t).
    pub fn radius(&self, theta: f64, t: f64) -> f64 {
        let at = self.locate(t);
        self.radius.value(at.segment, at.s, theta)
    }

    /// The surface point S(θ, t) = C(t) + R(t)·(r cos θ, r sin θ, 0).
    pub fn surface_point(&self, theta: f64, t: f64) -> DVec3 {
        self.point(theta, t, 0.0, 0.0)
    }

    /// The point at binding parameters (θ, t, d, h), Eq. 2 extended by the axial offset h:
    /// `C(t) + R(t)·((r(θ,t) + d)·cos θ, (r(θ,t) + d)·sin θ, h)`.
    pub fn point(&self, theta: f64, t: f64, d: f64, h: f64) -> DVec3 {
        let at = self.locate(t);
        let segment = &self.segments[at.segment];
        let rho = self.radius.value(at.segment, at.s, theta) + d;
        let (sin, cos) = theta.sin_cos();
        segment.curve.value(at.s) + segment.orientation.value(at.s) * DVec3::new(rho * cos, rho * sin, h)
    }
}

/// The knot intervals of C(t) (the natural cubic spline through the centers) and R(t) (the
/// `rotation` interpolation of the normalized rotations) through `keys` at `knots`.
fn axis_segments(keys: &[Key], knots: &[f64], rotation: RotationInterpolation) -> Vec<Segment> {
    let centers: Vec<DVec3> = keys.iter().map(|key| key.center).collect();
    let mut pieces = Vec::with_capacity(keys.len() - 1);
    orientation::for_each_piece(rotation, knots, |i| keys[i].rotation.normalize(), |_, piece| pieces.push(piece));
    center_curve(knots, &centers)
        .into_iter()
        .zip(pieces)
        .enumerate()
        .map(|(k, (curve, orientation))| Segment { t0: knots[k], t1: knots[k + 1], curve, orientation })
        .collect()
}

/// Checks keys as [`Sweep::try_new`] documents; every number within
/// [`MAX_RIG_COORDINATE`](crate::limits::MAX_RIG_COORDINATE), so that every value the sweep
/// evaluates to is finite.
fn validate_keys(keys: &[Key]) -> Result<(), SweepError> {
    validate_count(keys)?;
    let samples = keys[0].radii.len();
    for (index, key) in keys.iter().enumerate() {
        validate_frame(index, key)?;
        validate_radii(index, key, samples)?;
    }
    Ok(())
}

/// At least 2 and at most [`MAX_KEYS_PER_SWEEP`](crate::limits::MAX_KEYS_PER_SWEEP) keys.
fn validate_count(keys: &[Key]) -> Result<(), SweepError> {
    if keys.len() < 2 {
        return Err(SweepError::TooFewKeys { count: keys.len() });
    }
    if keys.len() > crate::limits::MAX_KEYS_PER_SWEEP {
        return Err(SweepError::TooManyKeys { count: keys.len() });
    }
    Ok(())
}

/// Key `key`'s center and rotation: finite, in range, a usable quaternion.
fn validate_frame(key: usize, Key { center, rotation, .. }: &Key) -> Result<(), SweepError> {
    use crate::limits::MAX_RIG_COORDINATE;
    if !center.is_finite() {
        return Err(SweepError::NonFinite { key, field: "center" });
    }
    if let Some(&value) = center.to_array().iter().find(|c| c.abs() > MAX_RIG_COORDINATE) {
        return Err(SweepError::CenterOutOfRange { key, value });
    }
    if !rotation.is_finite() {
        return Err(SweepError::NonFinite { key, field: "rotation" });
    }
    let length_squared = rotation.length_squared();
    if length_squared == 0.0 {
        return Err(SweepError::ZeroRotation { key });
    }
    if !length_squared.is_normal() {
        return Err(SweepError::RotationScale { key, length_squared });
    }
    Ok(())
}

/// Key `key`'s radii: `samples` of them (3 to [`MAX_RADII_PER_KEY`](crate::limits::MAX_RADII_PER_KEY)),
/// each finite, non-negative and in range.
fn validate_radii(key: usize, Key { radii, .. }: &Key, samples: usize) -> Result<(), SweepError> {
    use crate::limits::MAX_RIG_COORDINATE;
    if radii.len() < 3 {
        return Err(SweepError::TooFewRadii { key, count: radii.len() });
    }
    if radii.len() > crate::limits::MAX_RADII_PER_KEY {
        return Err(SweepError::TooManyRadii { key, count: radii.len() });
    }
    if radii.len() != samples {
        return Err(SweepError::RadiusCountMismatch { key, expected: samples, found: radii.len() });
    }
    for (index, &value) in radii.iter().enumerate() {
        if !value.is_finite() {
            return Err(SweepError::NonFinite { key, field: "radius" });
        }
        if value < 0.0 {
            return Err(SweepError::NegativeRadius { key, index, value });
        }
        if value > MAX_RIG_COORDINATE {
            return Err(SweepError::RadiusOutOfRange { key, index, value });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
