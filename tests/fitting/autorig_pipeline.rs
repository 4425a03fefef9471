//! The whole pipeline on real meshes and the procedural star: `autorig` with the default
//! falloff, a pose bending every part by 45° at its middle key (the one nearest the middle of
//! its length), then the CPU reference deformation. Every part moves, nothing tears (largest
//! edge stretch ≤ 2 outside the bends' creases, whose stretch is the sweep's own and is
//! printed), and the body's unowned vertices stay exactly put; vertices at one rest position
//! (an unwelded seam's copies) stay together.
//!
//! With `SWEEPFFD_PICTURES_DIR=DIR`, each mesh, its rig and the bent pose are written there
//! for `sweepffd render --mesh DIR/NAME.obj --rig DIR/NAME-rig.json --pose DIR/NAME-pose.json`.

use crate::common;
use crate::common::star;

use std::path::PathBuf;

use glam::DVec3;
use sweepffd::deform::deform_vertices;
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::mesh::weld::weld;
use sweepffd::rig::Rig;

use common::bends::{largest_stretch, middle_key, turned_keys};

/// Rigs `mesh`, bends every part by 45° at its middle key and checks the deformation; returns
/// the largest edge stretch.
fn bend_every_part(name: &str, mesh: &Mesh, expected_parts: usize) -> f64 {
    let rigged = autorig(mesh, &AutorigOptions::default()).unwrap();
    assert!(rigged.parts.len() >= expected_parts, "{name}: {} parts", rigged.parts.len());
    let document = rigged.document();
    let rig = Rig::from_document(&document, None).unwrap();
    let owners = rig.owners(mesh, name).unwrap();
    let bindings = rig.bind_mesh(mesh, &owners, &|_| {});
    let keys = turned_keys(&rig, true, 45.0);
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
    // wide as an interval is long: the sweep's own crease, reported apart from the seams. An
    // edge is in it where the range of its ends' t on one sweep meets those intervals (a long
    // edge of a coarse ear may bind on both sides of them), or one end's t does where only
    // that end binds to the sweep. A vertex in a band between two sweeps binds to both, so a
    // child's crease reaches into its parent's vertices there (a finger taken whole from its
    // fork bends at a middle key inside the palm).
    let mut second: Vec<Option<sweepffd::bind::Binding>> = vec![None; mesh.positions.len()];
    for band in &bindings.bands {
        second[band.vertex as usize] = Some(band.second);
    }
    let bound_to = |v: u32| -> Vec<(u32, f64)> {
        let first = bindings.vertices[v as usize];
        [Some(first), second[v as usize]]
            .into_iter()
            .flatten()
            .filter(|binding| binding.sweep != u32::MAX)
            .map(|binding| (binding.sweep, binding.params.t))
            .collect()
    };
    let crease = |(a, b): (u32, u32)| {
        let in_crease = |sweep: u32, lo: f64, hi: f64| {
            let rest = &rig.rest()[sweep as usize];
            let (knots, middle) = (rest.knots(), middle_key(rest));
            lo <= knots[middle + 1] && hi >= knots[middle - 1]
        };
        let ends: Vec<(u32, f64)> = bound_to(a).into_iter().chain(bound_to(b)).collect();
        ends.iter().any(|&(sweep, _)| {
            let on_it = ends.iter().filter(|&&(other, _)| other == sweep).map(|&(_, t)| t);
            let (lo, hi) = on_it.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| (lo.min(t), hi.max(t)));
            in_crease(sweep, lo, hi)
        })
    };
    // Vertices at one rest position (an unwelded patch seam's two copies, which no edge joins)
    // stay together.
    let twins = weld(&mesh.positions);
    let mut seams = 0;
    for (v, &first) in twins.iter().enumerate() {
        if first as usize != v {
            seams += 1;
            assert_eq!(out[v], out[first as usize], "{name}: seam vertices {first} and {v} parted");
        }
    }
    let (stretch, _) = largest_stretch(mesh, &out, |edge| !crease(edge));
    let (in_crease, _) = largest_stretch(mesh, &out, crease);
    eprintln!(
        "{name}: {} parts bent 45° at the middle key; largest edge stretch {stretch:.3} outside the bends' creases \
         ({in_crease:.3} in them); {} unowned body vertices kept; {seams} seam vertices kept with their twins",
        rigged.parts.len(),
        body.len()
    );
    if let Ok(dir) = std::env::var("SWEEPFFD_PICTURES_DIR") {
        let dir = PathBuf::from(dir);
        // A shared mesh in a folder is written beside the others.
        let name = name.replace('/', "-");
        LoadedMesh::from(mesh.clone()).save(&dir.join(format!("{name}.obj")), &mesh.positions).unwrap();
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

/// The shared meshes no fitting constant was chosen on: spot (coarse legs), the chair, the
/// Newell teapot (unwelded patch seams: a seam's two copies of a vertex must move together),
/// the McGuire teapot (welded, hollow), the dino, the blocky man (limbs that are boxes of their
/// own) and wuson (a leg that is a chain of two sweeps, the hoof a child of the leg, both
/// bent); and the faerie, on which the coarse rims' rules were chosen (legs cut at the crotch,
/// their rims squared off; arms whose shoulders' rims are evened, each ending in its hand),
/// each with what autorig finds on it.
#[test]
fn meshes_no_constant_was_tuned_on_bend_without_tearing() {
    for (file, expected_parts) in [
        ("spot_triangulated.obj", 4),
        ("chair.off", 4),
        ("teapot_newell.obj", 3),
        ("teapot_mcguire/teapot.obj", 1),
        ("dino.off", 3),
        ("characters/blocky_man.obj", 5),
        ("characters/wuson.obj", 5),
        ("characters/faerie.obj", 7),
    ] {
        let Some(path) = common::shared_mesh(file) else { return };
        let stretch = bend_every_part(file, &Mesh::load(&path).unwrap(), expected_parts);
        assert!(stretch <= 2.0, "{file}: largest edge stretch {stretch:.3}");
    }
}

/// Bends every part of the kept test mesh `file` (`tests/meshes`), rigged into at least
/// `expected_parts` parts, and checks its largest edge stretch outside the bends.
fn kept_mesh_bends(file: &str, expected_parts: usize) {
    let name = file.trim_end_matches(".obj");
    let stretch = bend_every_part(name, &common::kept_mesh(file), expected_parts);
    assert!(stretch <= 2.0, "{name}: largest edge stretch {stretch:.3}");
}

/// Sydney (`tests/meshes/sydney.obj`, a public low-poly game character of one component, kept
/// with the tests): her legs cut at her fork, her arms as chains (the raised one with its hand
/// a branch of its upper arm and forearm), her braid and her head, every link bent.
#[test]
fn sydney_bends_every_chain_without_tearing() {
    kept_mesh_bends("sydney.obj", 9);
}

/// BCN_Epileptic (`tests/meshes/bcn_epileptic.obj`, a public game character of three meshes,
/// kept with the tests): both legs, both arms with their fingers, the head with its neck (its
/// eyes and teeth with it) and the ponytail, every sweep bent.
#[test]
fn the_game_man_bends_every_chain_without_tearing() {
    kept_mesh_bends("bcn_epileptic.obj", 16);
}

/// Mr. Fixit (`tests/meshes/mrfixit.obj`, a public T-posed game character of one surface, kept
/// with the tests): both legs, both arms as chains with their thumbs and fingers, the head,
/// every sweep bent.
#[test]
fn mr_fixit_bends_every_chain_without_tearing() {
    kept_mesh_bends("mrfixit.obj", 13);
}
