//! The fit follows the part (the skeleton of geodesic level sets as its first guess): curved
//! and L-shaped limbs, obliquely cut rims and rigidly moved meshes, on the shared meshes, each
//! against the principal-axis first guess on the same part.

use crate::common;

use std::time::Instant;

use glam::{DQuat, DVec3};
use sweepffd::fit::axis::principal_axis;
use sweepffd::fit::{Fit, FitOptions, fit, largest_connected};
use sweepffd::mesh::Mesh;

/// Fits `vertices` with default options and with the principal axis as the first guess,
/// prints both and returns the default fit and its time in seconds.
fn fit_and_compare(mesh: &Mesh, vertices: &[u32], name: &str) -> (Fit, f64) {
    let started = Instant::now();
    let fitted = fit(mesh, vertices, &FitOptions::default()).unwrap();
    let seconds = started.elapsed().as_secs_f64();
    let positions: Vec<DVec3> = vertices.iter().map(|&v| mesh.positions[v as usize]).collect();
    let (centroid, direction) = principal_axis(&positions);
    let options = FitOptions { axis: Some(vec![centroid - direction, centroid + direction]), ..FitOptions::default() };
    let old = fit(mesh, vertices, &options).unwrap();
    let (q, o) = (fitted.quality, old.quality);
    let partial = fitted.sections.iter().filter(|s| s.open || s.borrowed).count();
    eprintln!(
        "{name}: {} vertices, {} keys ({partial} partial), RMS |d| {:.2}%, max {:.1}% of the mean radius, \
         {} without a root, {seconds:.3} s; principal axis: {} keys, RMS {:.2}%, max {:.1}%, {} without a root",
        q.vertices,
        fitted.keys.len(),
        100.0 * q.rms_d,
        100.0 * q.max_d,
        q.without_root,
        old.keys.len(),
        100.0 * o.rms_d,
        100.0 * o.max_d,
        o.without_root,
    );
    for step in &fitted.steps {
        eprintln!("  {}: RMS {:.2}%", step.label, 100.0 * step.quality.rms_d);
    }
    let complete = fitted.sections.iter().filter(|s| !s.open && !s.borrowed).count();
    eprintln!(
        "  {complete} of {} sections complete; rim {:.4?} near key 0 and the last key",
        fitted.keys.len(),
        fitted.rim
    );
    assert_eq!(q.vertices, vertices.len(), "{name}");
    assert_eq!(q.without_root, 0, "{name}: every owned vertex binds with a root");
    assert!(seconds <= 1.0, "{name}: {seconds:.3} s");
    (fitted, seconds)
}

fn load(name: &str) -> Option<Mesh> {
    common::shared_mesh(name).map(|path| Mesh::load(&path).unwrap())
}

#[test]
fn the_bunnys_ears_fit_from_their_skeletons() {
    let Some(mesh) = load("bunny_stanford_zipper.obj") else { return };
    let front = largest_connected(&mesh, |p| p.z < -0.012 && p.x < -0.055 && p.y > 0.13);
    let (fitted, _) = fit_and_compare(&mesh, &front, "bunny front ear");
    assert!(fitted.quality.rms_d <= 0.10, "front ear: {:?}", fitted.quality);
    // The back ear's cupped sections are crescents, star-shaped around no center: ≤ 15%.
    let back = largest_connected(&mesh, |p| p.x > -0.055 && p.x < 0.0 && p.y > 0.148 && p.z < 0.01);
    let (fitted, _) = fit_and_compare(&mesh, &back, "bunny back ear");
    assert!(fitted.quality.rms_d <= 0.15, "back ear: {:?}", fitted.quality);
}

/// The armadillo's leg on the −x side from the hip down, with its foot.
fn armadillo_leg_with_foot(p: DVec3) -> bool {
    p.x < -5.0 && p.y < -8.0 && p.z < 35.0
}

/// The armadillo's leg with its foot, fitted as one part from the hip to the toes. Its foot is
/// a flat paw with claws, no tube: one sweep around the ankle's right angle stays looser than
/// the target of 10% (within the 15% allowed for sections that are not star-shaped), and the
/// foot alone fits no better. The leg from hip to ankle fits within 10%.
#[test]
fn the_armadillos_leg_with_its_foot_fits_as_one_part() {
    let Some(mesh) = load("armadillo_50k.obj") else { return };
    let whole = largest_connected(&mesh, armadillo_leg_with_foot);
    let (fitted, _) = fit_and_compare(&mesh, &whole, "armadillo leg with foot, one part");
    assert!(fitted.quality.rms_d <= 0.15, "{:?}", fitted.quality);
    // Key 0 at the hip, the last key down at the foot.
    let (hip, toe) = (fitted.keys[0].center, fitted.keys[fitted.keys.len() - 1].center);
    assert!(hip.y > -14.0 && toe.y < -40.0, "key 0 at {hip}, the last key at {toe}");

    let leg = largest_connected(&mesh, |p| armadillo_leg_with_foot(p) && p.y > -44.0);
    let (fitted, _) = fit_and_compare(&mesh, &leg, "armadillo leg, hip to ankle");
    assert!(fitted.quality.rms_d <= 0.10, "leg: {:?}", fitted.quality);
}

/// Spot's leg around (x, z) = (sx·0.21, z0) (its head is towards −z, its hind legs at
/// z0 = 0.79, its front legs at z0 = 0.06): the vertices below the belly (y = −0.56) there.
fn spot_leg(sx: f64, z0: f64) -> impl Fn(DVec3) -> bool {
    move |p: DVec3| p.y < -0.56 && (p.x - sx * 0.21).abs() < 0.2 && (p.z - z0).abs() < 0.22
}

#[test]
fn spots_legs_fit_from_their_skeletons() {
    let Some(mesh) = load("spot_triangulated.obj") else { return };
    for (name, sx, z0) in
        [("hind +x", 1.0, 0.79), ("hind −x", -1.0, 0.79), ("front +x", 1.0, 0.06), ("front −x", -1.0, 0.06)]
    {
        let leg = largest_connected(&mesh, spot_leg(sx, z0));
        let (fitted, _) = fit_and_compare(&mesh, &leg, &format!("spot {name} leg"));
        assert!(fitted.quality.rms_d <= 0.10, "spot {name} leg: {:?}", fitted.quality);
    }
}

/// A quadruped's lower leg (spot's hind leg on the +x side) selected with a box tilted 30° about x, so its rim is cut
/// obliquely: below the plane through (0, −0.6, 0.79) with normal (0, cos 30°, sin 30°).
#[test]
fn a_lower_leg_cut_obliquely_fits_with_complete_sections() {
    let Some(mesh) = load("spot_triangulated.obj") else { return };
    let normal = DVec3::new(0.0, 30f64.to_radians().cos(), 30f64.to_radians().sin());
    let origin = DVec3::new(0.0, -0.6, 0.79);
    let leg = largest_connected(&mesh, |p| (p - origin).dot(normal) < 0.0 && p.x > 0.0 && (p.z - 0.79).abs() < 0.25);
    let (fitted, _) = fit_and_compare(&mesh, &leg, "spot's obliquely cut lower leg");
    assert!(fitted.quality.rms_d <= 0.12, "{:?}", fitted.quality);
    let borrowed = fitted.sections.iter().filter(|s| s.borrowed).count();
    assert!(borrowed <= 1, "{borrowed} keys borrowed their sections: {:?}", fitted.sections);
}

/// A rotation and translation of `mesh`.
fn moved(mesh: &Mesh, rotation: DQuat, translation: DVec3) -> Mesh {
    let mut moved = mesh.clone();
    for p in &mut moved.positions {
        *p = rotation * *p + translation;
    }
    moved
}

/// Fits `vertices` of `mesh` and of its rigidly moved copy; returns the worst distance between
/// the moved keys' centers and the copy's, relative to the part's length, and the two RMS |d|.
fn moved_fit(mesh: &Mesh, vertices: &[u32], name: &str) -> (f64, f64, f64) {
    let rotation = DQuat::from_axis_angle(DVec3::new(0.3, -0.8, 0.5).normalize(), 1.1);
    let translation = DVec3::new(12.5, -40.0, 7.25);
    let other = moved(mesh, rotation, translation);
    let here = fit(mesh, vertices, &FitOptions::default()).unwrap();
    let there = fit(&other, vertices, &FitOptions::default()).unwrap();
    assert_eq!(here.keys.len(), there.keys.len(), "{name}");
    let length: f64 = here.keys.windows(2).map(|w| w[0].center.distance(w[1].center)).sum();
    let worst = here
        .keys
        .iter()
        .zip(&there.keys)
        .map(|(a, b)| (rotation * a.center + translation).distance(b.center))
        .fold(0.0, f64::max);
    let (a, b) = (here.quality.rms_d, there.quality.rms_d);
    eprintln!(
        "moved {name}: worst key center {:.2e} of the part's length {length:.4}, RMS {:.4}% vs {:.4}%",
        worst / length,
        100.0 * a,
        100.0 * b
    );
    (worst / length, a, b)
}

#[test]
fn fitting_a_rigidly_moved_part_gives_the_moved_keys() {
    let mut parts: Vec<(Mesh, Vec<u32>, &str)> = Vec::new();
    if let Some(mesh) = load("armadillo_50k.obj") {
        let leg = largest_connected(&mesh, armadillo_leg_with_foot);
        parts.push((mesh, leg, "armadillo leg with foot"));
    }
    if let Some(mesh) = load("bunny_stanford_zipper.obj") {
        let ear = largest_connected(&mesh, |p| p.z < -0.012 && p.x < -0.055 && p.y > 0.13);
        parts.push((mesh, ear, "bunny front ear"));
    }
    if let Some(mesh) = load("spot_triangulated.obj") {
        let leg = largest_connected(&mesh, spot_leg(1.0, 0.79));
        parts.push((mesh, leg, "spot hind +x leg"));
    }
    for (mesh, vertices, name) in &parts {
        let (worst, a, b) = moved_fit(mesh, vertices, name);
        assert!(worst <= 1e-6, "{name}: key centers differ by {worst} of the part's length");
        assert!((a - b).abs() <= 1e-6, "{name}: RMS |d| {a} vs {b}");
    }
}
