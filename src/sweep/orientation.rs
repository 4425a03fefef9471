//! The orientation R(t) of a sweep's moving cross-section (§3), in one of two interpolations
//! ([`RotationInterpolation`]) of the key quaternions q_i:
//!
//! - **linear** (the paper's): on [u_i, u_{i+1}], `q(t) = normalize((1−s)·q_i + s·q̃_{i+1})` with
//!   `q̃_{i+1} = ±q_{i+1}` chosen so that `q_i · q̃_{i+1} ≥ 0`. R is C⁰ at the keys: its angular
//!   velocity jumps there.
//! - **cubic**: the keys are sign-aligned along the sweep (each q̃_i on the side of q̃_{i−1}) and
//!   joined by the cubic Hermite spline in R⁴ whose tangent at each key is Fritsch and
//!   Butland's harmonic mean of the slopes beside it (each slope weighted by the other's length:
//!   no tangent beside a still interval, so the spline never turns back past a key; the chord's
//!   slope at the ends), then normalized.
//!   q(t) and so R(t) are C¹ across the keys. Each tangent is shortened where needed so that on
//!   both of its intervals `|h·m − Δq| ≤ |Δq|` (Δq the interval's chord, h its width): the cubic
//!   then stays within 2·(4/27)·|Δq| of the chord, whose points have norm ≥ cos 45°, so
//!   |q(s)| ≥ 0.28 and normalizing never divides by a vanishing norm.
//!
//! Either way one knot interval holds `q(s) = a0 + a1·s + a2·s² + a3·s³` ([`OrientationPiece`]),
//! with a2 = a3 = 0 for the linear one, and `N(t) = R(t)·e_z`.

use glam::{DQuat, DVec3};

/// How R(t) interpolates the key rotations; chosen per sweep (`"rotation_interpolation"` in a
/// rig file).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "json", serde(rename_all = "lowercase"))]
pub enum RotationInterpolation {
    /// The paper's normalized linear interpolation: C⁰ at the keys.
    #[default]
    Linear,
    /// A normalized cubic Hermite spline of the sign-aligned quaternions: C¹ across the keys.
    Cubic,
}

/// R(t) on one knot interval: `q(s) = a0 + a1·s + a2·s² + a3·s³`, normalized.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrientationPiece {
    /// q(0) = q_i (unit; for the cubic interpolation, sign-aligned along the sweep).
    pub start: DQuat,
    /// q(1) = q̃_{i+1}: unit, on the side of `start` (`start · end ≥ 0`).
    pub end: DQuat,
    /// Power-basis coefficients a0 … a3 of q(s); a2 = a3 = 0 for the linear interpolation.
    pub power: [DQuat; 4],
    /// Whether a2 or a3 may be non-zero (the cubic interpolation).
    pub cubic: bool,
}

const ZERO: DQuat = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);

impl OrientationPiece {
    /// The linear piece between two normalized key rotations.
    pub fn new(start: DQuat, end: DQuat) -> OrientationPiece {
        let end = if start.dot(end) >= 0.0 { end } else { -end };
        OrientationPiece { start, end, power: [start, end - start, ZERO, ZERO], cubic: false }
    }

    /// The cubic Hermite piece from `start` to `end` (unit, sign-aligned) with tangents
    /// `start_tangent` and `end_tangent` in s (dq/ds, that is h·dq/dt).
    pub fn hermite(start: DQuat, end: DQuat, start_tangent: DQuat, end_tangent: DQuat) -> OrientationPiece {
        let chord = end - start;
        let power = [
            start,
            start_tangent,
            chord * 3.0 - start_tangent * 2.0 - end_tangent,
            start_tangent + end_tangent - chord * 2.0,
        ];
        OrientationPiece { start, end, power, cubic: true }
    }

    /// The interpolated quaternion before normalization, q(s). Its norm is at least ½√2 for
    /// the linear interpolation (unit, sign-aligned ends) and at least 0.28 for the cubic one
    /// (see the module docs).
    pub fn unnormalized(&self, s: f64) -> DQuat {
        if !self.cubic {
            return self.start * (1.0 - s) + self.end * s;
        }
        let [a0, a1, a2, a3] = self.power;
        a0 + (a1 + (a2 + a3 * s) * s) * s
    }

    /// dq/ds, the derivative of [`OrientationPiece::unnormalized`].
    pub fn derivative(&self, s: f64) -> DQuat {
        let [_, a1, a2, a3] = self.power;
        if !self.cubic {
            return a1;
        }
        a1 + (a2 * 2.0 + a3 * (3.0 * s)) * s
    }

    /// R(t) as a unit quaternion at local parameter `s`.
    pub fn value(&self, s: f64) -> DQuat {
        self.unnormalized(s).normalize()
    }

    /// Coefficients `[n0, …, n6]` of `n(s) = Σ n_m·s^m`, the third column of the rotation
    /// matrix of the unnormalized quaternion `q(s)` (that column times `|q(s)|²`), so that
    /// `N(t) = n(s) / |q(s)|²`. Binding uses it: ⟨v − C(t), N(t)⟩ has the sign of the
    /// polynomial ⟨v − C(s), n(s)⟩. For the linear interpolation n3 … n6 are zero.
    pub fn normal_numerator(&self) -> [DVec3; 7] {
        let a = self.power;
        let degree = if self.cubic { 3 } else { 1 };
        std::array::from_fn(|m| {
            let mut sum = DVec3::ZERO;
            for i in 0..=degree.min(m) {
                let j = m - i;
                if j <= degree && i < j {
                    sum += 2.0 * normal_bilinear(a[i], a[j]);
                } else if i == j {
                    sum += normal_bilinear(a[i], a[i]);
                }
            }
            sum
        })
    }
}

/// Calls `piece(k, …)` with R(t)'s piece on each knot interval k of the unit key rotations
/// `rotation(0..knots.len())` at `knots`, in order and without allocating.
pub fn for_each_piece(
    interpolation: RotationInterpolation,
    knots: &[f64],
    rotation: impl Fn(usize) -> DQuat,
    mut piece: impl FnMut(usize, OrientationPiece),
) {
    let keys = knots.len();
    match interpolation {
        RotationInterpolation::Linear => {
            for k in 0..keys - 1 {
                piece(k, OrientationPiece::new(rotation(k), rotation(k + 1)));
            }
        }
        RotationInterpolation::Cubic => {
            // A window of the sign-aligned keys k − 1 … k + 2, moved along the sweep.
            let aligned = |key: usize, before: DQuat| {
                let q = rotation(key);
                if before.dot(q) >= 0.0 { q } else { -q }
            };
            let at = |key: usize, q: DQuat| KeyFrame { q, u: knots[key] };
            let mut current = at(0, rotation(0));
            let mut next = at(1, aligned(1, current.q));
            let mut start_tangent = key_tangent(None, current, Some(next));
            for k in 0..keys - 1 {
                let after = (k + 2 < keys).then(|| at(k + 2, aligned(k + 2, next.q)));
                let end_tangent = key_tangent(Some(current), next, after);
                let h = next.u - current.u;
                piece(k, OrientationPiece::hermite(current.q, next.q, start_tangent * h, end_tangent * h));
                start_tangent = end_tangent;
                current = next;
                if let Some(after) = after {
                    next = after;
                }
            }
        }
    }
}

/// A sign-aligned key quaternion and its knot.
#[derive(Clone, Copy)]
struct KeyFrame {
    q: DQuat,
    u: f64,
}

/// dq/dt at `key`: the harmonic mean of the slopes beside it (see the module docs), the
/// chord's slope at an end, then shortened so that on each interval beside
/// the key `|h·m − Δq| ≤ |Δq|` (see the module docs).
fn key_tangent(before: Option<KeyFrame>, key: KeyFrame, after: Option<KeyFrame>) -> DQuat {
    let slope = |a: KeyFrame, b: KeyFrame| (b.q - a.q) / (b.u - a.u);
    let tangent = match (before, after) {
        (Some(a), Some(b)) => {
            // Fritsch–Butland's harmonic mean, for vectors: each slope weighted by the other's
            // length, so a key beside a still interval gets no tangent.
            let (before, after) = (slope(a, key), slope(key, b));
            let (l0, l1) = (before.length(), after.length());
            if l0 + l1 == 0.0 { ZERO } else { (before * l1 + after * l0) / (l0 + l1) }
        }
        (Some(a), None) => slope(a, key),
        (None, Some(b)) => slope(key, b),
        (None, None) => ZERO,
    };
    let length_squared = tangent.length_squared();
    if length_squared == 0.0 {
        return tangent;
    }
    // |λh·m − Δ|² ≤ |Δ|² ⟺ λ ≤ 2·m·Δ / (h·|m|²).
    let mut scale: f64 = 1.0;
    for (a, b) in [before.map(|a| (a, key)), after.map(|b| (key, b))].into_iter().flatten() {
        let chord = b.q - a.q;
        let h = b.u - a.u;
        scale = scale.min((2.0 * tangent.dot(chord) / (h * length_squared)).max(0.0));
    }
    tangent * scale
}

/// The symmetric bilinear form B with `B(q, q) = |q|²·R(q/|q|)·e_z`, i.e. the third column
/// `(2(xz + wy), 2(yz − wx), w² − x² − y² + z²)` of the rotation matrix of a unit quaternion.
pub fn normal_bilinear(p: DQuat, q: DQuat) -> DVec3 {
    DVec3::new(
        p.x * q.z + p.z * q.x + p.w * q.y + p.y * q.w,
        p.y * q.z + p.z * q.y - p.w * q.x - p.x * q.w,
        p.w * q.w - p.x * q.x - p.y * q.y + p.z * q.z,
    )
}

#[cfg(test)]
mod tests;
