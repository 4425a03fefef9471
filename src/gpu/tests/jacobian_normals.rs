//! Jacobian normals (`DeformerDescriptor::with_jacobian_normals`): the fused deform kernel
//! against its CPU twin and the f64 reference, its positions against the plain deform kernel's,
//! and its normals against the normals of the deformed triangles, on real meshes under the
//! bend-twist-taper pose of the equivalence tests, with falloff bands and with instances.
//!
//! Without a GPU adapter these tests print a notice and pass; `SWEEPFFD_REQUIRE_GPU=1` (set by
//! CI, which installs Mesa's lavapipe) makes a missing adapter fail them.

use crate::common;

use common::normal_angles::{angle, at};
use glam::{DVec3, Vec4};
use sweepffd::bind::SweepBinder;
use sweepffd::coeffs::{BAND_FLAG, GpuBinding, SweepCoefficients, UNOWNED};
use sweepffd::cpu;
use sweepffd::deform::deform_vertex;
use sweepffd::deform::jacobian::{deformed_normal, is_beyond_end, normal_coordinates};
use sweepffd::deform::jacobian_normal_vertices;
use sweepffd::fit::{FitOptions, fit, largest_connected};
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, rest_positions};
use sweepffd::mesh::Mesh;
use sweepffd::normals::{NormalAdjacency, jacobian_reach, vertex_normals};
use sweepffd::rig::{Rig, RigSweep, VertexSelection};
use sweepffd::sweep::RotationInterpolation;
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

const POSE: BendTwistTaper = BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 };
/// GPU vs twin and twin vs f64, radians.
const NORMAL_TOLERANCE: f64 = 1e-3;
/// The 99th percentile of the angle between the output normals (Jacobian normals, and
/// triangle normals where the Jacobian misses the probed facets) and the triangle normals over
/// every vertex whose one-ring one sweep moves whole, degrees.
const P99_TARGET_DEG: f64 = 2.0;

/// The worst angle over `vertices` and its vertex.
fn worst(vertices: &[usize], a: impl Fn(usize) -> DVec3, b: impl Fn(usize) -> DVec3) -> (f64, usize) {
    vertices.iter().map(|&i| (angle(a(i), b(i)), i)).fold((0.0, 0), |w, x| if x.0 > w.0 { x } else { w })
}

/// The `q`-quantile of `values`.
fn quantile(mut values: Vec<f64>, q: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(((values.len() as f64 - 1.0) * q).round() as usize).copied().unwrap_or(0.0)
}

/// A deformer of `mesh` bound to `rig` with triangle normals, through the Jacobian or not.
fn deformer(context: &GpuContext, mesh: &Mesh, rig: &Rig, owners: &[u32], jacobian: bool) -> GpuDeformer {
    let positions = rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let bands = rig.band_weights(mesh, owners);
    let source = BindingSource::Bind { owners, bands: &bands };
    let mut descriptor = DeformerDescriptor::new(rig.rest(), &positions, source).with_triangles(&triangles);
    if jacobian {
        descriptor = descriptor.with_jacobian_normals();
    }
    GpuDeformer::new(context, &descriptor).unwrap()
}

/// The comparisons on one mesh and rig; returns the 99th percentile of the angle between the
/// Jacobian normals alone and the triangle normals over every vertex of the Jacobian reach (one
/// sweep moving its one-ring whole), degrees.
fn check(name: &str, mesh: &Mesh, rig: &Rig, pose: &BendTwistTaper, target: Target) -> Option<f64> {
    let context = common::gpu()?;
    let owners = rig.owners(mesh, name).unwrap();
    let diagonal = mesh.diagonal();
    let posed = rig.pose(&pose.keys(rig)).unwrap();
    let mut faced = deformer(context, mesh, rig, &owners, false);
    let mut fused = deformer(context, mesh, rig, &owners, true);
    faced.deform(&posed).unwrap();
    fused.deform(&posed).unwrap();

    // Positions: the fused kernel's equal the plain kernel's.
    let (positions, faced_positions) = (fused.read_positions().unwrap(), faced.read_positions().unwrap());
    let (error, ulps, worst_at) = common::worst_f32(&positions, &faced_positions);
    println!("{name}: fused vs plain positions, max |Δ| {error:.2e} ({ulps} ULP) at vertex {}", worst_at / 3);
    assert!(error as f64 <= 1e-6 * diagonal, "{name}: fused positions off by {error:e}");

    // Which normals the deform kernel writes: those of the vertices whose one-ring one sweep
    // moves whole and whose Jacobian normals match their facets under the probe pose.
    let bindings = fused.read_bindings().unwrap();
    let mut coefficients = SweepCoefficients::new(rig.rest());
    let influence: Vec<u32> = bindings
        .iter()
        .map(|b| if b.cell < BAND_FLAG { coefficients.sweep_of_cell(b.cell) } else { UNOWNED })
        .collect();
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let reach = jacobian_reach(&triangles, &influence);
    let adjacency = NormalAdjacency::new(&mesh.faces, mesh.positions.len());
    let rest = rest_positions(&mesh.positions);
    let twin_written = jacobian_normal_vertices(rig.rest(), &rest, &adjacency, &triangles, &influence);
    let in_reach: Vec<usize> = (0..bindings.len()).filter(|&i| reach[i]).collect();
    // The deformer probed on the GPU, in f32: it decides as its f64 twin, but for vertices whose
    // angle lies at the tolerance's edge.
    let written = fused.jacobian_normal_vertices().expect("built with Jacobian normals").to_vec();
    let disagree: Vec<usize> = (0..written.len()).filter(|&i| written[i] != twin_written[i]).collect();
    println!(
        "{name}: probe, GPU vs f64 twin disagree on {} of {} vertices in reach {:?}",
        disagree.len(),
        in_reach.len(),
        &disagree[..disagree.len().min(8)]
    );
    assert!(disagree.iter().all(|&i| reach[i]), "{name}: the GPU probe decided a vertex outside the reach");
    assert!(
        disagree.len() as f64 <= 1e-3 * in_reach.len() as f64 + 2.0,
        "{name}: the GPU probe disagrees with its twin on {} of {} vertices",
        disagree.len(),
        in_reach.len()
    );
    let by_deform: Vec<usize> = (0..bindings.len()).filter(|&i| written[i]).collect();
    let by_faces: Vec<usize> = (0..bindings.len()).filter(|&i| !written[i]).collect();
    let normals = fused.read_normals().unwrap().unwrap();
    let faced_normals = faced.read_normals().unwrap().unwrap();

    // The twin, from the GPU's bindings and the twin's rest normals.
    let rest_f32 = cpu::packed(&mesh.positions);
    let mut rest_normals = vec![0.0; rest_f32.len()];
    cpu::normals::normals(&rest_f32, &adjacency, &mut rest_normals);
    let records = cpu::jacobian::coordinates(&coefficients.cells, &bindings, &rest_normals);
    coefficients.update(&posed).unwrap();
    let (mut twin_positions, mut twin_normals) = (rest_f32.clone(), rest_normals.clone());
    cpu::deform::deform_with_normals(&coefficients.cells, &bindings, &records, &mut twin_positions, &mut twin_normals);
    let moved =
        |values: &[f32]| -> Vec<f32> { by_deform.iter().flat_map(|&i| at(values, i).as_vec3().to_array()).collect() };
    let (error, ulps, worst_at) = common::worst_f32(&moved(&positions), &moved(&twin_positions));
    let worst_at = by_deform.get(worst_at / 3).copied().unwrap_or(0);
    println!("{name}: fused positions vs twin, max |Δ| {error:.2e} ({ulps} ULP) at vertex {worst_at}");
    assert!(error as f64 <= 1e-5 * diagonal, "{name}: fused positions off the twin's by {error:e}");
    let (gpu_twin, worst_at) = worst(&by_deform, |i| at(&normals, i), |i| at(&twin_normals, i));
    println!("{name}: Jacobian normals, GPU vs twin worst angle {gpu_twin:.2e} rad at vertex {worst_at}");
    assert!(gpu_twin <= NORMAL_TOLERANCE, "{name}: GPU off the twin by {gpu_twin} rad at vertex {worst_at}");

    // The f64 reference, from its own bindings and rest normals.
    let reference = rig.bind_mesh(mesh, &owners, &|_| {});
    let rest_normals64 = vertex_normals(&mesh.positions, &adjacency);
    let reference_normal = |i: usize| {
        let b = &reference.vertices[i];
        let rest = &rig.rest()[b.sweep as usize];
        let coordinates = normal_coordinates(rest, &b.params, rest_normals64[i]);
        deformed_normal(&posed[b.sweep as usize], &b.params, &coordinates)
    };
    let twin_f64: Vec<f64> = by_deform.iter().map(|&i| angle(at(&twin_normals, i), reference_normal(i))).collect();
    let (p999, max) = (quantile(twin_f64.clone(), 0.999), quantile(twin_f64, 1.0));
    println!("{name}: Jacobian normals, twin vs f64: 99.9th percentile {p999:.2e} rad, max {max:.2e} rad");
    assert!(p999 <= NORMAL_TOLERANCE, "{name}: twin off the f64 reference by {p999} rad (99.9th percentile)");

    // Against the triangle normals: the band vertices and the unbound ones keep them to the bit.
    let (kept, worst_at) = worst(&by_faces, |i| at(&normals, i), |i| at(&faced_normals, i));
    assert_eq!(kept, 0.0, "{name}: vertex {worst_at} outside the Jacobian's reach changed its normal");
    // Over the whole reach: the output normals, and the Jacobian normals alone (the twin's,
    // which it writes for every bound vertex).
    let against_faces = |values: &[f32]| -> (f64, f64, f64) {
        let degrees: Vec<f64> =
            in_reach.iter().map(|&i| angle(at(values, i), at(&faced_normals, i)).to_degrees()).collect();
        let mean = degrees.iter().sum::<f64>() / degrees.len().max(1) as f64;
        (mean, quantile(degrees.clone(), 0.99), quantile(degrees, 1.0))
    };
    let (mean, p99, max) = against_faces(&normals);
    let (jacobian_mean, jacobian_p99, jacobian_max) = against_faces(&twin_normals);
    let fallback = 1.0 - by_deform.len() as f64 / in_reach.len().max(1) as f64;
    println!(
        "{name}: output vs triangle normals over the {} vertices of the reach: mean {mean:.3}°, 99th \
         percentile {p99:.3}°, max {max:.2}°; {:.1}% left to the triangles (Jacobian alone: mean \
         {jacobian_mean:.3}°, 99th percentile {jacobian_p99:.3}°, max {jacobian_max:.2}°)",
        in_reach.len(),
        100.0 * fallback
    );
    let degrees: Vec<f64> =
        by_deform.iter().map(|&i| angle(at(&normals, i), at(&faced_normals, i)).to_degrees()).collect();
    let mean = degrees.iter().sum::<f64>() / degrees.len().max(1) as f64;
    // Turning each rest normal with its cross-section's frame alone misses the stretch.
    let framed: Vec<f64> = by_deform
        .iter()
        .map(|&i| {
            let b = &reference.vertices[i];
            let t = b.params.t;
            let sweep = b.sweep as usize;
            let n = posed[sweep].orientation(t) * (rig.rest()[sweep].orientation(t).inverse() * rest_normals64[i]);
            angle(n, at(&faced_normals, i)).to_degrees()
        })
        .collect();
    let framed_mean = framed.iter().sum::<f64>() / framed.len().max(1) as f64;
    let framed_p99 = quantile(framed, 0.99);
    println!(
        "{name}: Jacobian vs triangle normals over the {} vertices it writes: mean {mean:.3}° (frame \
         rotation alone: mean {framed_mean:.3}°, 99th percentile {framed_p99:.2}°)",
        by_deform.len()
    );
    match target {
        Target::Facets(limit) => {
            assert!(p99 <= limit, "{name}: 99th percentile {p99}° over {limit}°");
            assert!(mean < framed_mean, "{name}: the Jacobian does no better than the frame");
        }
        Target::Deformation => {
            // Where the two disagree most, the deformed facets are what is off: the Jacobian
            // normal is the normal of the deformation itself, to finite differences of
            // binding and Eq. 2 over a step far below the facets' size.
            let mut order: Vec<(f64, usize)> =
                by_deform.iter().map(|&i| (angle(at(&normals, i), at(&faced_normals, i)), i)).collect();
            order.sort_by(|a, b| b.0.total_cmp(&a.0));
            for &(disagreement, i) in order.iter().take(20) {
                let b = &reference.vertices[i];
                let sweep = b.sweep as usize;
                let binder = SweepBinder::new(&rig.rest()[sweep]);
                let f = |y: DVec3| deform_vertex(&posed[sweep], &binder.bind(y));
                let n = rest_normals64[i];
                let (u, e, x) = (n.any_orthonormal_vector(), 1e-6 * diagonal, mesh.positions[i]);
                let v = n.cross(u);
                // Differences across the end plane of a sweep straddle its kink: not a test.
                let corners = [x + e * u, x - e * u, x + e * v, x - e * v];
                if corners.iter().any(|&y| is_beyond_end(&binder.bind(y)) != is_beyond_end(&b.params)) {
                    continue;
                }
                let fd = (f(x + e * u) - f(x - e * u)).cross(f(x + e * v) - f(x - e * v));
                let off = angle(reference_normal(i), fd);
                assert!(off < 1e-4, "{name}: vertex {i} off the deformation's normal by {off} rad");
                assert!(disagreement > off);
            }
        }
    }
    Some(jacobian_p99)
}

/// What the Jacobian normals are held to against the triangle normals.
#[derive(Clone, Copy)]
enum Target {
    /// The 99th percentile of the angle at most this many degrees: parts fitted to their
    /// sweeps, bent as an animator would.
    Facets(f64),
    /// The worst vertices are the deformation's own normals (finite differences), wherever the
    /// deformed facets go: a whole mesh on one axis sweep, folded through its axis by the
    /// equivalence tests' extreme pose.
    Deformation,
}

/// A moderate pose: each part bent by about 45°, twisted a little and tapered.
const BEND: BendTwistTaper = BendTwistTaper { bend: 0.8, twist: 0.3, taper: 0.9 };

/// A rig of one fitted sweep per part, each owning its vertices, with the fit's falloff.
/// A named part: which vertices make it up, by position.
type Part = (&'static str, fn(DVec3) -> bool);

fn fitted_rig(mesh: &Mesh, parts: &[Part], falloff: Option<f64>) -> Rig {
    let sweeps = parts
        .iter()
        .map(|&(name, inside)| {
            let vertices = largest_connected(mesh, inside);
            let fitted = fit(mesh, &vertices, &FitOptions::default()).unwrap();
            RigSweep {
                name: name.to_string(),
                vertices: Some(VertexSelection::Indices(vertices)),
                keys: fitted.keys,
                knots: None,
                parent: None,
                falloff: falloff.unwrap_or(fitted.falloff),
                rotation: Default::default(),
            }
        })
        .collect();
    Rig::new(sweeps).unwrap()
}

fn load(file: &str) -> Option<Mesh> {
    common::shared_mesh(file).map(|path| Mesh::load(&path).unwrap())
}

fn check_whole(file: &str) {
    let Some(mesh) = load(file) else { return };
    check(file, &mesh, &common::axis_rig(&mesh, 9, 16), &POSE, Target::Deformation);
}

#[test]
fn bunny_ears_jacobian_normals() {
    let Some(mesh) = load("bunny_stanford_zipper.obj") else { return };
    let rig = fitted_rig(
        &mesh,
        &[
            ("front_ear", |p| p.z < -0.012 && p.x < -0.055 && p.y > 0.13),
            ("back_ear", |p| p.x > -0.055 && p.x < 0.0 && p.y > 0.148 && p.z < 0.01),
        ],
        None,
    );
    let Some(jacobian) = check("bunny ears", &mesh, &rig, &BEND, Target::Facets(P99_TARGET_DEG)) else { return };
    // The ears' thin sheets: the Jacobian normals alone miss the facets (4.8°).
    assert!(jacobian > P99_TARGET_DEG, "bunny ears: the Jacobian alone meets the target ({jacobian}°)");
}

#[test]
fn armadillo_leg_jacobian_normals() {
    let Some(mesh) = load("armadillo_50k.obj") else { return };
    let leg: [Part; 1] = [("leg", |p| p.x < -5.0 && p.y < -8.0 && p.y > -44.0)];
    // With the fit's falloff nearly all the leg is in its bands; without, all but its rims.
    check("armadillo leg", &mesh, &fitted_rig(&mesh, &leg, None), &BEND, Target::Facets(P99_TARGET_DEG));
    // Without: the leg's bumps bend within their one-rings (13.5° at the 99th percentile
    // through the Jacobian alone, 1.1° with the rings the probe finds too coarse left to the
    // triangles).
    check("armadillo leg, hard", &mesh, &fitted_rig(&mesh, &leg, Some(0.0)), &BEND, Target::Deformation);
}

#[test]
fn teapot_parts_jacobian_normals() {
    let Some(mesh) = load("teapot_newell_parts.obj") else { return };
    let Some(jacobian) = check("teapot", &mesh, &common::teapot_rig(&mesh), &BEND, Target::Facets(P99_TARGET_DEG))
    else {
        return;
    };
    // The coarse spout and handle, and the rings across the parts' end planes: the Jacobian
    // normals alone miss the facets (4.7°).
    assert!(jacobian > P99_TARGET_DEG, "teapot: the Jacobian alone meets the target ({jacobian}°)");
}

#[test]
fn whole_bunny_jacobian_normals() {
    check_whole("bunny_stanford_zipper.obj");
}

#[test]
fn whole_teapot_jacobian_normals() {
    check_whole("teapot_newell.obj");
}

#[test]
fn whole_armadillo_jacobian_normals() {
    check_whole("armadillo_50k.obj");
}

#[test]
fn tube_jacobian_normals() {
    let tube = Tube { rings: 65, around: 48, length: 4.0, radius: 0.5 };
    check("tube", &tube.mesh(), &tube_rig(&tube, 8, 16), &BEND, Target::Facets(P99_TARGET_DEG));
}

#[test]
fn tube_jacobian_normals_with_cubic_rotations() {
    let tube = Tube { rings: 65, around: 48, length: 4.0, radius: 0.5 };
    let linear = tube_rig(&tube, 8, 16);
    let sweeps = linear.sweeps().iter().cloned();
    let cubic = sweeps.map(|sweep| sweep.with_rotation_interpolation(RotationInterpolation::Cubic)).collect();
    check("tube, cubic rotations", &tube.mesh(), &Rig::new(cubic).unwrap(), &BEND, Target::Facets(P99_TARGET_DEG));
}

#[test]
fn falloff_bands_keep_their_triangle_normals() {
    for falloff in [0.0, 0.8] {
        let (mesh, rig) = common::falloff_tubes::attached_arm(falloff);
        // The end caps' fans (a third of a tube's rim facets span its whole radius) bend
        // visibly: 2.3° at the 99th percentile with falloff through the Jacobian alone, 0.04°
        // with them left to the triangles.
        let target = Target::Facets(P99_TARGET_DEG);
        check(&format!("attached arm, falloff {falloff}"), &mesh, &rig, &BEND, target);
        let (mesh, rig) = common::falloff_tubes::split_tube(falloff);
        check(&format!("split tube, falloff {falloff}"), &mesh, &rig, &BEND, target);
    }
}

#[test]
fn every_instance_gets_its_own_jacobian_normals() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube { rings: 33, around: 24, length: 4.0, radius: 0.5 };
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 6, 12));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let source = BindingSource::Bind { owners: &owners, bands: &[] };
    let descriptor = DeformerDescriptor::new(rig.rest(), &positions, source)
        .with_triangles(&triangles)
        .with_instances(3)
        .with_jacobian_normals();
    let mut deformer = GpuDeformer::new(context, &descriptor).unwrap();
    let poses: Vec<_> = (0..3)
        .map(|k| {
            let pose = BendTwistTaper { bend: 0.4 * k as f64, twist: 0.5 * k as f64, taper: 1.0 - 0.1 * k as f64 };
            rig.pose(&pose.keys(&rig)).unwrap()
        })
        .collect();
    for (k, posed) in poses.iter().enumerate() {
        deformer.set_pose(k as u32, posed).unwrap();
    }
    let mut encoder = context.device.create_command_encoder(&Default::default());
    deformer.encode(&mut encoder);
    context.queue.submit([encoder.finish()]);
    let bindings: Vec<GpuBinding> = deformer.read_bindings().unwrap();
    let adjacency = NormalAdjacency::new(&mesh.faces, mesh.positions.len());
    let rest_f32 = cpu::packed(&mesh.positions);
    let mut rest_normals = vec![0.0; rest_f32.len()];
    cpu::normals::normals(&rest_f32, &adjacency, &mut rest_normals);
    let mut coefficients = SweepCoefficients::new(rig.rest());
    let records: Vec<Vec4> = cpu::jacobian::coordinates(&coefficients.cells, &bindings, &rest_normals);
    // The vertices whose normals the deform kernel writes; the normals pass recomputes the rest.
    let influence = vec![0; positions.len()];
    let written = jacobian_normal_vertices(rig.rest(), &positions, &adjacency, &triangles, &influence);
    let bound: Vec<usize> = (0..bindings.len()).filter(|&i| bindings[i].cell != UNOWNED && written[i]).collect();
    for (k, posed) in poses.iter().enumerate() {
        coefficients.update(posed).unwrap();
        let (mut p, mut n) = (rest_f32.clone(), rest_normals.clone());
        cpu::deform::deform_with_normals(&coefficients.cells, &bindings, &records, &mut p, &mut n);
        let gpu = deformer.read_instance_normals(k as u32).unwrap().unwrap();
        let (error, worst_at) = worst(&bound, |i| at(&gpu, i), |i| at(&n, i));
        println!("instance {k}: Jacobian normals, GPU vs twin worst angle {error:.2e} rad at vertex {worst_at}");
        assert!(error <= NORMAL_TOLERANCE, "instance {k}: {error} rad at vertex {worst_at}");
    }
}

#[test]
fn jacobian_normals_need_triangles_and_fixed_bands() {
    let Some(context) = common::gpu() else { return };
    let (mesh, rig) = common::falloff_tubes::attached_arm(0.5);
    let owners = rig.owners(&mesh, "arm").unwrap();
    let positions = rest_positions(&mesh.positions);
    let source = BindingSource::Bind { owners: &owners, bands: &[] };
    let descriptor = DeformerDescriptor::new(rig.rest(), &positions, source).with_jacobian_normals();
    let error = GpuDeformer::new(context, &descriptor).unwrap_err().to_string();
    assert!(error.contains("need triangles"), "{error}");
    let mut deformer = deformer(context, &mesh, &rig, &owners, true);
    let bands = rig.band_weights(&mesh, &owners);
    let error = deformer.set_bands(&positions, &bands).unwrap_err().to_string();
    assert!(error.contains("Jacobian normals"), "{error}");
}
