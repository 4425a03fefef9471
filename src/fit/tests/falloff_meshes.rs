//! Seamless deformation of real connected meshes (the falloff acceptance): parts fitted with
//! `fit`'s defaults stay attached to the rest of the mesh when they are swung from their base
//! or bent from their middle, where the same poses without falloff tear the surface.

use crate::common;

use glam::DVec3;
use sweepffd::bind::{MeshBindings, UNOWNED};
use sweepffd::cpu;
use sweepffd::deform::deform_vertices;
use sweepffd::fit::attached::reversed;
use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::gpu::BindingSource;
use sweepffd::mesh::Mesh;
use sweepffd::rig::{Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Key;
use sweepffd::synthetic::BendTwistTaper;

use common::bends::{largest_stretch, middle_key, turned_keys};

/// The bunny's ear that bends towards −z (as the zipper scan is oriented, y up).
fn bunny_front_ear(p: DVec3) -> bool {
    p.z < -0.012 && p.x < -0.055 && p.y > 0.13
}

/// The bunny's other ear.
fn bunny_back_ear(p: DVec3) -> bool {
    p.x > -0.055 && p.x < 0.0 && p.y > 0.148 && p.z < 0.01
}

/// The armadillo's leg on the −x side, from the hip (y = −8) down, with its foot.
fn armadillo_leg(p: DVec3) -> bool {
    p.x < -5.0 && p.y < -8.0
}

/// Where a fitted sweep's key 0 is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum KeyZero {
    /// At the end where the part is attached, as `fit` places it.
    Attached,
    /// At the other end, as sweeps were fitted before `fit` oriented them.
    Free,
}

/// A rig of one sweep per part, each fitted with `fit`'s defaults but for the falloff.
fn fitted_rig(mesh: &Mesh, parts: &[(&str, Vec<u32>)], falloff: Option<f64>, key_zero: KeyZero) -> Rig {
    let sweeps = parts
        .iter()
        .map(|(name, vertices)| {
            let fitted = fit(mesh, vertices, &FitOptions { falloff, ..FitOptions::default() }).unwrap();
            let keys = match key_zero {
                KeyZero::Attached => fitted.keys.clone(),
                KeyZero::Free => reversed(&fitted.keys),
            };
            RigSweep {
                name: name.to_string(),
                vertices: Some(VertexSelection::Indices(vertices.clone())),
                keys,
                knots: None,
                parent: None,
                falloff: fitted.falloff,
                rotation: Default::default(),
            }
        })
        .collect();
    Rig::new(sweeps).unwrap()
}

/// Every mesh edge once.
/// The two poses of the acceptance, for every sweep at once: key 0 turned by 30° about its
/// local x axis, and the middle key bent by 60° about its widest diameter; both local (the keys
/// after the edited one follow).
fn poses(rig: &Rig) -> Vec<(&'static str, Vec<Vec<Key>>)> {
    vec![("key 0 turned 30°", turned_keys(rig, false, 30.0)), ("middle key bent 60°", turned_keys(rig, true, 60.0))]
}

/// The largest turn of a triangle's normal between rest and pose, over the triangles with a
/// vertex in a band and none that `skip`, degrees.
fn largest_band_normal_turn(mesh: &Mesh, bindings: &MeshBindings, posed: &[DVec3], skip: impl Fn(u32) -> bool) -> f64 {
    let weights = bindings.weights();
    let in_band = |v: u32| weights[v as usize] > 0.0 && weights[v as usize] < 1.0;
    let normal = |p: &[DVec3], [a, b, c]: [u32; 3]| {
        (p[b as usize] - p[a as usize]).cross(p[c as usize] - p[a as usize]).try_normalize()
    };
    mesh.faces
        .triangles()
        .filter(|t| t.iter().any(|&v| in_band(v)) && !t.iter().any(|&v| skip(v)))
        .filter_map(|t| Some(normal(&mesh.positions, t)?.angle_between(normal(posed, t)?).to_degrees()))
        .fold(0.0, f64::max)
}

/// Whether vertex `v` lies in the crease of a bend at the middle key: bound within the two knot
/// intervals beside its sweep's middle key ([`middle_key`], the one turned). A 60° turn of one key bends the sweep within those
/// intervals alone (R(t) interpolates the keys interval by interval), which stretches the outside
/// of a part as wide as an interval is long and folds its inside, whatever happens at its
/// boundary: the sweep's own shape, not a seam.
fn in_crease(rig: &Rig, bindings: &MeshBindings, v: u32) -> bool {
    let binding = bindings.vertices[v as usize];
    if binding.sweep == u32::MAX {
        return false;
    }
    let rest = &rig.rest()[binding.sweep as usize];
    let (knots, middle) = (rest.knots(), middle_key(rest));
    (knots[middle - 1]..=knots[middle + 1]).contains(&binding.params.t)
}

/// The largest edge stretch of each acceptance pose (the crease of the middle-key bend left
/// out, and reported), with the largest normal turn of a band triangle.
fn measure(name: &str, mesh: &Mesh, rig: &Rig) -> Vec<(f64, f64)> {
    let owners = rig.owners(mesh, name).unwrap();
    let bindings = rig.bind_mesh(mesh, &owners, &|_| {});
    let widths: Vec<String> = rig.sweeps().iter().map(|s| format!("{:.4}", s.falloff)).collect();
    let widths = widths.join(" / ");
    let mut measured = Vec::new();
    for (i, (pose, keys)) in poses(rig).into_iter().enumerate() {
        let posed = rig.pose(&keys).unwrap();
        let mut out = vec![DVec3::ZERO; mesh.positions.len()];
        deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut out);
        let crease = |v: u32| i == 1 && in_crease(rig, &bindings, v);
        let (stretch, edge) = largest_stretch(mesh, &out, |(a, b)| !crease(a) && !crease(b));
        let turn = largest_band_normal_turn(mesh, &bindings, &out, crease);
        eprint!("{name}, {pose}, falloff {widths}: largest edge stretch {stretch:.2} at {edge:?}");
        if i == 1 {
            let (inside, _) = largest_stretch(mesh, &out, |(a, b)| crease(a) || crease(b));
            eprint!(" (in the bend's crease {inside:.2})");
        }
        eprintln!(", largest band normal turn {turn:.1}°");
        measured.push((stretch, turn));
    }
    measured
}

/// The acceptance: with the default falloff neither pose stretches an edge past 2 or turns a
/// band triangle past 90°; without falloff the swing tears the seam (> 4), and so does the bend
/// with key 0 at the free end.
fn check_seams(name: &str, mesh: &Mesh, parts: &[(&str, Vec<u32>)]) {
    let seamless = measure(name, mesh, &fitted_rig(mesh, parts, None, KeyZero::Attached));
    for (pose, (stretch, turn)) in ["swing", "bend"].iter().zip(seamless) {
        assert!(stretch <= 2.0, "{name}, {pose}: largest stretch {stretch:.2}");
        assert!(turn <= 90.0, "{name}, {pose}: a band triangle turned {turn:.1}°");
    }
    let hard = measure(name, mesh, &fitted_rig(mesh, parts, Some(0.0), KeyZero::Attached));
    assert!(hard[0].0 > 4.0, "{name}, swing without falloff: {:.2}", hard[0].0);
    let free = measure(name, mesh, &fitted_rig(mesh, parts, Some(0.0), KeyZero::Free));
    assert!(free[1].0 > 4.0, "{name}, bend with key 0 at the free end: {:.2}", free[1].0);
}

#[test]
fn the_bunnys_ears_stay_attached_when_swung_and_bent() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let parts = [
        ("front_ear", largest_connected(&mesh, bunny_front_ear)),
        ("back_ear", largest_connected(&mesh, bunny_back_ear)),
    ];
    check_seams("bunny", &mesh, &parts);
}

#[test]
fn the_armadillos_leg_stays_attached_when_swung_and_bent() {
    let Some(path) = common::shared_mesh("armadillo_50k.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let parts = [("leg", largest_connected(&mesh, armadillo_leg))];
    check_seams("armadillo", &mesh, &parts);
}

/// The GPU, the f32 twin and the f64 reference with falloff on: positions within 1e-5 × the
/// diagonal, the worst vertex reported.
fn gpu_matches_reference(name: &str, mesh: &Mesh, rig: &Rig) {
    let Some(context) = common::gpu() else { return };
    let owners = rig.owners(mesh, name).unwrap();
    let bindings = rig.bind_mesh(mesh, &owners, &|_| {});
    let weights = rig.band_weights(mesh, &owners);
    let keys = BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 }.keys(rig);
    let posed = rig.pose(&keys).unwrap();
    let mut reference = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut reference);
    let source = BindingSource::Bind { owners: &owners, bands: &weights };
    let mut deformer = common::deformer(context, rig.rest(), &mesh.positions, source, Some(&mesh.faces)).unwrap();
    deformer.deform(&posed).unwrap();
    let gpu = deformer.read_positions().unwrap();
    let reference = cpu::packed(&reference);
    let twin = super::twin::twin_positions(rig, mesh, &bindings, &keys);
    let diagonal = mesh.diagonal() as f32;
    for (pair, a, b) in
        [("twin vs f64", &twin, &reference), ("GPU vs twin", &gpu, &twin), ("GPU vs f64", &gpu, &reference)]
    {
        let (error, ulps, at) = common::worst_f32(a, b);
        eprintln!(
            "{name}: {} band vertices; {pair} {:.2e} × diagonal ({error:.2e}), {ulps} ULP, worst vertex {}",
            bindings.bands.len(),
            error / diagonal,
            at / 3
        );
        assert!(error <= 1e-5 * diagonal, "{name}: {pair} {error:e} at vertex {}", at / 3);
    }
}

#[test]
fn gpu_twin_and_reference_agree_with_falloff_on_real_meshes() {
    let (Some(bunny), Some(armadillo), Some(teapot)) = (
        common::shared_mesh("bunny_stanford_zipper.obj"),
        common::shared_mesh("armadillo_50k.obj"),
        common::shared_mesh("teapot_newell_parts.obj"),
    ) else {
        return;
    };
    let mesh = Mesh::load(&bunny).unwrap();
    let ears = [
        ("front_ear", largest_connected(&mesh, bunny_front_ear)),
        ("back_ear", largest_connected(&mesh, bunny_back_ear)),
    ];
    gpu_matches_reference("bunny", &mesh, &fitted_rig(&mesh, &ears, None, KeyZero::Attached));
    let mesh = Mesh::load(&armadillo).unwrap();
    let leg = [("leg", largest_connected(&mesh, armadillo_leg))];
    gpu_matches_reference("armadillo", &mesh, &fitted_rig(&mesh, &leg, None, KeyZero::Attached));
    // The teapot's hierarchy with a falloff on every sweep: its parts are separate patches, so
    // only where they share a vertex is there a band.
    let mesh = Mesh::load(&teapot).unwrap();
    let rig = common::teapot_rig(&mesh);
    let sweeps = rig.sweeps().iter().map(|s| RigSweep { falloff: 0.3, ..s.clone() }).collect();
    gpu_matches_reference("teapot", &mesh, &Rig::new(sweeps).unwrap());
}

/// A part whose selection ends along an unwelded patch seam: the Newell teapot's `body` group
/// (its rim and bottom, other patches, unowned), fitted with the default falloff and bent by
/// 45° at its middle key. Every vertex at one rest position stays with its copies: those on
/// the seams inside the body (one owner) and those on its seams with the rim and the bottom
/// (the body's copy fading to rest there, as the unowned copy stays).
#[test]
fn the_teapots_body_bends_without_opening_its_patch_seams() {
    let Some(path) = common::shared_mesh("teapot_newell_parts.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let body = mesh.group_vertices("body").unwrap();
    let rig = fitted_rig(&mesh, &[("body", body)], None, KeyZero::Attached);
    let owners = rig.owners(&mesh, "teapot").unwrap();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let posed = rig.pose(&turned_keys(&rig, true, 45.0)).unwrap();
    let mut out = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut out);
    let twins = sweepffd::mesh::weld::weld(&mesh.positions);
    let (mut inside, mut across) = (0, 0);
    for (v, &first) in twins.iter().enumerate() {
        let first = first as usize;
        if first == v {
            continue;
        }
        match (owners[v] == owners[first], owners[v] == UNOWNED) {
            (true, false) => inside += 1,
            (false, _) => across += 1,
            (true, true) => {}
        }
        assert_eq!(out[v], out[first], "seam vertices {first} and {v} parted");
    }
    let moved = out.iter().zip(&mesh.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    eprintln!(
        "teapot body: moved up to {moved:.3}; {inside} seam copies inside the body, {across} across its edge kept together"
    );
    assert!(moved > 0.1 && inside > 0 && across > 0, "moved {moved}, {inside} inside, {across} across");
}
