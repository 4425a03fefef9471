//! Binding on synthetic sweeps: roots, ends, round trips, rigid motion.

use glam::{DQuat, DVec3};

use super::*;
use crate::deform::deform_vertex;
use crate::sweep::Key;

/// A sweep bent through three quarters of a circle of radius 2 in the xz plane, frames
/// following the bend: the cross-section planes of its first and last quarter cross, so many
/// points lie on several of them.
fn u_bend() -> Sweep {
    let keys: Vec<Key> = (0..=KEYS)
        .map(|i| {
            let a = 1.5 * std::f64::consts::PI * i as f64 / KEYS as f64;
            let center = DVec3::new(2.0 - 2.0 * a.cos(), 0.0, 2.0 * a.sin());
            let rotation = DQuat::from_rotation_y(a);
            Key { center, rotation, radii: (0..8).map(|j| 0.5 + 0.1 * (j % 3) as f64).collect() }
        })
        .collect();
    Sweep::try_new(&keys, None).unwrap()
}

const KEYS: usize = 9;

fn straight() -> Sweep {
    let keys = [
        Key::circle(DVec3::ZERO, DQuat::IDENTITY, 1.0, 8),
        Key::circle(DVec3::new(0.0, 0.0, 2.0), DQuat::IDENTITY, 0.5, 8),
    ];
    Sweep::try_new(&keys, None).unwrap()
}

/// Points around and inside the U-bend, including its inner side where the planes cross.
fn probe_points() -> Vec<DVec3> {
    let mut points = Vec::new();
    for i in 0..12 {
        for j in 0..12 {
            for k in 0..5 {
                points.push(DVec3::new(-1.0 + 0.5 * i as f64, -1.0 + 0.5 * k as f64, -1.0 + 0.35 * j as f64));
            }
        }
    }
    points
}

fn f(sweep: &Sweep, v: DVec3, t: f64) -> f64 {
    (v - sweep.center(t)).dot(sweep.normal(t))
}

#[test]
fn straight_sweep_binds_by_orthogonal_projection() {
    let sweep = straight();
    let binding = SweepBinder::new(&sweep).bind(DVec3::new(0.0, 0.3, 0.5));
    assert!((binding.t - 0.25).abs() < 1e-12);
    assert!((binding.theta - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert!((binding.d - (0.3 - 0.875)).abs() < 1e-12, "{binding:?}");
    assert!(binding.h.abs() < 1e-15);
}

#[test]
fn vertex_beyond_an_end_takes_that_end_and_its_axial_offset() {
    let sweep = straight();
    let binder = SweepBinder::new(&sweep);
    let below = binder.bind(DVec3::new(0.2, 0.0, -0.75));
    assert_eq!((below.t, below.h), (0.0, -0.75));
    let above = binder.bind(DVec3::new(0.0, -0.1, 2.5));
    assert_eq!(above.t, 1.0);
    assert!((above.h - 0.5).abs() < 1e-15);
}

#[test]
fn vertex_on_the_axis_binds_without_nan() {
    let binding = SweepBinder::new(&straight()).bind(DVec3::new(0.0, 0.0, 1.0));
    assert_eq!(binding.theta, 0.0);
    assert!((binding.d + 0.75).abs() < 1e-12);
}

#[test]
fn every_bound_root_is_a_root_and_the_nearest_one() {
    let sweep = u_bend();
    let binder = SweepBinder::new(&sweep);
    let samples = 20_000;
    let mut multi_root_vertices = 0;
    for v in probe_points() {
        let at = binder.cross_section(v);
        let segment = &sweep.segments()[at.segment];
        let t = segment.t0 + at.s * (segment.t1 - segment.t0);
        let roots = binder.roots(v);
        if roots.len() > 1 {
            multi_root_vertices += 1;
        }
        if roots.is_empty() {
            assert!(t == 0.0 || t == 1.0);
            continue;
        }
        assert!(f(&sweep, v, t).abs() <= 1e-12, "f(t) = {} at {v}", f(&sweep, v, t));
        // Dense sampling: no sign change of f brackets a root nearer to v.
        let bound_distance = sweep.center(t).distance(v);
        let mut previous = f(&sweep, v, 0.0);
        for i in 1..=samples {
            let (a, b) = ((i - 1) as f64 / samples as f64, i as f64 / samples as f64);
            let value = f(&sweep, v, b);
            if (previous >= 0.0) != (value >= 0.0) {
                let nearest = sweep.center(a).distance(v).min(sweep.center(b).distance(v));
                assert!(nearest >= bound_distance - 1e-3, "a nearer root near t = {a} for {v}");
            }
            previous = value;
        }
    }
    assert!(multi_root_vertices > 50, "the probe must exercise vertices with several roots");
}

#[test]
fn bind_then_deform_at_rest_reproduces_every_vertex() {
    let sweep = u_bend();
    let binder = SweepBinder::new(&sweep);
    for v in probe_points() {
        let back = deform_vertex(&sweep, &binder.bind(v));
        assert!(back.distance(v) < 1e-12, "{v} came back as {back}");
    }
}

#[test]
fn rigid_motion_of_every_key_moves_every_vertex_by_that_motion() {
    let rest = u_bend();
    let motion = DQuat::from_axis_angle(DVec3::new(0.3, -1.0, 0.4).normalize(), 0.9);
    let offset = DVec3::new(3.0, -2.0, 7.0);
    let keys: Vec<Key> = (0..=KEYS)
        .map(|i| {
            let t = rest.knots()[i];
            Key {
                center: motion * rest.center(t) + offset,
                rotation: motion * rest.orientation(t),
                radii: (0..8).map(|j| 0.5 + 0.1 * (j % 3) as f64).collect(),
            }
        })
        .collect();
    let posed = Sweep::try_new(&keys, Some(rest.knots())).unwrap();
    let binder = SweepBinder::new(&rest);
    for v in probe_points() {
        let moved = deform_vertex(&posed, &binder.bind(v));
        assert!(moved.distance(motion * v + offset) < 1e-12);
    }
}

#[test]
fn bind_vertices_leaves_unowned_vertices_unbound() {
    let sweeps = [straight()];
    let positions = [DVec3::new(0.0, 0.5, 1.0), DVec3::new(5.0, 5.0, 5.0)];
    let bindings = bind_vertices(&sweeps, &[0, UNOWNED], &positions, &|_| {});
    assert_eq!(bindings[0].sweep, 0);
    assert_eq!(bindings[1], Binding::UNOWNED);
}

/// The nearest root as found by searching every interval in order: the first root along the
/// axis of those nearest to v, what [`SweepBinder::nearest_root`] must return.
fn nearest_root_of_every_interval(sweep: &Sweep, binder: &SweepBinder, v: DVec3) -> Option<AxisPoint> {
    let mut best: Option<(AxisPoint, f64)> = None;
    for at in binder.roots(v) {
        let d2 = sweep.segments()[at.segment].curve.value(at.s).distance_squared(v);
        if best.is_none_or(|(_, best_d2)| d2 < best_d2) {
            best = Some((at, d2));
        }
    }
    best.map(|(at, _)| at)
}

/// A long sweep winding in three dimensions, 24 keys.
fn long_wave() -> Sweep {
    let keys: Vec<Key> = (0..24)
        .map(|i| {
            let s = i as f64 * 0.4;
            let center = DVec3::new(s, 0.8 * (0.7 * s).sin(), 0.5 * (0.4 * s).cos());
            Key { center, rotation: DQuat::from_rotation_y(0.3 * (0.5 * s).sin()), radii: vec![0.3, 0.35, 0.25, 0.3] }
        })
        .collect();
    Sweep::try_new(&keys, None).unwrap()
}

#[test]
fn skipping_far_intervals_finds_the_root_every_interval_would() {
    let mut compared = 0;
    for sweep in [u_bend(), long_wave(), straight()] {
        let binder = SweepBinder::new(&sweep);
        let (lo, hi) = sweep
            .segments()
            .iter()
            .flat_map(|segment| [segment.curve.value(0.0), segment.curve.value(1.0)])
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
        let (lo, hi) = (lo - DVec3::ONE, hi + DVec3::ONE);
        for i in 0..4000 {
            let f = |k: f64| (i as f64 * k).fract();
            let v = lo + (hi - lo) * DVec3::new(f(0.618_034), f(0.754_878), f(0.569_840));
            let expected = nearest_root_of_every_interval(&sweep, &binder, v);
            assert_eq!(binder.nearest_root(v), expected, "{v}");
            compared += usize::from(expected.is_some());
        }
    }
    assert!(compared > 3000, "only {compared} points had a root");
}

#[test]
fn an_intervals_bounding_sphere_holds_its_piece_and_rules_out_far_intervals() {
    let sweep = long_wave();
    let binder = SweepBinder::new(&sweep);
    for (segment, bound) in sweep.segments().iter().zip(&binder.bounds) {
        for k in 0..=100 {
            let p = segment.curve.value(k as f64 / 100.0);
            for v in [p, p + DVec3::new(0.3, -2.0, 1.0), DVec3::new(50.0, 3.0, -2.0)] {
                assert!(bound.nearest_possible(v) <= v.distance(p), "{v} nearer than the bound allows");
            }
        }
    }
    // Near key 3, the root is at most a radius away, and most intervals lie farther than that.
    let v = sweep.segments()[3].curve.value(0.0) + DVec3::new(0.0, 0.2, 0.1);
    let at = binder.nearest_root(v).unwrap();
    let d2 = sweep.segments()[at.segment].curve.value(at.s).distance_squared(v);
    let skipped = binder.bounds.iter().filter(|b| b.nearest_possible(v).max(0.0).powi(2) > d2).count();
    assert!(skipped >= 18, "{skipped} of {} intervals ruled out", binder.bounds.len());
}
