//! Where a sweep folds: the stretches of its axis where Eq. 2 stops being one-to-one, found
//! before a pose is used so that a user can be warned (the output is still made).
//!
//! - **Cross-sections cross.** Neighbouring cross-sections at t and t + dt meet where the
//!   surface point's velocity along N(t) vanishes: ∂S/∂t · N = C′·N + (ω × q)·N = 0, with
//!   q = R(t)·(r cos θ, r sin θ, 0) the point's offset from the axis and ω the angular velocity
//!   of the frame R(t). For a tube whose frames follow its spine, (ω × q)·N = −r·κ·|C′| on the
//!   inside of a bend, so the ratio −(ω × q)·N / (C′·N) is r·κ, and the sections cross where
//!   it reaches 1 (the radius reaches the radius of curvature). The same ratio measures
//!   frames that turn faster than the spine bends (a key turned alone).
//! - **Keys step backwards.** A key center behind the plane of its neighbour (the chord
//!   c_{i+1} − c_i against N at either end): the sweep runs back along itself there.
//! - **Frames flip.** R(t) turns by more than 90° between neighbouring keys. The interpolation
//!   of their quaternions takes the shorter way round, so a turn that grows past 180° snaps to
//!   the other way; past 90° the sweep is halfway there, and its sections turn unevenly.

use glam::{DQuat, DVec3};

use super::Sweep;

/// Samples per knot interval along t.
pub const SAMPLES_PER_INTERVAL: usize = 16;
/// Samples around θ at each t.
pub const SAMPLES_AROUND: usize = 32;
/// Frames that turn by more than this many degrees between neighbouring keys flip.
pub const FLIP_DEGREES: f64 = 90.0;

/// What folds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FoldKind {
    /// Neighbouring cross-sections intersect: r·κ ≥ 1 (the amount is the largest r·κ; infinite
    /// where the spine runs behind the cross-sections' planes).
    SectionsCross,
    /// A key's center lies behind its neighbour's plane (the amount is the largest distance
    /// behind, in mesh units).
    KeysStepBack,
    /// The frame turns by more than [`FLIP_DEGREES`] between neighbouring keys (the amount is
    /// the largest turn, in degrees).
    FrameFlips,
}

/// One stretch of a sweep's axis that folds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fold {
    /// What folds there.
    pub kind: FoldKind,
    /// The stretch [t0, t1] of the axis.
    pub t: [f64; 2],
    /// How much (see [`FoldKind`]).
    pub amount: f64,
}

impl std::fmt::Display for Fold {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [t0, t1] = self.t;
        match self.kind {
            FoldKind::SectionsCross if self.amount.is_infinite() => {
                write!(f, "its cross-sections cross for t in [{t0:.3}, {t1:.3}]: the spine runs behind their planes")
            }
            FoldKind::SectionsCross => write!(
                f,
                "its cross-sections cross for t in [{t0:.3}, {t1:.3}]: the radius reaches the spine's radius of \
                 curvature (r·κ up to {:.2})",
                self.amount
            ),
            FoldKind::KeysStepBack => write!(
                f,
                "its keys step backwards for t in [{t0:.3}, {t1:.3}]: a key's center lies {:.3e} behind its \
                 neighbour's plane",
                self.amount
            ),
            FoldKind::FrameFlips => write!(
                f,
                "its frame flips for t in [{t0:.3}, {t1:.3}]: it turns {:.0}° between neighbouring keys",
                self.amount
            ),
        }
    }
}

impl Sweep {
    /// The stretches of the axis where the sweep folds (see the module docs), each kind's
    /// neighbouring stretches merged, in order of kind and t.
    pub fn folds(&self) -> Vec<Fold> {
        let mut folds = Vec::new();
        let mut crossing = Stretches::new(FoldKind::SectionsCross);
        for segment in &self.segments {
            for j in 0..=SAMPLES_PER_INTERVAL {
                let s = j as f64 / SAMPLES_PER_INTERVAL as f64;
                let t = segment.t0 + (segment.t1 - segment.t0) * s;
                let rotation = segment.orientation.value(s);
                crossing.sample(t, self.sections_ratio(segment, s, rotation));
            }
        }
        folds.extend(crossing.finish());
        let mut flips = Vec::new();
        for (i, segment) in self.segments.iter().enumerate() {
            let t = [self.knots[i], self.knots[i + 1]];
            let degrees = segment.orientation.start.angle_between(segment.orientation.end).to_degrees();
            if degrees > FLIP_DEGREES {
                merged(&mut flips, Fold { kind: FoldKind::FrameFlips, t, amount: degrees });
            }
            let (start, end) = (segment.curve.value(0.0), segment.curve.value(1.0));
            let chord = end - start;
            let behind = [segment.orientation.start, segment.orientation.end]
                .map(|q| -(chord.dot(q * DVec3::Z)))
                .into_iter()
                .fold(f64::NEG_INFINITY, f64::max);
            if behind >= 0.0 {
                merged(&mut folds, Fold { kind: FoldKind::KeysStepBack, t, amount: behind });
            }
        }
        folds.extend(flips);
        folds
    }

    /// The largest −(ω × q)·N / (C′·N) over θ at local parameter `s` of `segment` (whose frame
    /// there is `rotation`), where it is at least 1; infinite where C′·N ≤ 0.
    fn sections_ratio(&self, segment: &super::Segment, s: f64, rotation: DQuat) -> Option<f64> {
        let normal = rotation * DVec3::Z;
        let along = segment.curve.derivative(s).dot(normal);
        // ω by a central difference of R within the interval (one-sided at its ends), per unit
        // of t as C′ is.
        let step = 1e-5;
        let (lo, hi) = ((s - step).max(0.0), (s + step).min(1.0));
        let per_t = 1.0 / ((hi - lo) * (segment.t1 - segment.t0));
        let rate = (segment.orientation.value(hi) - segment.orientation.value(lo)) * per_t;
        let omega = 2.0 * (rate * rotation.conjugate()).xyz();
        if along <= 0.0 {
            return Some(f64::INFINITY);
        }
        let at = self.locate(segment.t0 + (segment.t1 - segment.t0) * s);
        let ratio = (0..SAMPLES_AROUND)
            .map(|j| {
                let theta = std::f64::consts::TAU * j as f64 / SAMPLES_AROUND as f64;
                let r = self.radius.value(at.segment, at.s, theta);
                let offset = rotation * DVec3::new(r * theta.cos(), r * theta.sin(), 0.0);
                -omega.cross(offset).dot(normal) / along
            })
            .fold(f64::NEG_INFINITY, f64::max);
        (ratio >= 1.0).then_some(ratio)
    }
}

/// Pushes `fold` onto `folds`, merged into the last one where that is of its kind and reaches it.
fn merged(folds: &mut Vec<Fold>, fold: Fold) {
    match folds.last_mut() {
        Some(last) if last.kind == fold.kind && last.t[1] >= fold.t[0] => {
            last.t[1] = fold.t[1];
            last.amount = last.amount.max(fold.amount);
        }
        _ => folds.push(fold),
    }
}

/// Samples along t merged into stretches where they fold.
struct Stretches {
    kind: FoldKind,
    open: Option<Fold>,
    done: Vec<Fold>,
}

impl Stretches {
    fn new(kind: FoldKind) -> Stretches {
        Stretches { kind, open: None, done: Vec::new() }
    }

    /// The sample at `t`: folding by `amount`, or not.
    fn sample(&mut self, t: f64, amount: Option<f64>) {
        match (amount, &mut self.open) {
            (Some(amount), Some(open)) => {
                open.t[1] = t;
                open.amount = open.amount.max(amount);
            }
            (Some(amount), None) => self.open = Some(Fold { kind: self.kind, t: [t, t], amount }),
            (None, _) => self.done.extend(self.open.take()),
        }
    }

    fn finish(mut self) -> Vec<Fold> {
        self.done.extend(self.open.take());
        self.done
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::Key;

    /// Keys along a circular arc of radius `bend_radius` turning by `angle` in the xz plane, each
    /// normal to it (frames following the spine), with circular sections of radius `radius`.
    fn arc(keys: usize, bend_radius: f64, angle: f64, radius: f64) -> Sweep {
        let keys: Vec<Key> = (0..keys)
            .map(|i| {
                let a = angle * i as f64 / (keys - 1) as f64;
                let center = DVec3::new(bend_radius * (1.0 - a.cos()), 0.0, bend_radius * a.sin());
                Key::circle(center, DQuat::from_rotation_y(a), radius, 16)
            })
            .collect();
        Sweep::try_new(&keys, None).unwrap()
    }

    #[test]
    fn a_straight_or_gently_bent_tube_does_not_fold() {
        assert_eq!(arc(9, 1e6, 1e-6, 0.5).folds(), vec![]);
        assert_eq!(arc(17, 2.0, 1.5, 1.0).folds(), vec![], "r·κ = 0.5");
    }

    /// On an arc the ratio is r·κ: a tube of radius 1.5 bent at radius 1 folds along its
    /// middle, by r·κ = 1.5 (to the accuracy of the spline through the keys), and not where
    /// the natural spline straightens towards its ends.
    #[test]
    fn a_tube_thicker_than_its_bend_radius_folds_by_r_kappa() {
        let folds = arc(33, 1.0, 2.0, 1.5).folds();
        assert_eq!(folds.len(), 1, "{folds:?}");
        let fold = folds[0];
        assert_eq!(fold.kind, FoldKind::SectionsCross);
        assert!((fold.amount - 1.5).abs() < 0.05, "{fold:?}");
        assert!(fold.t[0] < 0.2 && fold.t[1] > 0.8, "{fold:?}");
        // Below 1 no fold: radius 0.9 at the same bend.
        assert_eq!(arc(33, 1.0, 2.0, 0.9).folds(), vec![]);
        assert!(fold.to_string().contains("r·κ up to 1.5"), "{fold}");
    }

    #[test]
    fn a_key_behind_its_neighbours_plane_steps_back() {
        let mut keys: Vec<Key> =
            (0..5).map(|i| Key::circle(DVec3::new(0.0, 0.0, i as f64), DQuat::IDENTITY, 0.2, 8)).collect();
        keys[3].center = DVec3::new(2.0, 0.0, 1.5);
        let folds = Sweep::try_new(&keys, None).unwrap().folds();
        let knots = Sweep::try_new(&keys, None).unwrap().knots().to_vec();
        let back: Vec<&Fold> = folds.iter().filter(|f| f.kind == FoldKind::KeysStepBack).collect();
        assert_eq!(back.len(), 1, "{folds:?}");
        assert_eq!(back[0].t, [knots[2], knots[3]]);
        assert!((back[0].amount - 0.5).abs() < 1e-12, "{:?}", back[0]);
    }

    #[test]
    fn a_key_turned_nearly_half_a_turn_flips_the_frame() {
        let turned = |degrees: f64| {
            let keys: Vec<Key> = (0..4)
                .map(|i| {
                    let rotation = if i >= 2 { DQuat::from_rotation_z(degrees.to_radians()) } else { DQuat::IDENTITY };
                    Key::circle(DVec3::new(0.0, 0.0, i as f64), rotation, 0.2, 8)
                })
                .collect();
            Sweep::try_new(&keys, None).unwrap().folds()
        };
        let flips = turned(179.9);
        assert!(
            flips
                .iter()
                .any(|f| f.kind == FoldKind::FrameFlips && f.t[0] >= 1.0 / 3.0 - 1e-12 && f.t[1] <= 2.0 / 3.0 + 1e-12),
            "{flips:?}"
        );
        // A twist about the spine of 80° between two keys neither flips nor crosses.
        assert_eq!(turned(80.0), vec![]);
    }
}
