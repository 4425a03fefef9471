//! Direct controls (§4) on a bent six-key sweep: drag_point in each mode and move_section reach
//! their targets within 1e-4 × the sweep's length, in at most 50 iterations.

use glam::{DQuat, DVec3};
use sweepffd::bind::VertexBinding;
use sweepffd::edit::{
    Controls, DragMode, EditError, KeyMode, SectionTarget, angle_between, chord_length, drag_point, move_key,
    move_sections,
};
use sweepffd::sweep::{Key, Sweep};

/// Six keys along a quarter circle of radius 3 in the xz plane, frames following it, with
/// radii that vary around each key.
fn bent_keys() -> Vec<Key> {
    (0..6)
        .map(|i| {
            let a = std::f64::consts::FRAC_PI_2 * i as f64 / 5.0;
            Key {
                center: DVec3::new(3.0 - 3.0 * a.cos(), 0.0, 3.0 * a.sin()),
                rotation: DQuat::from_rotation_y(-a),
                radii: (0..8).map(|j| 0.4 + 0.05 * ((i + j) % 3) as f64).collect(),
            }
        })
        .collect()
}

fn knots(keys: &[Key]) -> Vec<f64> {
    Sweep::try_new(keys, None).unwrap().knots().to_vec()
}

fn point_on(keys: &[Key], knots: &[f64], point: VertexBinding) -> DVec3 {
    let VertexBinding { theta, t, d, h } = point;
    Sweep::try_new(keys, Some(knots)).unwrap().point(theta, t, d, h)
}

/// Drags S(θ, t) to `target` and checks it arrives within 1e-4 × length in ≤ 50 iterations.
fn check_drag(target_of: impl Fn(DVec3, &[Key]) -> DVec3, mode: DragMode, k: usize) {
    let mut keys = bent_keys();
    let knots = knots(&keys);
    let point = VertexBinding { theta: 1.2, t: 0.62, d: 0.0, h: 0.0 };
    let start = point_on(&keys, &knots, point);
    let target = target_of(start, &keys);
    let length = chord_length(&keys);
    let iterations = drag_point(&mut keys, &knots, point, target, mode, k, &Controls::default()).unwrap();
    let reached = point_on(&keys, &knots, point);
    println!("{mode:?}: {iterations} iterations, {:.2e} × length from the target", reached.distance(target) / length);
    assert!(iterations <= 50);
    assert!(reached.distance(target) <= 1e-4 * length, "{mode:?}: {reached} vs {target}");
    assert!(start.distance(target) > 0.05 * length, "the target must be a real move");
}

#[test]
fn drag_point_reaches_its_target_moving_and_turning_keys() {
    check_drag(|v, _| v + DVec3::new(0.6, -0.4, 0.5), DragMode::Both, 2);
}

#[test]
fn drag_point_reaches_its_target_by_translation() {
    check_drag(|v, _| v + DVec3::new(-0.5, 0.3, 0.4), DragMode::Translate, 3);
}

#[test]
fn drag_point_reaches_a_target_made_by_turning_the_lower_key() {
    // t = 0.62 lies above key 3. The target is where the point goes when key 3 turns (the keys
    // above following): reachable by rotation alone, and the drag must find it again.
    check_drag(
        |_, keys| {
            let mut turned = keys.to_vec();
            let turn = DQuat::from_axis_angle(DVec3::new(1.0, 0.0, -0.5).normalize(), 0.6);
            move_key(&mut turned, 3, DVec3::ZERO, turn, KeyMode::Local);
            point_on(&turned, &knots(keys), VertexBinding { theta: 1.2, t: 0.62, d: 0.0, h: 0.0 })
        },
        DragMode::Rotate,
        1,
    );
}

#[test]
fn drag_to_an_unreachable_target_reports_the_remaining_distance() {
    let mut keys = bent_keys();
    let knots = knots(&keys);
    let point = VertexBinding { theta: 0.5, t: 0.5, d: 0.0, h: 0.0 };
    let far = point_on(&keys, &knots, point) * 3.0 + DVec3::splat(10.0);
    let error = drag_point(&mut keys, &knots, point, far, DragMode::Rotate, 1, &Controls::default()).unwrap_err();
    let EditError::NotConverged { iterations, remaining, .. } = error else { panic!("{error}") };
    assert_eq!(iterations, 50);
    assert!(remaining > 1.0);
    assert!(error.to_string().starts_with("did not converge in 50 iterations: still"), "{error}");
}

#[test]
fn move_section_reaches_position_and_orientation() {
    let mut keys = bent_keys();
    let knots = knots(&keys);
    let length = chord_length(&keys);
    let before = Sweep::try_new(&keys, Some(&knots)).unwrap();
    let t = 0.37;
    let turn = DQuat::from_axis_angle(DVec3::new(1.0, 0.5, 0.2).normalize(), 0.4);
    let target = SectionTarget {
        t,
        center: before.center(t) + DVec3::new(0.3, 0.2, -0.4),
        rotation: turn * before.orientation(t),
    };
    let iterations = move_sections(&mut keys, &knots, &[target], &Controls::default()).unwrap();
    let after = Sweep::try_new(&keys, Some(&knots)).unwrap();
    let (distance, angle) =
        (after.center(t).distance(target.center), angle_between(after.orientation(t), target.rotation));
    println!("move_section: {iterations} iterations, {:.2e} × length, {angle:.2e} rad", distance / length);
    assert!(iterations <= 50);
    assert!(distance <= 1e-4 * length && angle <= 1e-3, "{distance} {angle}");
}

#[test]
fn dragging_a_bound_vertex_puts_the_deformed_vertex_on_target() {
    use sweepffd::bind::bind_vertices;
    use sweepffd::deform::deform_hard;
    use sweepffd::edit::{Edit, Posing};
    use sweepffd::synthetic::{Tube, tube_rig};

    // The rig's radius is smaller than the mesh's, so the vertices are bound with d > 0.
    let tube = Tube { rings: 24, around: 16, length: 3.0, radius: 0.4 };
    let mesh = tube.mesh();
    let rig = tube_rig(&Tube { radius: 0.3, ..tube }, 5, 8);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = bind_vertices(rig.rest(), &owners, &mesh.positions, &|_| {});
    let vertex = 12 * 16 + 5;
    assert_eq!(bindings[vertex].sweep, 0);
    let VertexBinding { theta, t, d, h } = bindings[vertex].params;
    assert!(d > 0.05, "the vertex lies off the sweep: d = {d}");
    let target = mesh.positions[vertex] + DVec3::new(0.4, -0.3, 0.2);

    let mut posing = Posing::new(&rig);
    let edit =
        Edit::DragPoint { sweep: "tube".into(), theta, t, d, h, to: target.to_array(), mode: DragMode::Both, keys: 2 };
    posing.apply(&edit).unwrap();
    let posed = posing.sweeps().unwrap();
    let mut deformed = vec![DVec3::ZERO; mesh.positions.len()];
    deform_hard(&posed, &bindings, &mesh.positions, &mut deformed);
    let miss = deformed[vertex].distance(target);
    println!("bound vertex {vertex}: {:.2e} × length from its target", miss / 3.0);
    assert!(miss <= 1e-4 * 3.0, "{} vs {target}", deformed[vertex]);
}
