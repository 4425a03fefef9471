//! Rigid motions of key cross-sections: the local transforms T of §3–§4 as they act on keys.

use glam::{DQuat, DVec3};

use crate::sweep::Key;

/// The rigid motion x ↦ to + Q·(x − from): rotation Q about `from`, then translation to `to`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// Q.
    pub rotation: DQuat,
    /// The fixed point of the rotation.
    pub from: DVec3,
    /// Where `from` goes.
    pub to: DVec3,
}

impl Motion {
    /// The motion that does nothing.
    pub const IDENTITY: Motion = Motion { rotation: DQuat::IDENTITY, from: DVec3::ZERO, to: DVec3::ZERO };

    /// The motion that takes the frame (center, rotation) of `from` onto that of `to`.
    pub fn between(from: &Key, to: &Key) -> Motion {
        Motion {
            rotation: (to.rotation.normalize() * from.rotation.normalize().inverse()).normalize(),
            from: from.center,
            to: to.center,
        }
    }

    /// Rotation `rotation` about `pivot`, then translation by `translation`.
    pub fn about(pivot: DVec3, rotation: DQuat, translation: DVec3) -> Motion {
        Motion { rotation: rotation.normalize(), from: pivot, to: pivot + translation }
    }

    /// Where the motion takes point `x`.
    pub fn point(&self, x: DVec3) -> DVec3 {
        self.to + self.rotation * (x - self.from)
    }

    /// `key` moved by the motion (radii unchanged).
    pub fn key(&self, key: &Key) -> Key {
        let mut moved = key.clone();
        self.apply(&mut moved);
        moved
    }

    /// Moves `key` by the motion in place (its radii are not touched, nor copied).
    pub fn apply(&self, key: &mut Key) {
        (key.center, key.rotation) = self.frame(key);
    }

    /// The center and rotation the motion gives `key`.
    pub fn frame(&self, key: &Key) -> (DVec3, DQuat) {
        (self.point(key.center), (self.rotation * key.rotation).normalize())
    }

    /// The fraction `w` ∈ [0, 1] of the motion, for the key at `at`: the rotation slerped from
    /// the identity and the displacement of `at` scaled, so that w = 0 leaves the key and w = 1
    /// applies the whole motion.
    pub fn fraction_at(&self, w: f64, at: DVec3) -> Motion {
        let rotation = DQuat::IDENTITY.slerp(self.rotation, w);
        Motion { rotation, from: at, to: at + w * (self.point(at) - at) }
    }

    /// The rotation angle in radians.
    pub fn angle(&self) -> f64 {
        angle_between(DQuat::IDENTITY, self.rotation)
    }
}

/// The angle of the rotation taking `a` to `b`, in [0, π].
pub fn angle_between(a: DQuat, b: DQuat) -> f64 {
    let dot = a.normalize().dot(b.normalize()).abs().min(1.0);
    2.0 * dot.acos()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn between_takes_one_frame_onto_the_other() {
        let a = Key::circle(DVec3::new(1.0, 2.0, 3.0), DQuat::from_rotation_x(0.4), 1.0, 4);
        let b = Key::circle(DVec3::new(-2.0, 0.5, 1.0), DQuat::from_rotation_y(-1.1), 1.0, 4);
        let moved = Motion::between(&a, &b).key(&a);
        assert!(moved.center.distance(b.center) < 1e-15);
        assert!(angle_between(moved.rotation, b.rotation) < 1e-7);
    }

    #[test]
    fn fractions_blend_from_nothing_to_the_whole_motion() {
        let motion = Motion::about(DVec3::X, DQuat::from_rotation_z(1.0), DVec3::new(0.0, 2.0, 0.0));
        let at = DVec3::new(3.0, 1.0, 0.0);
        assert!(motion.fraction_at(0.0, at).point(at).distance(at) < 1e-15);
        assert!(motion.fraction_at(1.0, at).point(at).distance(motion.point(at)) < 1e-14);
        assert!((motion.fraction_at(0.5, at).angle() - 0.5).abs() < 1e-12);
    }
}
