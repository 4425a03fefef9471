//! Pointer gestures and the one edit each drag makes (§4): a mesh point follows the pointer on
//! the plane facing the camera through where it was grabbed; a key ring is moved on that plane,
//! turned about the view direction or has its radii scaled.

use glam::{DQuat, DVec3, Vec2, Vec3};

use super::orbit::Orbit;
use super::session::Settings;
use sweepffd::bind::VertexBinding;
use sweepffd::edit::{DragMode, Edit, KeyMode};

/// What dragging a key ring does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum KeyTool {
    /// Moves the key on the plane facing the camera.
    #[default]
    Move,
    /// Turns the key about the view direction through its center.
    Rotate,
    /// Scales the key's radii by the ratio of the pointer's distances from its center.
    Scale,
}

/// A drag in progress.
#[derive(Clone, Debug, PartialEq)]
pub enum Gesture {
    /// Turning the camera.
    Orbit { last: Vec2 },
    /// Moving the camera sideways.
    Pan { last: Vec2 },
    /// Dragging a bound mesh point (direct point control).
    Point {
        /// The sweep that owns the vertex.
        sweep: String,
        /// The vertex's binding to the sweep at rest.
        binding: VertexBinding,
        /// Where the point was when grabbed.
        anchor: Vec3,
        /// The key below the point, and its center, which a rotate drag turns the point about.
        below: usize,
        /// See `below`.
        pivot: Vec3,
    },
    /// Bending the sweep that owns a grabbed mesh point over a span around the point's t: the
    /// sweep's end C(1) follows the pointer's moves on the plane facing the camera through it,
    /// and the sweep past the span turns about C(t) by the turn that takes the end there.
    Bend {
        /// The sweep's name.
        sweep: String,
        /// Where the grabbed point is bound, the span's middle.
        t: f64,
        /// The span's width in t.
        span: f64,
        /// Where the pointer was pressed.
        start: Vec2,
        /// The sweep's end C(1) when grabbed.
        end: Vec3,
        /// C(t) and R(t) of the sweep when grabbed.
        pivot: Vec3,
        /// See `pivot`.
        frame: DQuat,
    },
    /// Dragging a key ring.
    Key {
        /// The sweep's name.
        sweep: String,
        /// The key's index.
        key: usize,
        /// What the drag does.
        tool: KeyTool,
        /// Where the pointer was pressed.
        start: Vec2,
        /// The key's center when grabbed, and where it appears.
        center: Vec3,
        /// See `center`.
        center_pixel: Vec2,
    },
}

impl Gesture {
    /// The edit that brings the grabbed thing to the pointer at `pointer`, or `None` for
    /// camera gestures.
    pub fn edit(&self, pointer: Vec2, camera: &Orbit, size: Vec2, settings: &Settings) -> Option<Edit> {
        match self {
            Gesture::Orbit { .. } | Gesture::Pan { .. } => None,
            Gesture::Point { sweep, binding, anchor, below, pivot } => {
                if settings.drag_mode == DragMode::Rotate {
                    // The angular part alone (Fig. 14d): the key below the point turns about its
                    // center (the keys after it following) so that the point heads for the point
                    // of its sphere under the pointer. Turning one key is exact, where iterating
                    // a drag_point to a target on the sphere is not (the spline through the
                    // fixed keys bends too).
                    let to = on_sphere(camera.ray(pointer, size), *pivot, anchor.distance(*pivot));
                    let turn = DQuat::from_rotation_arc(
                        (*anchor - *pivot).as_dvec3().normalize_or_zero(),
                        (to - *pivot).as_dvec3().normalize_or_zero(),
                    );
                    return Some(Edit::MoveKey {
                        sweep: sweep.clone(),
                        key: *below,
                        translate: [0.0; 3],
                        rotate: turn.to_array(),
                        mode: KeyMode::Local,
                    });
                }
                let to = camera.on_view_plane(pointer, size, *anchor).as_dvec3();
                Some(Edit::DragPoint {
                    sweep: sweep.clone(),
                    theta: binding.theta,
                    t: binding.t,
                    d: binding.d,
                    h: binding.h,
                    to: to.to_array(),
                    mode: settings.drag_mode,
                    keys: settings.drag_keys,
                })
            }
            Gesture::Bend { sweep, t, span, start, end, pivot, frame } => {
                // The turn about C(t) that takes the sweep's end to where the pointer's move
                // takes it, its axis in the frame of the cross-section at t.
                let moved = camera.on_view_plane(pointer, size, *end) - camera.on_view_plane(*start, size, *end);
                let (from, to) = ((*end - *pivot).as_dvec3(), (*end + moved - *pivot).as_dvec3());
                let axis = from.cross(to);
                let angle = axis.length().atan2(from.dot(to));
                let local = frame.inverse() * axis.try_normalize().unwrap_or(DVec3::X);
                Some(Edit::Bend {
                    sweep: sweep.clone(),
                    t: *t,
                    span: *span,
                    axis: local.to_array(),
                    angle_deg: angle.to_degrees(),
                })
            }
            Gesture::Key { sweep, key, tool, start, center, center_pixel } => {
                let (sweep, key) = (sweep.clone(), *key);
                let identity = DQuat::IDENTITY.to_array();
                Some(match tool {
                    KeyTool::Move => {
                        let from = camera.on_view_plane(*start, size, *center);
                        let to = camera.on_view_plane(pointer, size, *center);
                        let translate = (to - from).as_dvec3().to_array();
                        Edit::MoveKey { sweep, key, translate, rotate: identity, mode: settings.key_mode }
                    }
                    KeyTool::Rotate => {
                        let angle = |p: Vec2| (p - *center_pixel).to_angle();
                        // Pixel y points down, so a positive angle turns clockwise on screen: a
                        // right-handed turn about the direction the camera looks along.
                        let turn = f64::from(angle(pointer) - angle(*start));
                        let rotate = DQuat::from_axis_angle(camera.forward().as_dvec3(), turn).to_array();
                        Edit::MoveKey { sweep, key, translate: [0.0; 3], rotate, mode: settings.key_mode }
                    }
                    KeyTool::Scale => {
                        let reach = |p: Vec2| p.distance(*center_pixel).max(1.0);
                        let factor = f64::from(reach(pointer) / reach(*start)).clamp(0.05, 20.0);
                        Edit::ScaleRadii { sweep, key, factor, theta_range: None }
                    }
                })
            }
        }
    }
}

/// The point of the sphere (`center`, `radius`) where the ray (origin, unit direction) first
/// meets it, or the point of the sphere nearest to the ray if it misses.
fn on_sphere((origin, direction): (Vec3, Vec3), center: Vec3, radius: f32) -> Vec3 {
    let along = (center - origin).dot(direction);
    let nearest = origin + along * direction;
    let miss = nearest.distance(center);
    if miss < radius {
        return nearest - (radius * radius - miss * miss).sqrt() * direction;
    }
    center + radius * (nearest - center).normalize_or(-direction)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> (Orbit, Vec2) {
        (Orbit::framing(-Vec3::ONE, Vec3::ONE, 4.0 / 3.0), Vec2::new(800.0, 600.0))
    }

    #[test]
    fn point_drag_targets_the_pointer_on_the_view_plane() {
        let (camera, size) = setup();
        let anchor = Vec3::new(0.2, 0.1, 0.0);
        let gesture = Gesture::Point {
            sweep: "arm".into(),
            binding: VertexBinding { t: 0.5, theta: 1.0, d: 0.1, h: 0.0 },
            anchor,
            below: 0,
            pivot: Vec3::ZERO,
        };
        let pointer = Vec2::new(520.0, 280.0);
        let Some(Edit::DragPoint { to, theta, d, .. }) = gesture.edit(pointer, &camera, size, &Settings::default())
        else {
            panic!("a point drag makes a drag_point edit");
        };
        assert_eq!((theta, d), (1.0, 0.1));
        let to = glam::DVec3::from_array(to).as_vec3();
        assert!(camera.project(to, size).unwrap().distance(pointer) < 0.05);
        assert!((to - anchor).dot(camera.forward()).abs() < 1e-4);
    }

    #[test]
    fn rotate_drag_targets_the_sphere_about_the_pivot() {
        let (camera, size) = setup();
        let (anchor, pivot) = (Vec3::new(0.5, 0.0, 0.0), Vec3::ZERO);
        let gesture =
            Gesture::Point { sweep: "arm".into(), binding: VertexBinding::default(), anchor, below: 2, pivot };
        let settings = Settings { drag_mode: DragMode::Rotate, drag_keys: 3, ..Settings::default() };
        // The pointer over the pivot turns the point to the sphere's near side.
        let center = camera.project(pivot, size).unwrap();
        let Some(Edit::MoveKey { key, rotate, translate, mode, .. }) = gesture.edit(center, &camera, size, &settings)
        else {
            panic!("a rotate drag turns the key below the point");
        };
        assert_eq!((key, translate, mode), (2, [0.0; 3], KeyMode::Local));
        let turned = (DQuat::from_array(rotate) * anchor.as_dvec3()).as_vec3();
        assert!((turned.length() - 0.5).abs() < 1e-5);
        assert!(turned.normalize().dot(-camera.forward()) > 0.999, "{turned}");
        // A pointer off the sphere gets the sphere's point nearest its ray.
        let (origin, direction) = camera.ray(Vec2::new(790.0, 10.0), size);
        let far = on_sphere((origin, direction), pivot, 0.5);
        assert!((far.length() - 0.5).abs() < 1e-5);
        let nearest = origin + (pivot - origin).dot(direction) * direction;
        assert!((far - pivot).normalize().dot((nearest - pivot).normalize()) > 0.9999);
    }

    /// A bend drag turns the sweep about C(t) so that its end heads where the pointer's move
    /// takes it; the axis is given in the frame of the cross-section at t.
    #[test]
    fn bend_drag_turns_the_end_towards_the_pointer() {
        let (camera, size) = setup();
        let (end, pivot) = (Vec3::new(0.5, 0.0, 0.0), Vec3::ZERO);
        let frame = DQuat::from_rotation_y(0.7);
        let start = camera.project(Vec3::new(0.1, 0.0, 0.0), size).unwrap();
        let gesture = Gesture::Bend { sweep: "arm".into(), t: 0.4, span: 0.2, start, end, pivot, frame };
        let pointer = start + Vec2::new(-20.0, -60.0);
        let Some(Edit::Bend { t, span, axis, angle_deg, .. }) =
            gesture.edit(pointer, &camera, size, &Settings::default())
        else {
            panic!("a bend drag makes a bend edit");
        };
        assert_eq!((t, span), (0.4, 0.2));
        let moved = camera.on_view_plane(pointer, size, end) - camera.on_view_plane(start, size, end);
        let to = (end + moved).as_dvec3();
        let world = frame * DVec3::from_array(axis);
        let turned = DQuat::from_axis_angle(world, angle_deg.to_radians()) * end.as_dvec3();
        assert!(turned.normalize().dot(to.normalize()) > 1.0 - 1e-9, "{turned} towards {to}");
        assert!(angle_deg > 5.0, "{angle_deg}");
        assert!((DVec3::from_array(axis).length() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn key_tools_make_their_edits() {
        let (camera, size) = setup();
        let center_pixel = camera.project(Vec3::ZERO, size).unwrap();
        let key = |tool| Gesture::Key {
            sweep: "arm".into(),
            key: 1,
            tool,
            start: center_pixel + Vec2::new(50.0, 0.0),
            center: Vec3::ZERO,
            center_pixel,
        };
        let settings = Settings::default();
        let pointer = center_pixel + Vec2::new(0.0, 100.0);
        match key(KeyTool::Scale).edit(pointer, &camera, size, &settings) {
            Some(Edit::ScaleRadii { factor, .. }) => assert!((factor - 2.0).abs() < 1e-5, "{factor}"),
            other => panic!("{other:?}"),
        }
        match key(KeyTool::Rotate).edit(pointer, &camera, size, &settings) {
            Some(Edit::MoveKey { rotate, translate, .. }) => {
                let q = DQuat::from_array(rotate);
                assert!((q.angle_between(DQuat::IDENTITY) - std::f64::consts::FRAC_PI_2).abs() < 1e-5);
                assert_eq!(translate, [0.0; 3]);
            }
            other => panic!("{other:?}"),
        }
        match key(KeyTool::Move).edit(center_pixel + Vec2::new(50.0, 0.0), &camera, size, &settings) {
            Some(Edit::MoveKey { translate, .. }) => assert_eq!(translate, [0.0; 3]),
            other => panic!("{other:?}"),
        }
    }
}
