//! An orbit camera that frames a bounding box from an azimuth and an elevation.
//!
//! The world is taken as **Y-up** (as most OBJ files are): the camera sits on a sphere around
//! the center of the box, at `azimuth` degrees around the Y axis, measured from +Z towards +X
//! (azimuth 0 looks from the front, +Z, towards −Z; 90 looks from +X), and `elevation` degrees
//! above the XZ plane (90 looks straight down). A Z-up model is seen lying on its side; turn it
//! with the view angles (`--view 90,20` shows a model along Z from its side).

use glam::{Mat4, Vec3};

use super::RenderError;

/// Vertical field of view, degrees.
pub const FIELD_OF_VIEW_DEGREES: f32 = 30.0;

/// The direction the camera looks from: azimuth around Y (from +Z towards +X) and elevation
/// above the XZ plane, both in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewAngles {
    /// Degrees around the Y axis, from +Z towards +X; any finite value.
    pub azimuth: f32,
    /// Degrees above the XZ plane, from −90 to 90.
    pub elevation: f32,
}

impl Default for ViewAngles {
    /// Three-quarter view from the front right, a little above: azimuth 30°, elevation 20°.
    fn default() -> ViewAngles {
        ViewAngles { azimuth: 30.0, elevation: 20.0 }
    }
}

impl ViewAngles {
    /// The angles, checked: `Err(View)` if either is not finite or |elevation| > 90.
    pub fn try_new(azimuth: f32, elevation: f32) -> Result<ViewAngles, RenderError> {
        if !azimuth.is_finite() || !elevation.is_finite() || elevation.abs() > 90.0 {
            return Err(RenderError::View { azimuth, elevation });
        }
        Ok(ViewAngles { azimuth, elevation })
    }

    /// The unit vector from the target towards the eye:
    /// (cos e · sin a, sin e, cos e · cos a).
    pub fn direction(&self) -> Vec3 {
        let (a, e) = (self.azimuth.to_radians(), self.elevation.to_radians());
        Vec3::new(e.cos() * a.sin(), e.sin(), e.cos() * a.cos())
    }
}

/// A perspective camera: eye, target, up, vertical field of view and depth range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The camera position.
    pub eye: Vec3,
    /// The point looked at, in the middle of the picture.
    pub target: Vec3,
    /// The world direction that is up in the picture (not parallel to `target − eye`).
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub fov_y_degrees: f32,
    /// Near and far clip distances, 0 < near < far.
    pub near: f32,
    /// See `near`.
    pub far: f32,
}

impl Camera {
    /// The camera looking from `angles` at the center of the box (`min`, `max`), at the
    /// smallest distance where all eight corners of the box lie inside the picture of
    /// width/height `aspect` with a 5% margin on each side. A box of zero size is framed as a
    /// cube of side 1. At elevation ±90° the picture's up is the horizontal direction the
    /// azimuth points away from.
    pub fn framing(min: Vec3, max: Vec3, angles: ViewAngles, aspect: f32) -> Camera {
        let target = 0.5 * (min + max);
        let size = (max - min).length();
        let half = if size > 0.0 && size.is_finite() { 0.5 * (max - min) } else { Vec3::splat(0.5) };
        let radius = half.length();
        let direction = angles.direction();
        let up = if angles.elevation.abs() > 89.9 {
            let (a, sign) = (angles.azimuth.to_radians(), angles.elevation.signum());
            -sign * Vec3::new(a.sin(), 0.0, a.cos())
        } else {
            Vec3::Y
        };
        // Camera axes: `back` from the target to the eye, `right` and `true_up` across.
        let right = up.cross(direction).normalize_or(Vec3::X);
        let true_up = direction.cross(right);
        let tan_y = 0.9 * (0.5 * FIELD_OF_VIEW_DEGREES.to_radians()).tan();
        let tan_x = tan_y * aspect.max(1e-3);
        // A corner at c (relative to the target) is inside when the eye is at least
        // c·back + |c·right| / tan_x and c·back + |c·up| / tan_y away from the target.
        let distance = (0..8)
            .map(|i| {
                let sign = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
                let c = Vec3::new(sign(1) * half.x, sign(2) * half.y, sign(4) * half.z);
                let along = c.dot(direction);
                (along + c.dot(right).abs() / tan_x).max(along + c.dot(true_up).abs() / tan_y)
            })
            .fold(1.2 * radius, f32::max);
        Camera {
            eye: target + distance * direction,
            target,
            up,
            fov_y_degrees: FIELD_OF_VIEW_DEGREES,
            near: (distance - 1.5 * radius).max(1e-3 * radius),
            far: distance + 1.5 * radius,
        }
    }

    /// Clip from world for a picture of width/height `aspect` (right-handed, wgpu depth 0..1):
    /// `perspective(fov_y, aspect, near, far) · look_at(eye, target, up)`.
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        perspective(self.fov_y_degrees.to_radians(), aspect, self.near, self.far) * self.view()
    }

    /// View from world, right-handed: the camera at the origin looking down −z, `up` towards +y.
    pub fn view(&self) -> Mat4 {
        let forward = (self.target - self.eye).normalize_or(-Vec3::Z);
        let side = forward.cross(self.up).normalize_or(Vec3::X);
        let up = side.cross(forward);
        Mat4::from_cols(side.extend(0.0), up.extend(0.0), (-forward).extend(0.0), Vec3::ZERO.extend(1.0)).transpose()
            * Mat4::from_translation(-self.eye)
    }

    /// The unit direction towards the key light: from above, the left and the front of the
    /// camera, so that it moves with the view.
    pub fn key_light(&self) -> Vec3 {
        let back = (self.eye - self.target).normalize_or(Vec3::Z);
        let right = self.up.cross(back).normalize_or(Vec3::X);
        let up = back.cross(right);
        (0.8 * back + 0.6 * up - 0.4 * right).normalize()
    }
}

/// Clip from view: right-handed perspective with vertical field of view `fov_y` (radians),
/// mapping view depth −near → 0 and −far → 1 (wgpu's depth range).
fn perspective(fov_y: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let h = 1.0 / (0.5 * fov_y).tan();
    let w = h / aspect;
    let r = far / (near - far);
    Mat4::from_cols(
        glam::Vec4::new(w, 0.0, 0.0, 0.0),
        glam::Vec4::new(0.0, h, 0.0, 0.0),
        glam::Vec4::new(0.0, 0.0, r, -1.0),
        glam::Vec4::new(0.0, 0.0, r * near, 0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_view_looks_from_the_front_right_above() {
        let d = ViewAngles::default().direction();
        assert!(d.x > 0.0 && d.y > 0.0 && d.z > 0.0, "{d}");
        assert!((d.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn framed_box_corners_are_inside_the_picture() {
        let (min, max) = (Vec3::new(-1.0, 0.0, -3.0), Vec3::new(2.0, 5.0, 1.0));
        for (azimuth, elevation, aspect) in [(30.0, 20.0, 4.0 / 3.0), (200.0, -45.0, 0.5), (0.0, 90.0, 2.0)] {
            let camera = Camera::framing(min, max, ViewAngles::try_new(azimuth, elevation).unwrap(), aspect);
            let clip_from_world = camera.view_projection(aspect);
            for i in 0..8 {
                let corner = Vec3::new(
                    if i & 1 == 0 { min.x } else { max.x },
                    if i & 2 == 0 { min.y } else { max.y },
                    if i & 4 == 0 { min.z } else { max.z },
                );
                let ndc = clip_from_world.project_point3(corner);
                assert!(ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0, "{azimuth},{elevation}: corner {corner} at {ndc}");
                assert!((0.0..1.0).contains(&ndc.z), "{azimuth},{elevation}: corner {corner} depth {}", ndc.z);
            }
        }
    }

    #[test]
    fn near_and_far_map_to_depth_zero_and_one() {
        let camera = Camera::framing(-Vec3::ONE, Vec3::ONE, ViewAngles::default(), 1.5);
        let m = camera.view_projection(1.5);
        let forward = (camera.target - camera.eye).normalize();
        let near = m.project_point3(camera.eye + camera.near * forward);
        let far = m.project_point3(camera.eye + camera.far * forward);
        assert!(near.z.abs() < 1e-5 && (far.z - 1.0).abs() < 1e-5, "{near} {far}");
        assert!(near.x.abs() < 1e-5 && near.y.abs() < 1e-5);
        // Up in the world is up in the picture.
        let above = m.project_point3(camera.target + Vec3::Y * 0.1);
        assert!(above.y > 0.0, "{above}");
    }

    #[test]
    fn elevation_beyond_ninety_is_an_error() {
        assert!(ViewAngles::try_new(0.0, 91.0).is_err());
        assert!(ViewAngles::try_new(f32::NAN, 0.0).is_err());
        assert!(ViewAngles::try_new(-720.0, -90.0).is_ok());
    }

    #[test]
    fn empty_box_is_framed_as_a_unit_sphere() {
        let camera = Camera::framing(Vec3::ONE, Vec3::ONE, ViewAngles::default(), 1.0);
        assert!(camera.eye.is_finite() && camera.near > 0.0 && camera.far > camera.near);
    }
}
