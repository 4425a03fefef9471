//! The whole pipeline on real meshes and the procedural star: `autorig` with the default
//! falloff, a pose bending every part by 45° at its middle key, then the CPU reference
//! deformation. Every part moves, nothing tears (largest edge stretch ≤ 2 outside the bends'
//! creases, whose stretch is the sweep's own and is printed), and the body's unowned vertices
//! stay exactly put.
//!
//! With `SWEEPFFD_PICTURES_DIR=DIR`, each mesh, its rig and the bent pose are written there
//! for `sweepffd render --mesh DIR/NAME.obj --rig DIR/NAME-rig.json --pose DIR/NAME-pose.json`.

mod common;
#[path = "common/star.rs"]
mod star;

use std::path::PathBuf;

use glam::{DQuat, DVec3};
use sweepffd::deform::deform_vertices;
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;

/// The direction, in the plane of `key`, of its widest diameter: bending about it folds the
/// part across its thin side.
fn widest_axis(key: &Key) -> DVec3 {
    let m = key.radii.len();
    let diameter = |j: usize| key.radii[j] + key.radii[(j + m / 2) % m];
    let widest = (0..m).max_by(|&a, &b| diameter(a).total_cmp(&diameter(b))).unwrap_or(0);
    let theta = std::f64::consts::TAU * widest as f64 / m as f64;
    key.rotation.normalize() * DVec3::new(theta.cos(), theta.sin(), 0.0)
}

/// Every sweep's middle key turned by `degrees` about its widest diameter, the keys after it
/// following (local mode).
fn bent(rig: &Rig, degrees: f64) -> Vec<Vec<Key>> {
    let mut posing = Posing::new(rig);
    for sweep in rig.sweeps() {
        let key = sweep.keys.len() / 2;
        let axis = widest_axis(&sweep.keys[key]);
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

/// The largest deformed / rest length over the mesh's edges of nonzero rest length that
/// `counts`.
fn largest_stretch(mesh: &Mesh, posed: &[DVec3], counts: impl Fn(u32, u32) -> bool) -> f64 {
    let rest = &mesh.positions;
    mesh.faces
        .triangles()
        .flat_map(|[a, b, c]| [(a, b), (b, c), (c, a)])
        .filter(|&(a, b)| rest[a as usize] != rest[b as usize] && counts(a, b))
        .map(|(a, b)| posed[a as usize].distance(posed[b as usize]) / rest[a as usize].distance(rest[b as usize]))
        .fold(0.0, f64::max)
}

/// Rigs `mesh`, bends every part by 45° at its middle key and checks the deformation; returns
/// the largest edge stretch.
fn bend_every_part(name: &str, mesh: &Mesh, expected_parts: usize) -> f64 {
    let rigged = autorig(mesh, &AutorigOptions::default()).unwrap();
    assert!(rigged.parts.len() >= expected_parts, "{name}: {} parts", rigged.parts.len());
    let document = rigged.document();
    let rig = Rig::from_document(&document, None).unwrap();
    let owners = rig.owners(mesh, name).unwrap();
    let bindings = rig.bind_mesh(mesh, &owners, &|_| {});
    let keys = bent(&rig, 45.0);
    let posed = rig.pose(&keys).unwrap();
    let mut out = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut out);
    // Every part moves: some vertex of each by at least 5% of the part's length.
    for part in &rigged.parts {
        let length: f64 = part.fit.keys.windows(2).map(|w| w[0].center.distance(w[1].center)).sum();
        let moved =
            part.vertices.iter().map(|&v| out[v as usize].distance(mesh.positions[v as usize])).fold(0.0, f64::max);
        eprintln!("{name} {}: moved up to {:.1}% of its length", part.name, 100.0 * moved / length);
        assert!(moved >= 0.05 * length, "{name} {}: moved only {moved} of {length}", part.name);
    }
    // The body's unowned vertices outside every band stay exactly put.
    let mut in_band = vec![false; mesh.positions.len()];
    for band in &bindings.bands {
        in_band[band.vertex as usize] = true;
    }
    let body: Vec<usize> =
        (0..mesh.positions.len()).filter(|&v| bindings.vertices[v].sweep == u32::MAX && !in_band[v]).collect();
    assert!(!body.is_empty(), "{name}: the body is unowned");
    let strayed = body.iter().filter(|&&v| out[v] != mesh.positions[v]).count();
    assert_eq!(strayed, 0, "{name}: {strayed} of the body's {} unowned vertices moved", body.len());
    // A 45° turn of one key bends the sweep within the two knot intervals beside it (R(t)
    // interpolates the keys interval by interval), which stretches the outside of a part as
    // wide as an interval is long: the sweep's own crease, reported apart from the seams.
    let crease = |v: u32| {
        let binding = bindings.vertices[v as usize];
        binding.sweep != u32::MAX && {
            let knots = rig.rest()[binding.sweep as usize].knots();
            let middle = knots.len() / 2;
            (knots[middle - 1]..=knots[middle + 1]).contains(&binding.params.t)
        }
    };
    let stretch = largest_stretch(mesh, &out, |a, b| !crease(a) && !crease(b));
    let in_crease = largest_stretch(mesh, &out, |a, b| crease(a) || crease(b));
    eprintln!(
        "{name}: {} parts bent 45° at the middle key; largest edge stretch {stretch:.3} outside the bends' creases \
         ({in_crease:.3} in them); {} unowned body vertices kept",
        rigged.parts.len(),
        body.len()
    );
    if let Ok(dir) = std::env::var("SWEEPFFD_PICTURES_DIR") {
        let dir = PathBuf::from(dir);
        mesh.save(&dir.join(format!("{name}.obj")), &mesh.positions).unwrap();
        std::fs::write(dir.join(format!("{name}-rig.json")), document.to_json()).unwrap();
        std::fs::write(dir.join(format!("{name}-pose.json")), rig.pose_document(&keys).to_json()).unwrap();
    }
    stretch
}

#[test]
fn the_star_bends_every_tube_without_tearing() {
    let stretch = bend_every_part("star", &star::star_mesh(0.06), 5);
    assert!(stretch <= 2.0, "star: largest edge stretch {stretch:.3}");
}

#[test]
fn the_bunny_bends_both_ears_without_tearing() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let stretch = bend_every_part("bunny", &Mesh::load(&path).unwrap(), 2);
    assert!(stretch <= 2.0, "bunny: largest edge stretch {stretch:.3}");
}

#[test]
fn the_armadillo_bends_every_limb_without_tearing() {
    let Some(path) = common::shared_mesh("armadillo_50k.obj") else { return };
    let stretch = bend_every_part("armadillo", &Mesh::load(&path).unwrap(), 5);
    assert!(stretch <= 2.0, "armadillo: largest edge stretch {stretch:.3}");
}
