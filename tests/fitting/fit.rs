//! Fitting sweeps to real mesh parts (§3, Fig. 3): every owned vertex binds with a root (no
//! end clamping) and the fit is tight, measured as RMS |d| relative to the mean radius.

use crate::common;

use std::time::Instant;

use glam::DVec3;
use sweepffd::bind::SweepBinder;
use sweepffd::fit::{Fit, FitOptions, fit, largest_connected};
use sweepffd::mesh::Mesh;
use sweepffd::sweep::Sweep;

/// The bunny's ear that bends towards −z (as the zipper scan is oriented, y up).
fn bunny_front_ear(p: DVec3) -> bool {
    p.z < -0.012 && p.x < -0.055 && p.y > 0.13
}

/// The bunny's other ear, whose cupped sections are crescents.
fn bunny_back_ear(p: DVec3) -> bool {
    p.x > -0.055 && p.x < 0.0 && p.y > 0.148 && p.z < 0.01
}

/// The armadillo's leg on the −x side, from the hip (y = −8) to the ankle (y = −44).
fn armadillo_leg(p: DVec3) -> bool {
    p.x < -5.0 && p.y < -8.0 && p.y > -44.0
}

/// The centroid of the part's boundary: its vertices that share a mesh edge with a vertex
/// outside it.
fn boundary_centroid(mesh: &Mesh, vertices: &[u32]) -> DVec3 {
    let mut inside = vec![false; mesh.positions.len()];
    for &v in vertices {
        inside[v as usize] = true;
    }
    let mut boundary = vec![false; mesh.positions.len()];
    for face in mesh.faces.iter() {
        for (i, &a) in face.iter().enumerate() {
            let b = face[(i + 1) % face.len()];
            if inside[a as usize] != inside[b as usize] {
                boundary[if inside[a as usize] { a } else { b } as usize] = true;
            }
        }
    }
    let points: Vec<DVec3> = (0..mesh.positions.len()).filter(|&v| boundary[v]).map(|v| mesh.positions[v]).collect();
    assert!(!points.is_empty(), "the part has no boundary");
    points.iter().copied().sum::<DVec3>() / points.len() as f64
}

/// Key 0 sits at the end where the part is attached: its center is nearer the boundary's
/// centroid than the last key's center is, and the fit found more rim there.
fn key_0_is_attached(mesh: &Mesh, vertices: &[u32], fitted: &Fit, name: &str) {
    let rim = boundary_centroid(mesh, vertices);
    let first = fitted.keys[0].center.distance(rim);
    let last = fitted.keys[fitted.keys.len() - 1].center.distance(rim);
    eprintln!(
        "{name}: key 0 is {first:.5} from the boundary's centroid, the last key {last:.5}; rim {:.5} near key 0, {:.5} near the last",
        fitted.rim[0], fitted.rim[1]
    );
    assert!(first < last, "{name}: key 0 is {first} from the boundary's centroid, the last key {last}");
    assert!(fitted.rim[0] > fitted.rim[1], "{name}: rim {:?}", fitted.rim);
}

/// Fits the part and checks what the acceptance asks of every fit: each vertex has a root
/// on the fitted sweep, and the reported quality agrees with binding afresh.
fn fit_part(mesh: &Mesh, vertices: &[u32], name: &str) -> Fit {
    let started = Instant::now();
    let fitted = fit(mesh, vertices, &FitOptions::default()).unwrap();
    let seconds = started.elapsed().as_secs_f64();
    let q = fitted.quality;
    eprintln!(
        "{name}: {} vertices, {} keys, max |d| {:.1}%, RMS |d| {:.2}% of the mean radius {:.5}, {seconds:.3} s",
        q.vertices,
        fitted.keys.len(),
        100.0 * q.max_d,
        100.0 * q.rms_d,
        q.mean_radius
    );
    assert_eq!(q.vertices, vertices.len());
    let sweep = Sweep::try_new(&fitted.keys, None).unwrap();
    let binder = SweepBinder::new(&sweep);
    let (mut squares, mut radii) = (0.0, 0.0);
    for &v in vertices {
        let p = mesh.positions[v as usize];
        assert!(!binder.roots(p).is_empty(), "{name}: vertex {v} at {p} binds by end clamping");
        let b = binder.bind(p);
        squares += b.d * b.d;
        radii += sweep.radius(b.theta, b.t);
    }
    let n = vertices.len() as f64;
    let rms = (squares / n).sqrt() / (radii / n);
    assert!((rms - q.rms_d).abs() <= 1e-9, "{name}: reported RMS {} but binding gives {rms}", q.rms_d);
    assert_eq!(q.without_root, 0);
    fitted
}

#[test]
fn the_bunnys_ears_fit_with_every_vertex_bound_by_a_root() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let front = largest_connected(&mesh, bunny_front_ear);
    assert!(front.len() > 1500, "{}", front.len());
    let fitted = fit_part(&mesh, &front, "front ear");
    // The principal axis alone put this ear's key 0 at its tip.
    key_0_is_attached(&mesh, &front, &fitted, "front ear");
    assert!(fitted.quality.rms_d <= 0.10, "front ear: RMS |d| {:.3} of the mean radius", fitted.quality.rms_d);

    // The back ear's sections are crescents: around no center is such a section star-shaped,
    // so the radius function jumps at the crescent's horns and the fit stays looser.
    let back = largest_connected(&mesh, bunny_back_ear);
    assert!(back.len() > 1500, "{}", back.len());
    let fitted = fit_part(&mesh, &back, "back ear");
    // The principal axis alone already started this ear at its base.
    key_0_is_attached(&mesh, &back, &fitted, "back ear");
    assert!(fitted.quality.rms_d <= 0.15, "back ear: RMS |d| {:.3} of the mean radius", fitted.quality.rms_d);
}

#[test]
fn the_armadillos_leg_fits_tightly_and_refinement_tightens_it() {
    let Some(path) = common::shared_mesh("armadillo_50k.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let leg = largest_connected(&mesh, armadillo_leg);
    assert!(leg.len() > 3000, "{}", leg.len());
    let fitted = fit_part(&mesh, &leg, "armadillo leg");
    // Cut at the hip and at the ankle, the leg is attached at the hip, the longer loop; the
    // principal axis alone put key 0 at the ankle.
    key_0_is_attached(&mesh, &leg, &fitted, "armadillo leg");
    let (hip, ankle) = (fitted.keys[0].center.y, fitted.keys[fitted.keys.len() - 1].center.y);
    assert!(hip > -12.0 && ankle < -40.0, "key 0 at y = {hip}, the last key at y = {ankle}");
    assert!(fitted.quality.rms_d <= 0.10, "RMS |d| {:.3} of the mean radius", fitted.quality.rms_d);
    // Fig. 3: the rough enclosing sweep, the first cut and the refined fit, each tighter.
    let rms: Vec<f64> = fitted.steps.iter().map(|s| s.quality.rms_d).collect();
    assert!(rms.len() >= 3, "{rms:?}");
    assert!(rms[0] > 2.0 * rms[1], "sections cut: {rms:?}");
    assert!(*rms.last().unwrap() < rms[1], "refinement: {rms:?}");
    assert!(fitted.keys.len() > FitOptions::default().keys, "keys were inserted");
}
