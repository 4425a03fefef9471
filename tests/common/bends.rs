//! Bending every sweep of a rig, and measuring how far the bend stretches the mesh's edges.

use glam::{DQuat, DVec3};
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;

/// The direction, in the plane of `key`, of its widest diameter: bending about it folds the
/// part across its thin side.
pub fn widest_axis(key: &Key) -> DVec3 {
    let m = key.radii.len();
    let diameter = |j: usize| key.radii[j] + key.radii[(j + m / 2) % m];
    let widest = (0..m).max_by(|&a, &b| diameter(a).total_cmp(&diameter(b))).unwrap_or(0);
    let theta = std::f64::consts::TAU * widest as f64 / m as f64;
    key.rotation.normalize() * DVec3::new(theta.cos(), theta.sin(), 0.0)
}

/// The key of `sweep` nearest the middle of its length (its knot nearest ½): where a limb bends
/// midway, whichever end its keys crowd to (a finger taken whole from its fork has most of its
/// keys at its base in the palm).
pub fn middle_key(sweep: &sweepffd::sweep::Sweep) -> usize {
    let knots = sweep.knots();
    (1..knots.len() - 1).min_by(|&a, &b| (knots[a] - 0.5).abs().total_cmp(&(knots[b] - 0.5).abs())).unwrap_or(0)
}

/// Every sweep's key 0 turned by `degrees` about its local x axis (`middle` false), or its
/// middle key ([`middle_key`]) about its widest diameter (`middle` true); local mode, so the
/// keys after the edited one follow.
pub fn turned_keys(rig: &Rig, middle: bool, degrees: f64) -> Vec<Vec<Key>> {
    let mut posing = Posing::new(rig);
    for (sweep, rest) in rig.sweeps().iter().zip(rig.rest()) {
        let key = if middle { middle_key(rest) } else { 0 };
        let axis = if middle { widest_axis(&sweep.keys[key]) } else { sweep.keys[key].rotation.normalize() * DVec3::X };
        posing
            .apply(&Edit::MoveKey {
                sweep: sweep.name.clone(),
                key,
                translate: [0.0; 3],
                rotate: DQuat::from_axis_angle(axis, degrees.to_radians()).to_array(),
                mode: KeyMode::Local,
            })
            .unwrap();
    }
    posing.keys().to_vec()
}

/// The mesh's edges, each once, (low, high).
pub fn edges(mesh: &Mesh) -> Vec<(u32, u32)> {
    let mut edges: Vec<(u32, u32)> = mesh
        .faces
        .triangles()
        .flat_map(|[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// The largest deformed / rest length over the edges of the mesh that `counts`, and its edge.
pub fn largest_stretch(mesh: &Mesh, posed: &[DVec3], counts: impl Fn((u32, u32)) -> bool) -> (f64, (u32, u32)) {
    let rest = &mesh.positions;
    edges(mesh)
        .into_iter()
        .filter(|&(a, b)| rest[a as usize] != rest[b as usize] && counts((a, b)))
        .map(|(a, b)| {
            let (i, j) = (a as usize, b as usize);
            (posed[i].distance(posed[j]) / rest[i].distance(rest[j]), (a, b))
        })
        .fold((0.0, (0, 0)), |best, next| if next.0 > best.0 { next } else { best })
}

/// The largest and the smallest deformed / rest edge length over the whole mesh.
pub fn stretch_range(mesh: &Mesh, posed: &[DVec3]) -> (f64, f64) {
    let rest = &mesh.positions;
    edges(mesh)
        .into_iter()
        .filter(|&(a, b)| rest[a as usize] != rest[b as usize])
        .map(|(a, b)| posed[a as usize].distance(posed[b as usize]) / rest[a as usize].distance(rest[b as usize]))
        .fold((0.0, f64::INFINITY), |(hi, lo), s| (hi.max(s), lo.min(s)))
}

/// The axis to bend sweep `sweep` of `rig` about over the span of width `span` centred on `t`, in
/// the frame of the cross-section at t, and the sweep's reach w across it: the direction φ in
/// the sections' plane across which the sweep is thinnest over the span (the least, over φ, of
/// the largest distance r(θ, t)·|sin(θ − φ)| of its surface from the line through the center
/// along φ), as a knee bends across a leg's thin side.
pub fn thinnest_axis(rig: &Rig, sweep: usize, t: f64, span: f64) -> (DVec3, f64) {
    let rest = &rig.rest()[sweep];
    let reach = |phi: f64| {
        let mut largest: f64 = 0.0;
        for i in 0..=20 {
            let at = (t + span * (i as f64 / 20.0 - 0.5)).clamp(0.0, 1.0);
            for j in 0..64 {
                let theta = std::f64::consts::TAU * j as f64 / 64.0;
                largest = largest.max(rest.radius(theta, at) * (theta - phi).sin().abs());
            }
        }
        largest
    };
    let phi = (0..180)
        .map(|k| std::f64::consts::PI * k as f64 / 180.0)
        .min_by(|&a, &b| reach(a).total_cmp(&reach(b)))
        .unwrap_or(0.0);
    (DVec3::new(phi.cos(), phi.sin(), 0.0), reach(phi))
}

/// The largest change, in degrees, of the dihedral angle across any edge that two triangles
/// share, between the rest mesh and `posed`: a crease the deformation makes shows as a large
/// change on the edges along it, a smooth bend as small changes spread over many edges.
pub fn largest_crease(mesh: &Mesh, posed: &[DVec3]) -> f64 {
    use std::collections::HashMap;
    let triangles: Vec<[u32; 3]> = mesh.faces.triangles().collect();
    let mut sides: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (f, &[a, b, c]) in triangles.iter().enumerate() {
        for (x, y) in [(a, b), (b, c), (c, a)] {
            sides.entry((x.min(y), x.max(y))).or_default().push(f);
        }
    }
    let normal = |points: &[DVec3], f: usize| {
        let [a, b, c] = triangles[f].map(|i| points[i as usize]);
        (b - a).cross(c - a).normalize_or_zero()
    };
    let angle = |p: DVec3, q: DVec3| p.cross(q).length().atan2(p.dot(q)).to_degrees();
    sides
        .values()
        .filter(|faces| faces.len() == 2)
        .map(|faces| {
            let rest = angle(normal(&mesh.positions, faces[0]), normal(&mesh.positions, faces[1]));
            let moved = angle(normal(posed, faces[0]), normal(posed, faces[1]));
            (moved - rest).abs()
        })
        .fold(0.0, f64::max)
}
