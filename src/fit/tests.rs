use std::f64::consts::TAU;

use glam::{DQuat, DVec3};

use super::*;
use crate::bind::SweepBinder;
use crate::mesh::Faces;
use crate::sweep::Sweep;

/// A tube mesh on the surface of `sweep`: `around` × `along` vertices at θ_a = 2πa/around,
/// t_b = b/(along − 1), joined by quads.
fn surface_mesh(sweep: &Sweep, around: usize, along: usize) -> Mesh {
    let mut positions = Vec::with_capacity(around * along);
    for b in 0..along {
        let t = b as f64 / (along - 1) as f64;
        for a in 0..around {
            positions.push(sweep.surface_point(TAU * a as f64 / around as f64, t));
        }
    }
    let mut faces = Faces::new();
    for b in 0..along as u32 - 1 {
        for a in 0..around as u32 {
            let next = (a + 1) % around as u32;
            let row = b * around as u32;
            faces.push(&[row + a, row + next, row + around as u32 + next, row + around as u32 + a]);
        }
    }
    Mesh::from_parts(positions, faces, Vec::new()).unwrap()
}

/// Radii with only even harmonics in θ, so every cross-section is symmetric about its center
/// and its area centroid is the center itself.
fn even_radii(key: usize, samples: usize) -> Vec<f64> {
    (0..samples)
        .map(|j| {
            let theta = TAU * j as f64 / samples as f64;
            1.0 + 0.1 * key as f64 + 0.2 * (2.0 * theta + 0.3 * key as f64).cos() + 0.05 * (4.0 * theta).sin()
        })
        .collect()
}

#[test]
fn fitting_a_known_straight_sweep_recovers_its_radii_within_one_percent() {
    let keys: Vec<Key> = (0..5)
        .map(|i| Key {
            center: DVec3::new(0.0, 0.0, 1.5 * i as f64),
            rotation: DQuat::IDENTITY,
            radii: even_radii(i, 8),
        })
        .collect();
    let truth = Sweep::try_new(&keys, None).unwrap();
    let mesh = surface_mesh(&truth, 128, 100);
    let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    let fitted = fit(&mesh, &all, &FitOptions::default()).unwrap();
    assert_eq!(fitted.quality.without_root, 0);
    let length = 6.0;
    let mut worst = (0.0f64, 0, 0);
    let mut compared = 0;
    for (k, key) in fitted.keys.iter().enumerate() {
        // The straight sweep through equally spaced centers has C(t) = (0, 0, 6t).
        let t = key.center.z / length;
        if !(0.0..=1.0).contains(&t) {
            continue;
        }
        assert!(key.center.truncate().length() < 1e-3, "key {k} center {} is off the axis", key.center);
        let m = key.radii.len();
        for (j, &rho) in key.radii.iter().enumerate() {
            let direction =
                key.rotation * DVec3::new((TAU * j as f64 / m as f64).cos(), (TAU * j as f64 / m as f64).sin(), 0.0);
            let phi = direction.y.atan2(direction.x).rem_euclid(TAU);
            let expected = truth.radius(phi, t);
            let error = (rho - expected).abs() / expected;
            if error > worst.0 {
                worst = (error, k, j);
            }
            compared += 1;
        }
    }
    assert!(compared >= 4 * 16, "only {compared} radii lie within the tube");
    assert!(worst.0 <= 0.01, "worst radius error {:.3e} at key {} ray {}", worst.0, worst.1, worst.2);
    eprintln!("straight sweep: {compared} radii, worst relative error {:.2e}", worst.0);
}

#[test]
fn fitting_a_known_bent_sweep_puts_its_surface_on_the_true_one() {
    let centers = [
        DVec3::ZERO,
        DVec3::new(0.4, 0.0, 1.5),
        DVec3::new(1.4, 0.3, 2.8),
        DVec3::new(2.9, 0.5, 3.5),
        DVec3::new(4.3, 0.4, 3.6),
    ];
    let normals: Vec<DVec3> =
        (0..5).map(|i| (centers[(i + 1).min(4)] - centers[i.saturating_sub(1)]).normalize()).collect();
    let frames = super::frames::transported_frames(&normals);
    let keys: Vec<Key> =
        (0..5).map(|i| Key { center: centers[i], rotation: frames[i], radii: even_radii(i, 8) }).collect();
    let truth = Sweep::try_new(&keys, None).unwrap();
    let mesh = surface_mesh(&truth, 128, 160);
    let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    let options = FitOptions { axis: Some(centers.to_vec()), ..FitOptions::default() };
    let fitted = fit(&mesh, &all, &options).unwrap();
    assert_eq!(fitted.quality.without_root, 0);
    for step in &fitted.steps {
        eprintln!("{}: {:?}", step.label, step.quality);
    }
    eprintln!("{:?}", fitted.sections);
    assert!(fitted.quality.rms_d < 0.01, "{:?}", fitted.quality);
    // Every fitted key's boundary point, bound to the true sweep, lies on its surface.
    let binder = SweepBinder::new(&truth);
    let mut worst = 0.0f64;
    for key in &fitted.keys {
        let m = key.radii.len();
        for (j, &rho) in key.radii.iter().enumerate() {
            let angle = TAU * j as f64 / m as f64;
            let point = key.center + key.rotation * DVec3::new(angle.cos(), angle.sin(), 0.0) * rho;
            if binder.roots(point).is_empty() {
                continue;
            }
            let b = binder.bind(point);
            worst = worst.max(b.d.abs() / truth.radius(b.theta, b.t));
        }
    }
    assert!(worst <= 0.01, "worst |d|/r of a fitted boundary point: {worst:.3e}");
    eprintln!(
        "bent sweep: {} keys, RMS |d| {:.2e}, worst boundary point {worst:.2e}",
        fitted.keys.len(),
        fitted.quality.rms_d
    );
}

#[test]
fn bad_options_and_parts_are_refused() {
    let keys: Vec<Key> = (0..3).map(|i| Key::circle(DVec3::Z * i as f64, DQuat::IDENTITY, 1.0, 8)).collect();
    let mesh = surface_mesh(&Sweep::try_new(&keys, None).unwrap(), 16, 8);
    let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    let with = |o: FitOptions| fit(&mesh, &all, &o).unwrap_err().to_string();
    assert_eq!(with(FitOptions { keys: 1, ..FitOptions::default() }), "--keys must be at least 2, found 1");
    assert_eq!(with(FitOptions { radii: 2, ..FitOptions::default() }), "--radii must be at least 3, found 2");
    assert_eq!(with(FitOptions { max_keys: 3, ..FitOptions::default() }), "--max-keys (3) must be at least --keys (6)");
    assert_eq!(with(FitOptions { axis: Some(vec![DVec3::ONE]), ..FitOptions::default() }), FitError::Axis.to_string());
    let error = fit(&mesh, &[0, 1, 2], &FitOptions::default()).unwrap_err();
    assert_eq!(error, FitError::TooFewVertices(3));
    let error = fit(&mesh, &[0, 1, 2, 500], &FitOptions::default()).unwrap_err();
    assert_eq!(error, FitError::VertexOutOfRange { index: 500, count: 128 });
    // Every other vertex of a ring: no face lies wholly in the part.
    let sparse: Vec<u32> = (0..mesh.positions.len() as u32).step_by(2).collect();
    assert_eq!(fit(&mesh, &sparse, &FitOptions::default()).unwrap_err(), FitError::NoFaces);
}
