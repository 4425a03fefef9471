//! The viewer's camera: orbit around a target (left drag), pan (right drag), zoom (wheel), and
//! the conversions between window pixels and world rays that picking and dragging need.

use glam::{Mat4, Vec2, Vec3};

use crate::render::{Camera, FIELD_OF_VIEW_DEGREES, ViewAngles};

/// Degrees the camera turns per pixel dragged.
const DEGREES_PER_PIXEL: f32 = 0.3;
/// Distance factor per wheel line (zooming in by one line brings the eye 10% closer).
const ZOOM_PER_LINE: f32 = 0.9;

/// An orbit camera: the eye on a sphere of radius `distance` around `target`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// The point looked at.
    pub target: Vec3,
    /// Eye-to-target distance.
    pub distance: f32,
    /// Azimuth and elevation of the eye, as in [`ViewAngles`].
    pub angles: ViewAngles,
    /// Radius of the scene's bounding sphere, for the clip planes.
    pub scene_radius: f32,
}

impl Orbit {
    /// The camera of `sweepffd render` for the box (`min`, `max`) in a window of `aspect`.
    pub fn framing(min: Vec3, max: Vec3, aspect: f32) -> Orbit {
        let angles = ViewAngles::default();
        let camera = Camera::framing(min, max, angles, aspect);
        let scene_radius = (0.5 * (max - min).length()).max(1e-6);
        Orbit { target: camera.target, distance: camera.eye.distance(camera.target), angles, scene_radius }
    }

    /// The render camera: clip planes hug the scene's bounding sphere, and never cut closer
    /// than 1/1000 of the distance.
    pub fn camera(&self) -> Camera {
        let eye = self.target + self.distance * self.angles.direction();
        let near = (self.distance - 2.0 * self.scene_radius).max(1e-3 * self.distance);
        Camera {
            eye,
            target: self.target,
            up: Vec3::Y,
            fov_y_degrees: FIELD_OF_VIEW_DEGREES,
            near,
            far: self.distance + 2.0 * self.scene_radius,
        }
    }

    /// Turns the eye around the target by a pointer motion of `delta` pixels; the elevation
    /// stays within ±89°.
    pub fn rotate(&mut self, delta: Vec2) {
        let azimuth = self.angles.azimuth - DEGREES_PER_PIXEL * delta.x;
        let elevation = (self.angles.elevation + DEGREES_PER_PIXEL * delta.y).clamp(-89.0, 89.0);
        self.angles = ViewAngles { azimuth: azimuth.rem_euclid(360.0), elevation };
    }

    /// Moves target and eye so that the point under the pointer follows it by `delta` pixels
    /// (at the target's depth) in a window `height` pixels high.
    pub fn pan(&mut self, delta: Vec2, height: f32) {
        let camera = self.camera();
        let back = (camera.eye - camera.target).normalize();
        let right = Vec3::Y.cross(back).normalize_or(Vec3::X);
        let up = back.cross(right);
        let per_pixel = 2.0 * self.distance * (0.5 * FIELD_OF_VIEW_DEGREES.to_radians()).tan() / height.max(1.0);
        self.target += per_pixel * (-delta.x * right + delta.y * up);
    }

    /// Brings the eye closer (positive `lines`) or further.
    pub fn zoom(&mut self, lines: f32) {
        let factor = ZOOM_PER_LINE.powf(lines);
        self.distance = (self.distance * factor).clamp(1e-3 * self.scene_radius, 100.0 * self.scene_radius);
    }

    /// Clip from world for a window of `size` pixels.
    pub fn view_projection(&self, size: Vec2) -> Mat4 {
        self.camera().view_projection(size.x / size.y.max(1.0))
    }

    /// The ray through `pixel` (origin at the eye, unit direction) in a window of `size`.
    pub fn ray(&self, pixel: Vec2, size: Vec2) -> (Vec3, Vec3) {
        let inverse = self.view_projection(size).inverse();
        let ndc = Vec2::new(2.0 * pixel.x / size.x - 1.0, 1.0 - 2.0 * pixel.y / size.y);
        let near = inverse.project_point3(ndc.extend(0.0));
        let far = inverse.project_point3(ndc.extend(1.0));
        (self.camera().eye, (far - near).normalize())
    }

    /// The pixel where `point` appears, or `None` behind the eye.
    pub fn project(&self, point: Vec3, size: Vec2) -> Option<Vec2> {
        let clip = self.view_projection(size) * point.extend(1.0);
        if clip.w <= 0.0 {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        Some(Vec2::new((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y))
    }

    /// Where the ray through `pixel` meets the plane through `anchor` facing the camera: the
    /// point a dragged object at `anchor` should follow.
    pub fn on_view_plane(&self, pixel: Vec2, size: Vec2, anchor: Vec3) -> Vec3 {
        let (origin, direction) = self.ray(pixel, size);
        let normal = (self.target - self.camera().eye).normalize();
        let along = direction.dot(normal);
        if along.abs() < 1e-6 {
            return anchor;
        }
        origin + direction * ((anchor - origin).dot(normal) / along)
    }

    /// The unit direction the camera looks along.
    pub fn forward(&self) -> Vec3 {
        -self.angles.direction()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn orbit() -> Orbit {
        Orbit::framing(Vec3::new(-1.0, -2.0, -1.0), Vec3::new(1.0, 2.0, 1.0), 4.0 / 3.0)
    }

    #[test]
    fn projecting_a_point_on_a_pixel_ray_gives_that_pixel() {
        let (orbit, size) = (orbit(), Vec2::new(800.0, 600.0));
        for pixel in [Vec2::new(400.0, 300.0), Vec2::new(10.0, 590.0), Vec2::new(700.0, 20.0)] {
            let (origin, direction) = orbit.ray(pixel, size);
            let back = orbit.project(origin + 3.0 * direction, size).unwrap();
            assert!(back.distance(pixel) < 1e-2, "{pixel} -> {back}");
        }
        let center = orbit.project(orbit.target, size).unwrap();
        assert!(center.distance(Vec2::new(400.0, 300.0)) < 1e-2, "{center}");
    }

    #[test]
    fn view_plane_point_lies_under_the_pixel_at_the_anchor_depth() {
        let (orbit, size) = (orbit(), Vec2::new(800.0, 600.0));
        let anchor = Vec3::new(0.3, 0.5, -0.2);
        let moved = orbit.on_view_plane(Vec2::new(500.0, 250.0), size, anchor);
        assert!((moved - anchor).dot(orbit.forward()).abs() < 1e-4);
        assert!(orbit.project(moved, size).unwrap().distance(Vec2::new(500.0, 250.0)) < 1e-2);
    }

    #[test]
    fn pan_moves_the_target_with_the_pointer() {
        let (mut orbit, size) = (orbit(), Vec2::new(800.0, 600.0));
        let before = orbit.target;
        orbit.pan(Vec2::new(40.0, 0.0), size.y);
        // The old target now appears 40 pixels to the right of the center.
        let seen = orbit.project(before, size).unwrap();
        assert!((seen.x - 440.0).abs() < 0.5 && (seen.y - 300.0).abs() < 0.5, "{seen}");
    }

    #[test]
    fn rotation_keeps_the_elevation_off_the_poles() {
        let mut orbit = orbit();
        orbit.rotate(Vec2::new(0.0, 1e4));
        assert_eq!(orbit.angles.elevation, 89.0);
        assert!(orbit.camera().view_projection(1.0).is_finite());
    }
}
