//! The cubic rotation interpolation (`RotationInterpolation::Cubic`, C¹ frames) through every
//! path, on a tube whose rest keys tilt back and forth (so its rest frames turn about changing
//! axes and each binding polynomial is a true nonic) and on the armadillo's `autorig` rig:
//!
//! - the f64 reference binds every vertex to a root of ⟨v − C(t), N(t)⟩, and no root that
//!   dense sampling brackets is nearer (the nonic's roots are all found);
//! - the f32 twin binds and deforms like the f64 reference, the fast CPU path like the twin,
//!   the GPU like the twin and the f64 reference, under a bend, twist and taper;
//! - the cubic and the linear interpolation deform the same mesh differently (the check is not
//!   vacuous).
//!
//! Without a GPU adapter the GPU part prints a notice and passes; `SWEEPFFD_REQUIRE_GPU=1` (set
//! by CI) makes a missing adapter fail it.

use crate::common;

use common::sampled_roots::{f, nearest_sampled_root};

use glam::{DQuat, DVec3};
use rayon::prelude::*;
use sweepffd::bind::{Binding, bind_vertices};
use sweepffd::coeffs::{GpuBinding, SweepCoefficients, UNOWNED};
use sweepffd::cpu;
use sweepffd::cpu_fast::FastMesh;
use sweepffd::deform::deform_hard;
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::gpu::BindingSource;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::{RotationInterpolation, Sweep};
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

const POSE: BendTwistTaper = BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 };
/// `rig` with every sweep's rotations interpolated as `rotation` says.
fn with_rotation(rig: &Rig, rotation: RotationInterpolation) -> Rig {
    let sweeps = rig.sweeps().iter().cloned().map(|sweep| sweep.with_rotation_interpolation(rotation)).collect();
    Rig::new(sweeps).unwrap()
}

/// A tube of `tube_rig`'s nine keys, each tilted about x and y by a different small angle.
fn tilting_tube() -> (Mesh, Rig) {
    let tube = Tube { rings: 80, around: 32, length: 4.0, radius: 0.5 };
    let mut sweeps = tube_rig(&tube, 9, 16).sweeps().to_vec();
    for (i, key) in sweeps[0].keys.iter_mut().enumerate() {
        let i = i as f64;
        key.rotation = DQuat::from_rotation_x(0.2 * (1.7 * i).sin()) * DQuat::from_rotation_y(0.15 * (1.1 * i).cos());
    }
    (tube.mesh(), Rig::new(sweeps).unwrap())
}

/// Every bound t is a root, and no sampled root is nearer.
fn check_roots(name: &str, mesh: &Mesh, rig: &Rig, bindings: &[Binding]) {
    let diagonal = mesh.diagonal();
    let results: Vec<(usize, f64, f64)> = (0..bindings.len())
        .into_par_iter()
        .filter(|&i| bindings[i].sweep != UNOWNED)
        .map(|i| {
            let sweep = &rig.rest()[bindings[i].sweep as usize];
            let (v, t) = (mesh.positions[i], bindings[i].params.t);
            let sampled = nearest_sampled_root(sweep, v);
            let nearer_by = sampled.map_or(f64::NEG_INFINITY, |distance| sweep.center(t).distance(v) - distance);
            let at_end = t == 0.0 || t == 1.0;
            (i, if at_end && sampled.is_none() { 0.0 } else { f(sweep, v, t).abs() }, nearer_by)
        })
        .collect();
    let residual = results.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
    let nearer = results.iter().copied().max_by(|a, b| a.2.total_cmp(&b.2)).unwrap();
    println!(
        "{name}: f64 binding, worst |f(t)| {:.2e} × diagonal at vertex {}; a sampled root at most {:.2e} × diagonal \
         nearer (vertex {})",
        residual.1 / diagonal,
        residual.0,
        nearer.2.max(0.0) / diagonal,
        nearer.0
    );
    assert!(residual.1 <= 1e-6 * diagonal, "{name}: |f(t)| = {:e} at vertex {}", residual.1, residual.0);
    assert!(nearer.2 <= 1e-9 * diagonal, "{name}: a root nearer by {:e} to vertex {}", nearer.2, nearer.0);
}

/// The largest distance between `a` (packed f32) and `b`, and its vertex.
fn worst(a: &[f32], b: &[DVec3]) -> (f64, usize) {
    a.chunks_exact(3)
        .zip(b)
        .map(|(p, q)| DVec3::new(p[0].into(), p[1].into(), p[2].into()).distance(*q))
        .enumerate()
        .fold((0.0, 0), |(max, at), (i, e)| if e > max { (e, i) } else { (max, at) })
}

/// Each vertex's bound t (`None` for an unbound vertex), from f32 bindings of the rest sweeps.
fn parameters(coefficients: &SweepCoefficients, rest: &[Sweep], bindings: &[GpuBinding]) -> Vec<Option<f64>> {
    let t = |b: &GpuBinding| (b.cell != UNOWNED).then(|| coefficients.reference_binding(rest, b).params.t);
    bindings.iter().map(t).collect()
}

/// The largest |Δt| outside the vertices that chose another root (|Δt| > 1e-3), their count,
/// and the worst vertex.
fn worst_dt(a: &[Option<f64>], b: &[Option<f64>]) -> (f64, usize, usize) {
    let (mut worst, mut at, mut flips) = (0.0, 0, 0);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert_eq!(x.is_none(), y.is_none(), "vertex {i} bound on one side only");
        let (Some(x), Some(y)) = (x, y) else { continue };
        let dt = (x - y).abs();
        if dt > 1e-3 {
            flips += 1;
        } else if dt > worst {
            (worst, at) = (dt, i);
        }
    }
    (worst, flips, at)
}

fn check(name: &str, mesh: &Mesh, rig: &Rig) {
    let rest = rig.rest();
    assert!(rest.iter().all(|sweep| sweep.rotation_interpolation() == RotationInterpolation::Cubic));
    let diagonal = mesh.diagonal();
    let owners = rig.owners(mesh, name).unwrap();
    let bindings = bind_vertices(rest, &owners, &mesh.positions, &|_| {});
    check_roots(name, mesh, rig, &bindings);
    let posed = rig.pose(&POSE.keys(rig)).unwrap();
    let mut reference = vec![DVec3::ZERO; mesh.positions.len()];
    deform_hard(&posed, &bindings, &mesh.positions, &mut reference);

    // The f32 twin against the f64 reference.
    let mut coefficients = SweepCoefficients::new(rest);
    let rest_f32 = cpu::packed(&mesh.positions);
    let twin_bindings = cpu::bind::bind_to(rest, &owners, &rest_f32);
    let reference_t: Vec<Option<f64>> = bindings.iter().map(|b| (b.sweep != UNOWNED).then_some(b.params.t)).collect();
    let twin_t = parameters(&coefficients, rest, &twin_bindings);
    let (dt, flips, at) = worst_dt(&twin_t, &reference_t);
    println!("{name}: f32 twin vs f64 binding, worst |Δt| {dt:.2e} at vertex {at}, {flips} chose another root");
    assert!(dt <= 1e-5 && flips * 1000 <= mesh.positions.len(), "{name}: twin |Δt| {dt:e} at {at}, {flips} flips");
    coefficients.update(&posed).unwrap();
    let mut twin = rest_f32.clone();
    cpu::deform::deform(&coefficients.cells, &twin_bindings, &mut twin);
    let (error, at) = worst(&twin, &reference);
    println!("{name}: posed, f32 twin vs f64 worst {:.2e} × diagonal at vertex {at}", error / diagonal);
    assert!(error <= 1e-5 * diagonal, "{name}: twin vertex {at} off by {error:e}");

    // The fast CPU path against the twin.
    let mut fast = FastMesh::bind(rest, &owners, &[], &rest_f32);
    let mut fast_positions = rest_f32.clone();
    fast.deform(&posed, &mut fast_positions).unwrap();
    let twin_as_f64: Vec<DVec3> =
        twin.chunks_exact(3).map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into())).collect();
    let (error, at) = worst(&fast_positions, &twin_as_f64);
    println!("{name}: posed, fast CPU path vs twin worst {:.2e} × diagonal at vertex {at}", error / diagonal);
    assert!(error <= 1e-6 * diagonal, "{name}: fast path vertex {at} off the twin by {error:e}");

    // The linear interpolation moves the same mesh elsewhere.
    let linear = with_rotation(rig, RotationInterpolation::Linear);
    let linear_bindings = bind_vertices(linear.rest(), &owners, &mesh.positions, &|_| {});
    let mut linear_positions = vec![DVec3::ZERO; mesh.positions.len()];
    deform_hard(&linear.pose(&POSE.keys(&linear)).unwrap(), &linear_bindings, &mesh.positions, &mut linear_positions);
    let apart = linear_positions.iter().zip(&reference).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    println!("{name}: cubic vs linear interpolation, up to {:.2e} × diagonal apart", apart / diagonal);
    assert!(apart > 1e-3 * diagonal, "{name}: the interpolations agree to {apart:e}");

    // The GPU against the twin and the f64 reference.
    let Some(context) = common::gpu() else { return };
    let source = BindingSource::Bind { owners: &owners, bands: &[] };
    let mut deformer = common::deformer(context, rest, &mesh.positions, source, Some(&mesh.faces)).unwrap();
    let gpu_bindings = deformer.read_bindings().unwrap();
    let rest_coefficients = SweepCoefficients::new(rest);
    let (dt, flips, at) = worst_dt(&parameters(&rest_coefficients, rest, &gpu_bindings), &twin_t);
    println!("{name}: GPU vs twin binding, worst |Δt| {dt:.2e} at vertex {at}, {flips} chose another root");
    assert!(dt <= 1e-5 && flips * 1000 <= mesh.positions.len(), "{name}: GPU |Δt| {dt:e} at {at}, {flips} flips");
    deformer.deform(&posed).unwrap();
    let (error, at) = worst(&deformer.read_positions().unwrap(), &reference);
    println!("{name}: posed, GPU vs f64 worst {:.2e} × diagonal at vertex {at}", error / diagonal);
    assert!(error <= 1e-5 * diagonal, "{name}: GPU vertex {at} off by {error:e}");
}

#[test]
fn tilting_tube_with_cubic_rotations_agrees_on_every_path() {
    let (mesh, rig) = tilting_tube();
    check("tilting tube", &mesh, &with_rotation(&rig, RotationInterpolation::Cubic));
}

#[test]
fn armadillo_autorig_with_cubic_rotations_agrees_on_every_path() {
    let Some(path) = common::shared_mesh("armadillo_50k.obj") else { return };
    let mesh = Mesh::load(&path).unwrap();
    let document = autorig(&mesh, &AutorigOptions::default()).unwrap().document();
    let rig = Rig::from_document(&document, None).unwrap();
    check("armadillo autorig", &mesh, &with_rotation(&rig, RotationInterpolation::Cubic));
}
