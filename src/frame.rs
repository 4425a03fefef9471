//! A frame local to a part: where the f32 paths compute, so that their accuracy is relative to
//! the part wherever it sits and whatever its size.
//!
//! f32 holds about 7 digits. A mesh 10⁷ units from the origin keeps none of its shape in f32
//! positions (the demo tube moved by 0.7 units under its own rest pose), and one 10⁻²² of a
//! unit across underflows in squared terms. The f64 data are mapped into the frame
//! p' = (p − origin) / scale, where `origin` is the centre of the points' bounding box and
//! `scale` the power of two at or above its largest side: the part then spans about one unit
//! around zero. The f32 paths (the fast CPU path, the GPU kernels) bind and deform there, and
//! their results come back as origin + scale · p' in f64. A power-of-two scale makes the
//! scaling exact; only the subtraction of the origin rounds, once, in f64.
//!
//! Eq. 2 is covariant under translation and uniform scale: a sweep in the frame
//! ([`Sweep::in_frame`]) deforms the points in the frame as the sweep deforms the points
//! outside it. Bindings keep θ and t; d and h, lengths, are divided by the scale.
//!
//! An application drawing the engine's output buffers builds its deformer from
//! [`Frame::local_positions`] and [`Frame::local_sweeps`] (each frame's pose through
//! `local_sweeps` too) and draws with [`Frame::to_world_matrix`] as its model matrix, as
//! camera-relative rendering does: the buffers stay accurate relative to the part.

use glam::{DMat4, DVec3};

use crate::bind::{Binding, MeshBindings};
use crate::mesh::bounds_of;
use crate::sweep::Sweep;

/// The frame p' = (p − origin) / scale of a part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The part's centre, world units.
    pub origin: DVec3,
    /// A power of two at or above the part's largest side.
    pub scale: f64,
}

impl Frame {
    /// The world itself: origin 0, scale 1.
    pub const IDENTITY: Frame = Frame { origin: DVec3::ZERO, scale: 1.0 };

    /// The frame of `points`: the centre of their bounding box, and the power of two at or
    /// above its largest side ([`Frame::IDENTITY`] for no point, a single point or a
    /// non-finite one).
    pub fn of_points(points: &[DVec3]) -> Frame {
        let (lo, hi) = bounds_of(points);
        let (origin, side) = ((lo + hi) / 2.0, (hi - lo).max_element());
        if !(origin.is_finite() && side.is_finite() && side > 0.0) {
            return Frame::IDENTITY;
        }
        let scale = 2f64.powi(side.log2().ceil() as i32);
        if !scale.is_normal() {
            return Frame::IDENTITY;
        }
        Frame { origin, scale }
    }

    /// `p` in the frame.
    pub fn to_local(&self, p: DVec3) -> DVec3 {
        (p - self.origin) / self.scale
    }

    /// `p` (in the frame) in the world.
    pub fn to_world(&self, p: DVec3) -> DVec3 {
        self.origin + p * self.scale
    }

    /// The model matrix that draws points of the frame in the world.
    pub fn to_world_matrix(&self) -> DMat4 {
        DMat4::from_translation(self.origin) * DMat4::from_scale(DVec3::splat(self.scale))
    }

    /// `points` in the frame.
    pub fn local_positions(&self, points: &[DVec3]) -> Vec<DVec3> {
        points.iter().map(|&p| self.to_local(p)).collect()
    }

    /// `sweeps` in the frame ([`Sweep::in_frame`]).
    pub fn local_sweeps(&self, sweeps: &[Sweep]) -> Vec<Sweep> {
        sweeps.iter().map(|sweep| sweep.in_frame(self.origin, self.scale)).collect()
    }

    /// `bindings` (made in the world) in the frame: d and h divided by the scale.
    pub fn local_bindings(&self, bindings: &MeshBindings) -> MeshBindings {
        self.rescaled(bindings, 1.0 / self.scale)
    }

    /// `bindings` (made in the frame) in the world: d and h multiplied by the scale.
    pub fn world_bindings(&self, bindings: &MeshBindings) -> MeshBindings {
        self.rescaled(bindings, self.scale)
    }

    fn rescaled(&self, bindings: &MeshBindings, factor: f64) -> MeshBindings {
        let rescale = |binding: &Binding| {
            let mut binding = *binding;
            binding.params.d *= factor;
            binding.params.h *= factor;
            binding
        };
        let mut out = bindings.clone();
        out.vertices.iter_mut().for_each(|b| *b = rescale(b));
        out.bands.iter_mut().for_each(|band| band.second = rescale(&band.second));
        out
    }
}

#[cfg(test)]
mod tests {
    use glam::DQuat;

    use super::*;
    use crate::bind::SweepBinder;
    use crate::sweep::Key;

    #[test]
    fn the_frame_centres_the_points_at_a_power_of_two_scale() {
        let frame = Frame::of_points(&[DVec3::new(1e7, 0.0, -3.0), DVec3::new(1e7 + 3.0, 1.0, -2.0)]);
        assert_eq!(frame, Frame { origin: DVec3::new(1e7 + 1.5, 0.5, -2.5), scale: 4.0 });
        assert_eq!(Frame::of_points(&[]), Frame::IDENTITY);
        assert_eq!(Frame::of_points(&[DVec3::ONE]), Frame::IDENTITY);
        assert_eq!(Frame::of_points(&[DVec3::ZERO, DVec3::splat(f64::NAN)]), Frame::IDENTITY);
        let tiny = Frame::of_points(&[DVec3::ZERO, DVec3::splat(3e-25)]);
        assert_eq!(tiny.scale, 2f64.powi(-81));
        let p = DVec3::new(1e12 + 0.25, -2e12, 7.0);
        let frame = Frame::of_points(&[p, p + DVec3::ONE]);
        assert_eq!(frame.to_world(frame.to_local(p)), p);
    }

    /// A sweep and a point 10¹² away, scaled by 10⁻³: the point binds in the frame as in the
    /// world (θ and t; d and h over the scale), and Eq. 2 in the frame maps back to it.
    #[test]
    fn binding_and_eq_2_are_covariant_under_the_frame() {
        let at =
            |z: f64, r: f64| Key::circle(DVec3::new(1e12, 5.0, 1e-3 * z), DQuat::from_rotation_x(0.1 * z), 1e-3 * r, 8);
        let sweep = Sweep::try_new(&[at(0.0, 1.0), at(1.5, 0.8), at(3.0, 1.2)], None).unwrap();
        let p = DVec3::new(1e12 + 1.1e-3, 5.0 - 0.2e-3, 1.4e-3);
        let frame = Frame::of_points(&[DVec3::new(1e12 - 2e-3, 5.0 - 2e-3, 0.0), DVec3::new(1e12 + 2e-3, 5.0, 3e-3)]);
        let local = sweep.in_frame(frame.origin, frame.scale);
        let world = SweepBinder::new(&sweep).bind(p);
        let mine = SweepBinder::new(&local).bind(frame.to_local(p));
        assert!((world.t - mine.t).abs() < 1e-9 && (world.theta - mine.theta).abs() < 1e-9, "{world:?} {mine:?}");
        assert!((world.d - mine.d * frame.scale).abs() < 1e-9 * frame.scale, "{world:?} {mine:?}");
        let back = frame.to_world(local.point(mine.theta, mine.t, mine.d, mine.h));
        assert!((back - p).length() < 1e-9 * frame.scale, "{back} vs {p}");
        assert!((local.center(0.5) - frame.to_local(sweep.center(0.5))).length() < 1e-12);
        assert!((local.radius(1.0, 0.5) * frame.scale - sweep.radius(1.0, 0.5)).abs() < 1e-15);
    }
}
