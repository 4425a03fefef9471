//! Closed-form oracles and continuity checks for the sweep model.

use std::f64::consts::PI;

use glam::{DQuat, DVec3};

use super::*;

/// A straight sweep along z with `keys` circular keys of radii `radius(i)`.
fn straight(length: f64, radii: &[f64]) -> Sweep {
    let n = radii.len() - 1;
    let keys: Vec<Key> = radii
        .iter()
        .enumerate()
        .map(|(i, &r)| Key::circle(DVec3::new(0.0, 0.0, length * i as f64 / n as f64), DQuat::IDENTITY, r, 12))
        .collect();
    Sweep::try_new(&keys, None).unwrap()
}

fn bent_keys() -> Vec<Key> {
    let centers = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(0.2, 0.1, 1.0),
        DVec3::new(0.9, -0.3, 1.6),
        DVec3::new(1.8, 0.0, 1.9),
        DVec3::new(2.5, 0.6, 2.8),
    ];
    centers
        .iter()
        .enumerate()
        .map(|(i, &center)| Key {
            center,
            rotation: DQuat::from_rotation_y(0.45 * i as f64) * DQuat::from_rotation_z(0.3 * i as f64),
            radii: (0..8).map(|j| 0.3 + 0.05 * ((i + 2 * j) % 5) as f64).collect(),
        })
        .collect()
}

fn relative_error(value: f64, exact: f64) -> f64 {
    ((value - exact) / exact).abs()
}

#[test]
fn cylinder_volume_is_pi_r_squared_l() {
    let sweep = straight(3.0, &[0.7, 0.7, 0.7, 0.7]);
    let exact = PI * 0.7 * 0.7 * 3.0;
    assert!(relative_error(sweep.volume(), exact) <= 1e-9, "{} vs {exact}", sweep.volume());
}

#[test]
fn frustum_volume_matches_closed_form() {
    let (r0, r1, length) = (1.3, 0.4, 2.5);
    let sweep = straight(length, &[r0, r1]);
    let exact = PI * length * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
    assert!(relative_error(sweep.volume(), exact) <= 1e-9, "{} vs {exact}", sweep.volume());
}

#[test]
fn frustum_volume_is_unchanged_by_a_rigid_motion() {
    let (r0, r1, length) = (1.3, 0.4, 2.5);
    let motion = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 1.1);
    let offset = DVec3::new(10.0, -4.0, 7.5);
    let keys = [
        Key::circle(offset, motion, r0, 16),
        Key::circle(offset + motion * DVec3::new(0.0, 0.0, length), motion, r1, 16),
    ];
    let sweep = Sweep::try_new(&keys, None).unwrap();
    let exact = PI * length * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
    assert!(relative_error(sweep.volume(), exact) <= 1e-9);
}

#[test]
fn volume_of_a_bent_sweep_is_invariant_under_rigid_motion() {
    let keys = bent_keys();
    let motion = DQuat::from_axis_angle(DVec3::new(-0.3, 0.8, 0.1).normalize(), 2.3);
    let offset = DVec3::new(-3.0, 5.0, 1.0);
    let moved: Vec<Key> = keys
        .iter()
        .map(|key| Key { center: motion * key.center + offset, rotation: motion * key.rotation, ..key.clone() })
        .collect();
    let a = Sweep::try_new(&keys, None).unwrap().volume();
    let b = Sweep::try_new(&moved, None).unwrap().volume();
    assert!(relative_error(b, a) <= 1e-12, "{a} vs {b}");
}

#[test]
fn center_passes_exactly_through_every_key_center() {
    let keys = bent_keys();
    let sweep = Sweep::try_new(&keys, None).unwrap();
    for (key, &u) in keys.iter().zip(sweep.knots()) {
        assert_eq!(sweep.center(u), key.center);
    }
}

#[test]
fn center_is_natural_at_both_ends() {
    let sweep = Sweep::try_new(&bent_keys(), None).unwrap();
    assert_eq!(sweep.center_second_derivative(0.0), DVec3::ZERO);
    assert!(sweep.center_second_derivative(1.0).length() < 1e-12);
}

#[test]
fn center_derivatives_are_continuous_at_the_knots_by_finite_differences() {
    let sweep = Sweep::try_new(&bent_keys(), None).unwrap();
    let eps = 1e-6;
    for &u in &sweep.knots()[1..sweep.knots().len() - 1] {
        // One-sided difference quotients from each side must agree (C¹) …
        let left = (sweep.center(u) - sweep.center(u - eps)) / eps;
        let right = (sweep.center(u + eps) - sweep.center(u)) / eps;
        assert!((left - right).length() < 1e-4 * left.length().max(1.0), "C′ jumps at {u}");
        // … and so must the second difference quotients (C²).
        let left2 = (sweep.center(u) - 2.0 * sweep.center(u - eps) + sweep.center(u - 2.0 * eps)) / (eps * eps);
        let right2 = (sweep.center(u + 2.0 * eps) - 2.0 * sweep.center(u + eps) + sweep.center(u)) / (eps * eps);
        assert!((left2 - right2).length() < 1e-2 * left2.length().max(1.0), "C″ jumps at {u}");
        // The analytic derivatives agree with the central differences.
        let central = (sweep.center(u + eps) - sweep.center(u - eps)) / (2.0 * eps);
        assert!((central - sweep.center_derivative(u)).length() < 1e-6);
    }
}

#[test]
fn orientation_at_each_knot_is_the_key_rotation() {
    let keys = bent_keys();
    let sweep = Sweep::try_new(&keys, None).unwrap();
    for (key, &u) in keys.iter().zip(sweep.knots()) {
        let expected = DMat3::from_quat(key.rotation.normalize());
        let actual = DMat3::from_quat(sweep.orientation(u));
        assert!((expected - actual).to_cols_array().iter().all(|e| e.abs() < 1e-15), "at u = {u}");
    }
}

#[test]
fn surface_point_at_a_key_is_the_key_radius_away_from_its_center() {
    let keys = bent_keys();
    let sweep = Sweep::try_new(&keys, None).unwrap();
    let (key, u) = (&keys[2], sweep.knots()[2]);
    for (j, rho) in key.radii.iter().enumerate() {
        let theta = std::f64::consts::TAU * j as f64 / key.radii.len() as f64;
        let expected = key.center + key.rotation * DVec3::new(rho * theta.cos(), rho * theta.sin(), 0.0);
        assert!((sweep.surface_point(theta, u) - expected).length() < 1e-14);
    }
}

#[test]
fn locate_puts_interior_knots_at_the_start_of_their_interval() {
    let sweep = Sweep::try_new(&bent_keys(), None).unwrap();
    let u2 = sweep.knots()[2];
    assert_eq!(sweep.locate(u2), AxisPoint { segment: 2, s: 0.0 });
    assert_eq!(sweep.locate(1.0), AxisPoint { segment: 3, s: 1.0 });
    assert_eq!(sweep.locate(-0.5), AxisPoint { segment: 0, s: 0.0 });
}

#[test]
fn invalid_keys_are_rejected_with_the_key_at_fault() {
    let mut keys = bent_keys();
    keys[3].radii[5] = -1.0;
    assert_eq!(Sweep::try_new(&keys, None), Err(SweepError::NegativeRadius { key: 3, index: 5, value: -1.0 }));
    let mut keys = bent_keys();
    keys[1].rotation = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    assert_eq!(Sweep::try_new(&keys, None), Err(SweepError::ZeroRotation { key: 1 }));
    let mut keys = bent_keys();
    keys[4].radii.pop();
    assert_eq!(Sweep::try_new(&keys, None), Err(SweepError::RadiusCountMismatch { key: 4, expected: 8, found: 7 }));
    let mut keys = bent_keys();
    keys[2].center.y = f64::NAN;
    assert_eq!(Sweep::try_new(&keys, None), Err(SweepError::NonFinite { key: 2, field: "center" }));
    assert_eq!(Sweep::try_new(&bent_keys()[..1], None), Err(SweepError::TooFewKeys { count: 1 }));
}

use glam::DMat3;

#[test]
fn a_sweep_moved_rigidly_equals_the_one_rebuilt_from_the_moved_keys() {
    let keys = bent_keys();
    let sweep = Sweep::try_new(&keys, None).unwrap();
    let (rotation, translation) =
        (DQuat::from_rotation_x(2.3) * DQuat::from_rotation_z(-0.8), DVec3::new(3.0, -1.5, 40.0));
    let moved_keys: Vec<Key> = keys
        .iter()
        .map(|key| Key {
            center: rotation * key.center + translation,
            rotation: (rotation * key.rotation).normalize(),
            radii: key.radii.clone(),
        })
        .collect();
    let rebuilt = sweep.try_with_axis(&moved_keys).unwrap();
    let mut moved = sweep.clone();
    moved.try_move_rigidly(&moved_keys, rotation).unwrap();
    let mut worst = 0.0f64;
    for i in 0..=40 {
        let t = i as f64 / 40.0;
        for (theta, d, h) in [(0.0, 0.0, 0.0), (1.9, 0.2, -0.1), (4.4, -0.1, 0.3)] {
            worst = worst.max(moved.point(theta, t, d, h).distance(rebuilt.point(theta, t, d, h)));
        }
        worst = worst.max(moved.center_second_derivative(t).distance(rebuilt.center_second_derivative(t)));
    }
    // Relative to the coordinates (|C| ≈ 45): a few ulps.
    assert!(worst <= 1e-14 * 45.0, "moved vs rebuilt: {worst:e}");
    for (i, key) in moved_keys.iter().enumerate() {
        assert_eq!(moved.center(moved.knots()[i]), key.center, "C(u_{i}) is the moved center exactly");
    }
    // The rotation matters: moving by another one is a different sweep.
    let mut wrong = sweep.clone();
    wrong.try_move_rigidly(&moved_keys, DQuat::IDENTITY).unwrap();
    assert!(wrong.center(0.37).distance(rebuilt.center(0.37)) > 1e-3);
    // A moved key that is not valid is refused, the sweep untouched.
    let mut bad = moved_keys.clone();
    bad[2].center.x = f64::NAN;
    let mut kept = sweep.clone();
    assert!(kept.try_move_rigidly(&bad, rotation).is_err());
    assert_eq!(kept, sweep);
}

/// The volume enclosed by a dense tessellation of S(θ, t) closed by fans at both ends (the
/// divergence theorem, |Σ det(a, b, c)| / 6), to check Eq. 1 without it.
fn tessellated_volume(sweep: &Sweep, along: usize, around: usize) -> f64 {
    let point = |i: usize, j: usize| {
        sweep.surface_point(std::f64::consts::TAU * j as f64 / around as f64, i as f64 / along as f64)
    };
    let mut six_volume = 0.0;
    let mut triangle = |a: DVec3, b: DVec3, c: DVec3| six_volume += a.dot(b.cross(c));
    for i in 0..along {
        for j in 0..around {
            let (a, b, c, d) = (point(i, j), point(i, j + 1), point(i + 1, j + 1), point(i + 1, j));
            triangle(a, b, c);
            triangle(a, c, d);
        }
    }
    let (start, end) = (sweep.center(0.0), sweep.center(1.0));
    for j in 0..around {
        triangle(start, point(0, j + 1), point(0, j));
        triangle(end, point(along, j), point(along, j + 1));
    }
    six_volume.abs() / 6.0
}

/// Eq. 1 stays exact for the cubic rotation interpolation: on a bent, tilting sweep its volume
/// equals that of the tessellated surface, as the linear interpolation's does, and both are
/// invariant under a rigid motion; the two interpolations give different sweeps. The sections
/// are circles (of radii varying along the sweep): Eq. 1 counts the volume a section sweeps as
/// it slides along its normal, not the volume it sweeps turning about a center that is not its
/// centroid, so it is exact only for sections centred on C.
#[test]
fn eq1_volume_of_either_rotation_interpolation_matches_its_tessellated_surface() {
    let keys: Vec<Key> = bent_keys()
        .into_iter()
        .enumerate()
        .map(|(i, key)| Key { radii: vec![0.3 + 0.05 * (i % 3) as f64; 8], ..key })
        .collect();
    let motion = DQuat::from_axis_angle(DVec3::new(-0.3, 0.8, 0.1).normalize(), 2.3);
    let moved: Vec<Key> = keys
        .iter()
        .map(|key| Key { center: motion * key.center, rotation: motion * key.rotation, ..key.clone() })
        .collect();
    let mut volumes = Vec::new();
    for rotation in [RotationInterpolation::Linear, RotationInterpolation::Cubic] {
        let sweep = Sweep::try_new_with(&keys, None, rotation).unwrap();
        // The polygons inscribed in the circular sections have sin(2π/n)/(2π/n) of their area.
        let step = std::f64::consts::TAU / 256.0;
        let (eq1, tessellated) = (sweep.volume().abs(), tessellated_volume(&sweep, 2000, 256) * step / step.sin());
        println!("{rotation:?}: Eq. 1 {eq1:.9}, tessellated {tessellated:.9}");
        assert!(relative_error(tessellated, eq1) <= 1e-5, "{rotation:?}: {eq1} vs {tessellated}");
        let turned = Sweep::try_new_with(&moved, None, rotation).unwrap().volume().abs();
        assert!(relative_error(turned, eq1) <= 1e-12, "{rotation:?}: {eq1} vs {turned} moved");
        volumes.push(eq1);
    }
    assert!(relative_error(volumes[1], volumes[0]) > 1e-4, "the interpolations agree: {volumes:?}");
}

#[test]
fn cubic_rotation_normal_is_continuous_in_its_derivative_across_keys() {
    let cubic = Sweep::try_new_with(&bent_keys(), None, RotationInterpolation::Cubic).unwrap();
    let linear = Sweep::try_new(&bent_keys(), None).unwrap();
    let kink = |sweep: &Sweep| {
        let h = 1e-6;
        sweep.knots()[1..sweep.knots().len() - 1]
            .iter()
            .map(|&u| {
                let left = (sweep.normal(u - h) - sweep.normal(u - 2.0 * h)) / h;
                let right = (sweep.normal(u + 2.0 * h) - sweep.normal(u + h)) / h;
                (left - right).length() / left.length().max(right.length())
            })
            .fold(0.0, f64::max)
    };
    let (smooth, sharp) = (kink(&cubic), kink(&linear));
    println!("N′ jumps across the keys by at most {smooth:.2e} (cubic) and {sharp:.2e} (linear), relative");
    assert!(smooth < 1e-4, "cubic: N′ jumps by {smooth}");
    assert!(sharp > 0.05, "linear: N′ jumps by only {sharp}");
}
