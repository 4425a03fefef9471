//! Property tests on random sweeps and points: bind-then-deform at rest is the identity (f64
//! reference and f32 twin), and a rigid motion of every key moves every point by that motion.

use std::f64::consts::TAU;

use glam::{DQuat, DVec3};
use proptest::prelude::*;
use sweepffd::bind::SweepBinder;
use sweepffd::coeffs::SweepCoefficients;
use sweepffd::cpu;
use sweepffd::deform::deform_vertex;
use sweepffd::sweep::{Key, Sweep};

/// Keys along a random walk with unit-ish steps that turn by at most ~60° per key, frames
/// following the walk, radii between 0.1 and 0.6.
fn keys() -> impl Strategy<Value = Vec<Key>> {
    (2usize..7, 3usize..13).prop_flat_map(|(n, m)| {
        let steps = prop::collection::vec((0.6f64..1.4, -1.0f64..1.0, -1.0f64..1.0, -0.5f64..0.5), n);
        let radii = prop::collection::vec(prop::collection::vec(0.1f64..0.6, m), n);
        (steps, radii).prop_map(|(steps, radii)| {
            let mut rotation = DQuat::IDENTITY;
            let mut center = DVec3::ZERO;
            steps
                .iter()
                .zip(radii)
                .enumerate()
                .map(|(i, (&(length, turn_x, turn_y, twist), radii))| {
                    if i > 0 {
                        rotation =
                            (rotation * DQuat::from_euler(glam::EulerRot::XYZ, turn_x, turn_y, twist)).normalize();
                        center += rotation * DVec3::Z * length;
                    }
                    Key { center, rotation, radii }
                })
                .collect()
        })
    })
}

fn point() -> impl Strategy<Value = DVec3> {
    (-3.0f64..3.0, -3.0f64..3.0, -1.0f64..5.0).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn bind_then_deform_at_rest_is_the_identity(keys in keys(), points in prop::collection::vec(point(), 40)) {
        let sweep = Sweep::try_new(&keys, None).unwrap();
        let binder = SweepBinder::new(&sweep);
        for v in &points {
            let back = deform_vertex(&sweep, &binder.bind(*v));
            prop_assert!(back.distance(*v) <= 1e-9, "{v} came back as {back}");
        }
    }

    #[test]
    fn f32_twin_bind_then_deform_at_rest_is_the_identity(keys in keys(), points in prop::collection::vec(point(), 40)) {
        let sweeps = [Sweep::try_new(&keys, None).unwrap()];
        let coefficients = SweepCoefficients::new(&sweeps);
        let positions = cpu::packed(&points);
        let bindings = cpu::bind::bind_to(&sweeps, &vec![0; points.len()], &positions);
        let mut out = positions.clone();
        cpu::deform::deform(&coefficients.cells, &bindings, &mut out);
        for (i, v) in points.iter().enumerate() {
            let back = DVec3::new(out[3 * i] as f64, out[3 * i + 1] as f64, out[3 * i + 2] as f64);
            prop_assert!(back.distance(*v) <= 2e-5, "{v} came back as {back}");
        }
    }

    #[test]
    fn rigid_motion_of_every_key_moves_points_rigidly(
        keys in keys(),
        points in prop::collection::vec(point(), 20),
        axis in (-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0),
        angle in 0.0f64..TAU,
        offset in (-5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0),
    ) {
        let motion = DQuat::from_axis_angle(DVec3::new(axis.0, axis.1, axis.2).normalize(), angle);
        let offset = DVec3::new(offset.0, offset.1, offset.2);
        let rest = Sweep::try_new(&keys, None).unwrap();
        let moved_keys: Vec<Key> = keys
            .iter()
            .map(|k| Key { center: motion * k.center + offset, rotation: motion * k.rotation, ..k.clone() })
            .collect();
        let posed = Sweep::try_new(&moved_keys, Some(rest.knots())).unwrap();
        let binder = SweepBinder::new(&rest);
        for v in &points {
            let moved = deform_vertex(&posed, &binder.bind(*v));
            prop_assert!(moved.distance(motion * *v + offset) <= 1e-9, "{v}");
        }
    }
}
