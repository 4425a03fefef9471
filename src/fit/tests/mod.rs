mod autorig;
mod autorig_characters;
mod autorig_game_man;
mod autorig_hand;
mod autorig_star;
mod autorig_t_pose;
pub(crate) mod bent_tube;
mod falloff;
mod falloff_meshes;
mod falloff_rebind;
mod fit_sections;
mod fit_skeleton;
mod rigged_parts;
mod twin;

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
    let frames = super::frames::transported_frames(&normals, None);
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
    let with = |o: FitOptions| fit(&mesh, &all, &o).unwrap_err();
    let option = |o: FitOptions| match with(o) {
        FitError::Options(error) => error,
        other => panic!("not an option error: {other}"),
    };
    assert_eq!(option(FitOptions { keys: 1, ..FitOptions::default() }), OptionError::TooFewKeys(1));
    assert_eq!(option(FitOptions { radii: 2, ..FitOptions::default() }), OptionError::TooFewRadii(2));
    let below = option(FitOptions { max_keys: 3, ..FitOptions::default() });
    assert_eq!(below, OptionError::MaxKeysBelowKeys { max_keys: 3, keys: 6 });
    assert_eq!((below.field(), below.to_string().as_str()), ("max_keys", "max_keys (3) must be at least keys (6)"));
    let radii = option(FitOptions { radii: 10_000_000, ..FitOptions::default() });
    assert_eq!(radii.to_string(), "radii 10000000 is over the limit of 4096 radii per key");
    let keys = option(FitOptions { keys: 2000, max_keys: 2000, ..FitOptions::default() });
    assert_eq!(keys, OptionError::TooManyKeys(2000));
    let max_keys = option(FitOptions { max_keys: usize::MAX, ..FitOptions::default() });
    assert_eq!(max_keys.to_string(), "max_keys 18446744073709551615 is over the limit of 1024 keys per sweep");
    // The part has 128 vertices: more keys or radii than that (and than the defaults) are
    // refused; as many are allowed.
    let beyond = option(FitOptions { radii: 129, ..FitOptions::default() });
    assert_eq!(beyond, OptionError::BeyondPart { field: "radii", value: 129, most: 128, vertices: 128 });
    assert_eq!(beyond.to_string(), "radii 129 is more than a part of 128 vertices determines (at most 128)");
    let max_keys_beyond = option(FitOptions { max_keys: 129, ..FitOptions::default() });
    assert_eq!(max_keys_beyond.field(), "max_keys");
    assert!(fit(&mesh, &all, &FitOptions { radii: 128, ..FitOptions::default() }).is_ok());
    // The library names fields, never the command line's flags.
    for error in [below, radii, keys, max_keys, beyond] {
        assert!(!error.to_string().contains("--"), "{error}");
    }
    assert_eq!(with(FitOptions { axis: Some(vec![DVec3::ONE]), ..FitOptions::default() }), FitError::Axis);
    let error = fit(&mesh, &[0, 1, 2], &FitOptions::default()).unwrap_err();
    assert_eq!(error, FitError::TooFewVertices(3));
    let error = fit(&mesh, &[0, 1, 2, 500], &FitOptions::default()).unwrap_err();
    assert_eq!(error, FitError::VertexOutOfRange { index: 500, count: 128 });
    // Every other vertex of a ring: no face lies wholly in the part.
    let sparse: Vec<u32> = (0..mesh.positions.len() as u32).step_by(2).collect();
    assert_eq!(fit(&mesh, &sparse, &FitOptions::default()).unwrap_err(), FitError::NoFaces);
}

/// A cone-like tube along z from radius 1 at z = 0 to 0.5 at z = 6, 48 vertices around and 61
/// rings (ring b at z = b/10), open at both ends; `turn` rotates it by π about x (z → −z).
fn cone(turn: bool) -> Mesh {
    let keys = [(0.0, 1.0), (6.0, 0.5)].map(|(z, r)| Key::circle(DVec3::Z * z, DQuat::IDENTITY, r, 8));
    let mut mesh = surface_mesh(&Sweep::try_new(&keys, None).unwrap(), 48, 61);
    if turn {
        for p in &mut mesh.positions {
            *p = DQuat::from_rotation_x(std::f64::consts::PI) * *p;
        }
    }
    mesh
}

/// The vertices of the cone's rings `rings`.
fn rings(rings: std::ops::RangeInclusive<u32>) -> Vec<u32> {
    rings.flat_map(|b| b * 48..(b + 1) * 48).collect()
}

/// The length of the polygon of 48 sides inscribed in ring `b` of the cone.
fn ring_length(b: u32) -> f64 {
    let radius = 1.0 - 0.5 * b as f64 / 60.0;
    48.0 * 2.0 * radius * (std::f64::consts::PI / 48.0).sin()
}

#[test]
fn key_0_sits_at_the_longer_cut_of_a_part_cut_at_both_ends_either_way_round() {
    // Rings 10 to 50: cut at z = 1 (radius 0.92) and at z = 5 (radius 0.58).
    for turn in [false, true] {
        let mesh = cone(turn);
        let fitted = fit(&mesh, &rings(10..=50), &FitOptions::default()).unwrap();
        let wide = mesh.positions[10 * 48].z.signum() * DVec3::Z;
        let (first, last) = (fitted.keys[0].center, fitted.keys[fitted.keys.len() - 1].center);
        assert!(first.distance(wide) < 0.2 && last.distance(5.0 * wide) < 0.2, "turned {turn}: {first} … {last}");
        assert!((fitted.rim[0] - ring_length(10)).abs() < 1e-9, "{:?}", fitted.rim);
        assert!((fitted.rim[1] - ring_length(50)).abs() < 1e-9, "{:?}", fitted.rim);
        assert_eq!(fitted.quality.without_root, 0);
        assert!(fitted.quality.rms_d < 0.01, "{:?}", fitted.quality);
        // Every step's keys run the same way.
        for step in &fitted.steps {
            assert!(step.keys[0].center.distance(wide) < step.keys[step.keys.len() - 1].center.distance(wide));
        }
    }
}

#[test]
fn key_0_sits_at_the_only_cut_and_the_meshs_own_open_end_is_no_rim() {
    // Rings 0 to 40: the mesh's open end at z = 0 and a cut at z = 4 (the narrower end).
    for turn in [false, true] {
        let mesh = cone(turn);
        let fitted = fit(&mesh, &rings(0..=40), &FitOptions::default()).unwrap();
        let cut = mesh.positions[40 * 48].z.signum() * 4.0 * DVec3::Z;
        let (first, last) = (fitted.keys[0].center, fitted.keys[fitted.keys.len() - 1].center);
        assert!(first.distance(cut) < 0.2 && last.length() < 0.2, "turned {turn}: {first} … {last}");
        assert!((fitted.rim[0] - ring_length(40)).abs() < 1e-9 && fitted.rim[1] == 0.0, "{:?}", fitted.rim);
    }
}

#[test]
fn the_users_axis_order_wins_over_the_rim() {
    let mesh = cone(false);
    // From the free end to the cut: key 0 stays at the free end, the rim is reported at the last.
    let options = FitOptions { axis: Some(vec![DVec3::ZERO, DVec3::Z * 4.0]), ..FitOptions::default() };
    let fitted = fit(&mesh, &rings(0..=40), &options).unwrap();
    let (first, last) = (fitted.keys[0].center, fitted.keys[fitted.keys.len() - 1].center);
    assert!(first.length() < 0.2 && last.distance(DVec3::Z * 4.0) < 0.2, "{first} … {last}");
    assert!(fitted.rim[0] == 0.0 && (fitted.rim[1] - ring_length(40)).abs() < 1e-9, "{:?}", fitted.rim);
}

#[test]
fn turning_a_fit_end_for_end_keeps_its_quality() {
    let mesh = cone(false);
    let part = Part::new(&mesh, &rings(10..=50));
    let (fitted, mut steps) =
        super::refine::run(&part, &FitOptions::default(), 0.0, super::refine::KeyCount::Inserted).unwrap();
    let before: Vec<FitQuality> = steps.iter().map(|s| s.quality).collect();
    let turned = super::attached::turned(&part, &fitted, &mut steps).unwrap();
    let (q, p) = (fitted.measured.quality, turned.measured.quality);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
    assert!(
        (q.vertices, q.without_root) == (p.vertices, p.without_root)
            && close(q.mean_radius, p.mean_radius)
            && close(q.max_d, p.max_d)
            && close(q.rms_d, p.rms_d),
        "before {q:?}, turned {p:?}"
    );
    assert_eq!(turned.keys[0].center, fitted.keys[fitted.keys.len() - 1].center);
    let reversed: Vec<SectionReport> = fitted.sections.iter().rev().copied().collect();
    assert_eq!(turned.sections, reversed);
    // Every step's keys are turned too, and each is still the surface its quality was measured on.
    for (step, quality) in steps.iter().zip(before) {
        let sweep = Sweep::try_new(&step.keys, None).unwrap();
        let measured = super::quality::measure(&sweep, &part.positions).quality;
        assert!(close(measured.rms_d, quality.rms_d), "{}: {measured:?} but {quality:?}", step.label);
    }
    assert_eq!(steps.last().unwrap().keys, turned.keys);
}

#[test]
fn a_counted_fit_takes_exactly_its_keys_and_still_follows_the_part() {
    // Rings 10 to 50 of the cone: from z = 1 to z = 5.
    let mesh = cone(false);
    let part = rings(10..=50);
    let inserted = fit(&mesh, &part, &FitOptions::default()).unwrap();
    let length = |fit: &Fit| fit.keys.windows(2).map(|w| w[0].center.distance(w[1].center)).sum::<f64>();
    for keys in [3, 6, 11, 24, 40] {
        let counted = fit_with(&mesh, &part, &FitOptions::default(), 0.0, KeyCount::Exactly(keys)).unwrap();
        eprintln!(
            "{keys} keys: RMS |d| {:.3}%, key path {:.3} (inserted: {} keys, {:.3}%, {:.3})",
            100.0 * counted.quality.rms_d,
            length(&counted),
            inserted.keys.len(),
            100.0 * inserted.quality.rms_d,
            length(&inserted)
        );
        assert_eq!(counted.keys.len(), keys);
        assert!(counted.quality.rms_d <= 0.01 && counted.quality.without_root == 0, "{:?}", counted.quality);
        // Along the axis, from the wide cut to the narrow one, each key past the one before.
        assert!((length(&counted) - 4.0).abs() <= 0.1, "{keys} keys run {}", length(&counted));
        assert!(counted.keys.windows(2).all(|w| w[1].center.z > w[0].center.z), "{keys} keys");
    }
    // The fit left to itself stops at a count of its own.
    assert!(![3, 11, 24, 40].contains(&inserted.keys.len()), "{}", inserted.keys.len());
    // A count is checked as the most keys are.
    let counted = |keys| fit_with(&mesh, &part, &FitOptions::default(), 0.0, KeyCount::Exactly(keys));
    assert!(matches!(counted(1), Err(FitError::Options(OptionError::TooFewKeys(1)))));
    let most = crate::limits::MAX_KEYS_PER_SWEEP + 1;
    assert!(matches!(counted(most), Err(FitError::Options(OptionError::TooManyMaxKeys(m))) if m == most));
}

#[test]
fn the_falloff_is_the_users_or_a_fraction_of_the_parts_length() {
    let mesh = cone(false);
    let part = rings(10..=50);
    let fitted = fit(&mesh, &part, &FitOptions::default()).unwrap();
    let length: f64 = fitted.keys.windows(2).map(|w| w[0].center.distance(w[1].center)).sum();
    assert!((fitted.falloff - DEFAULT_FALLOFF_FRACTION * length).abs() < 1e-12, "{}", fitted.falloff);
    assert!((length - 4.0).abs() < 0.1, "the part is 4 long, the keys' chord {length}");
    let document = fitted.sweep_document("cone".to_string(), VertexSelection::All, None);
    assert_eq!(document.falloff, Some(fitted.falloff));

    let with = |falloff: f64| fit(&mesh, &part, &FitOptions { falloff: Some(falloff), ..FitOptions::default() });
    let given = with(0.75).unwrap();
    assert_eq!(given.falloff, 0.75);
    assert_eq!(given.sweep_document("cone".to_string(), VertexSelection::All, None).falloff, Some(0.75));
    let hard = with(0.0).unwrap();
    assert_eq!(hard.falloff, 0.0);
    assert_eq!(hard.sweep_document("cone".to_string(), VertexSelection::All, None).falloff, None);
    for bad in [-0.5, f64::NAN, f64::INFINITY] {
        assert_eq!(
            with(bad).unwrap_err().to_string(),
            format!("falloff must be a finite width of at least 0 (mesh units), found {bad}")
        );
    }
}
