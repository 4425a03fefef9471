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

/// Every sweep's key 0 turned by `degrees` about its local x axis (`middle` false), or its
/// middle key about its widest diameter (`middle` true); local mode, so the keys after the
/// edited one follow.
pub fn turned_keys(rig: &Rig, middle: bool, degrees: f64) -> Vec<Vec<Key>> {
    let mut posing = Posing::new(rig);
    for sweep in rig.sweeps() {
        let key = if middle { sweep.keys.len() / 2 } else { 0 };
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
