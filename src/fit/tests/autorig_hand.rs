//! `fit::autorig` on a procedural figure whose arms end in hands wider than the arms, with
//! fingers: a ball (the body) with two arms along ±x, each a tube, a round hand and three
//! fingers, and a leg along −y. Each arm is found whole, from the body to its fingertips: the
//! level sets of distance from a fingertip open onto the hand, but narrow again at the wrist,
//! so the limb search passes through the hand (a widening is not the body).

use crate::common::star::{implicit_mesh, smooth_min};

use glam::DVec3;
use sweepffd::fit::autorig::{AutorigOptions, autorig};

use crate::common::autorig_report::print_parts;

/// The distance from `p` to the segment `a`–`b` less `radius`: a capsule's signed distance.
fn capsule(p: DVec3, a: DVec3, b: DVec3, radius: f64) -> f64 {
    let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
    p.distance(a + (b - a) * t) - radius
}

/// The figure's signed distance.
fn figure(p: DVec3) -> f64 {
    let mut d = p.length() - 1.4;
    d = smooth_min(d, capsule(p, DVec3::ZERO, DVec3::new(0.0, -3.2, 0.0), 0.3));
    for side in [1.0, -1.0] {
        let at = |x: f64, y: f64| DVec3::new(side * x, y, 0.0);
        d = smooth_min(d, capsule(p, at(0.0, 0.0), at(2.6, 0.0), 0.25));
        d = smooth_min(d, capsule(p, at(2.9, 0.0), at(3.4, 0.0), 0.55));
        for (y, reach) in [(-0.3, 4.3), (0.0, 4.5), (0.3, 4.3)] {
            d = smooth_min(d, capsule(p, at(3.6, y), at(reach, y), 0.14));
        }
    }
    d
}

#[test]
fn an_arm_ending_in_a_hand_is_found_whole() {
    let mesh = implicit_mesh(&figure, 4.8, 0.06);
    let rigged = autorig(&mesh, &AutorigOptions::default()).unwrap();
    print_parts("figure", &mesh, &rigged);
    let mut keys = Vec::new();
    for side in [1.0, -1.0] {
        let x = |v: u32| side * mesh.positions[v as usize].x;
        let fingertip = (0..mesh.positions.len() as u32).max_by(|&a, &b| x(a).total_cmp(&x(b))).unwrap();
        let arm = rigged.parts.iter().find(|p| p.vertices.binary_search(&fingertip).is_ok());
        let arm = arm.unwrap_or_else(|| panic!("side {side}: no part holds the middle fingertip"));
        // The limb's links, from the body out: the part and any chain it is in.
        let limb = arm.name.split('.').next().unwrap();
        let links: Vec<_> = rigged.parts.iter().filter(|p| p.name.split('.').next() == Some(limb)).collect();
        let nearest = links.iter().flat_map(|p| p.vertices.iter()).map(|&v| x(v)).fold(f64::INFINITY, f64::min);
        eprintln!("side {side}: {limb} ({} links) reaches from x = {nearest:.2}", links.len());
        // The ball's radius is 1.4: the arm reaches from its shoulder, not from its palm (3.4).
        assert!(nearest < 1.8, "side {side}: the limb holding the fingertip starts at x = {nearest}");
        assert!(links.iter().all(|p| p.fit.quality.rms_d <= 0.05), "side {side}: {:?}", arm.fit.quality);
        keys.push(links.iter().map(|p| p.fit.keys.len()).sum::<usize>());
    }
    // Mirror arms are found alike (key insertion may differ by a key).
    assert!(keys[0].abs_diff(keys[1]) <= 1, "{keys:?}");
}
