//! The `bend` edit on limbs that `autorig` fits (the bunny's ears, spot's legs, the
//! armadillo's limbs): a 60° bend spread over a fifth of the limb, beside the same turn given
//! to the one key nearest the bend, measured by the edge lengths over the whole mesh (the CPU
//! reference; `tests/gpu` checks the GPU's deformation of the same bends).
//!
//! A bend whose cross-sections stay rigid and normal to the spine stretches its outer side by
//! 1 + w·κ and shortens its inner side by 1 − w·κ, where w is the surface's distance from the
//! bend's axis in the bend's plane and κ the spine's curvature: turned by α within a span s of
//! a limb of length L, κ is at least α / (s·L), and [`BEND_TAPER`]'s window makes its peak
//! 1 / (1 − taper) times that. That is the least stretch any bend within the span can have, and
//! the bend is held to it (within [`SLACK`] for the vertices' offsets from the fitted surface);
//! a key turned alone bends over its two knot intervals and misses it.

use crate::common;

use glam::{DQuat, DVec3};
use sweepffd::deform::deform_vertices;
use sweepffd::edit::{BEND_TAPER, Edit, KeyMode, Posing};
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::{FoldKind, Key, RotationInterpolation};

use common::bends::{largest_crease, stretch_range, thinnest_axis};

/// The bend: 60° at t = 0.5 over a fifth of the limb.
const ANGLE_DEGREES: f64 = 60.0;
const SPAN: f64 = 0.2;
/// The measured stretch may exceed the bound of the fitted surface by this factor: a vertex
/// lies off the surface by its d.
const SLACK: f64 = 1.1;

/// One limb bent both ways: the stretch ranges (largest, smallest) of the bend and of the
/// key turned alone, the least largest stretch of any bend within the span, and the keys.
struct Bent {
    limb: String,
    bend: (f64, f64),
    one_key: (f64, f64),
    /// The largest change of a dihedral angle (degrees) under the bend and under the key turned
    /// alone ([`largest_crease`]).
    creases: (f64, f64),
    least: f64,
    keys: usize,
    /// Whether the bend's pose is warned of as folding its cross-sections.
    folds: bool,
}

/// Bends each of `limbs` (part names) of `mesh`'s autorig by [`ANGLE_DEGREES`] over
/// [`SPAN`] at t = 0.5, and apart turns the key nearest t = 0.5 by as much.
fn bend_limbs(name: &str, mesh: &Mesh, limbs: &[&str]) -> Vec<Bent> {
    bend_limbs_with(name, mesh, limbs, RotationInterpolation::Linear)
}

/// [`bend_limbs`] with the rig's rotations interpolated as `rotation` says.
fn bend_limbs_with(name: &str, mesh: &Mesh, limbs: &[&str], rotation: RotationInterpolation) -> Vec<Bent> {
    let mut document = autorig(mesh, &AutorigOptions::default()).unwrap().document();
    document.rotation_interpolation = Some(rotation);
    let rig = Rig::from_document(&document, None).unwrap();
    let owners = rig.owners(mesh, name).unwrap();
    let bindings = rig.bind_mesh(mesh, &owners, &|_| {});
    let deformed = |keys: &[Vec<Key>]| {
        let posed = rig.pose(keys).unwrap();
        let mut out = vec![DVec3::ZERO; mesh.positions.len()];
        deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut out);
        assert!(out.iter().all(|p| p.is_finite()), "{name}: a non-finite vertex");
        out
    };
    limbs
        .iter()
        .map(|&limb| {
            let sweep = rig.sweep_index(limb).unwrap_or_else(|| panic!("{name}: no part {limb}"));
            let (axis, reach) = thinnest_axis(&rig, sweep, 0.5, SPAN);
            let mut posing = Posing::new(&rig);
            let bend = Edit::Bend { sweep: limb.into(), t: 0.5, span: SPAN, axis: axis.to_array(), angle_deg: ANGLE_DEGREES };
            posing.apply(&bend).unwrap();
            let warnings = posing.warnings().unwrap();
            for warning in &warnings {
                eprintln!("  warning: {warning}");
            }
            let folds = warnings.iter().any(|w| w.sweep == limb && w.fold.kind == FoldKind::SectionsCross);
            let knots = rig.rest()[sweep].knots();
            let key = (0..knots.len()).min_by(|&a, &b| (knots[a] - 0.5).abs().total_cmp(&(knots[b] - 0.5).abs())).unwrap();
            let world = rig.rest()[sweep].orientation(0.5) * axis;
            let mut turned = Posing::new(&rig);
            turned
                .apply(&Edit::MoveKey {
                    sweep: limb.into(),
                    key,
                    translate: [0.0; 3],
                    rotate: DQuat::from_axis_angle(world, ANGLE_DEGREES.to_radians()).to_array(),
                    mode: KeyMode::Local,
                })
                .unwrap();
            let pictures = std::env::var("SWEEPFFD_PICTURES_DIR").ok().filter(|_| rotation == RotationInterpolation::Linear);
            if let Some(dir) = pictures {
                // For `sweepffd render --mesh M --rig NAME-rig.json --pose NAME-LIMB-bend.json`.
                let dir = std::path::PathBuf::from(dir);
                let stem = name.trim_end_matches(".obj");
                std::fs::write(dir.join(format!("{stem}-rig.json")), rig.to_document().to_json()).unwrap();
                for (pose, keys) in [("bend", posing.keys()), ("one-key", turned.keys())] {
                    let path = dir.join(format!("{stem}-{limb}-{pose}.json"));
                    std::fs::write(path, rig.pose_document(keys).to_json()).unwrap();
                }
                // Where the close-up looks: the bend's center at rest, for `render --look-at`.
                let c = rig.rest()[sweep].center(0.5);
                std::fs::write(dir.join(format!("{stem}-{limb}-look-at.txt")), format!("{},{},{}", c.x, c.y, c.z)).unwrap();
            }
            let keys = &rig.sweeps()[sweep].keys;
            let length: f64 = keys.windows(2).map(|w| w[0].center.distance(w[1].center)).sum();
            let curvature = ANGLE_DEGREES.to_radians() / (SPAN * length) / (1.0 - BEND_TAPER);
            let (bend, one_key) = (deformed(posing.keys()), deformed(turned.keys()));
            let bent = Bent {
                limb: limb.into(),
                bend: stretch_range(mesh, &bend),
                one_key: stretch_range(mesh, &one_key),
                creases: (largest_crease(mesh, &bend), largest_crease(mesh, &one_key)),
                least: 1.0 + reach * curvature,
                keys: keys.len(),
                folds,
            };
            eprintln!(
                "{name} {limb} ({rotation:?} frames, {} keys, w/L {:.3}): 60° bend over a fifth: edges {:.3}–{:.3} of rest (1 + w·κ = {:.3}); key \
                 {key} turned 60° alone: {:.3}–{:.3}; warned of a fold: {}",
                bent.keys,
                reach / length,
                bent.bend.1,
                bent.bend.0,
                bent.least,
                bent.one_key.1,
                bent.one_key.0,
                bent.folds
            );
            bent
        })
        .collect()
}

/// Each limb's bend stretches its mesh no more than a bend within its span must (within
/// [`SLACK`]), and less than the key turned alone; it is warned of as folding where w·κ ≥ 1
/// (spot's legs, the armadillo's thickest limb) and not where w·κ ≤ 0.7; on the limbs of at least 15 keys thin enough
/// not to fold (w·κ < 1: not spot's legs), the key turned alone stretches past that bound (the
/// crease the bend removes).
#[test]
fn a_bend_over_a_fifth_of_a_limb_stretches_it_no_more_than_the_bend_must() {
    for (file, limbs) in [
        ("bunny_stanford_zipper.obj", &["limb0", "limb1"][..]),
        ("spot_triangulated.obj", &["limb0", "limb1", "limb2", "limb3"][..]),
        ("armadillo_50k.obj", &["limb0", "limb1", "limb2", "limb3", "limb4", "limb5"][..]),
    ] {
        let Some(path) = common::shared_mesh(file) else { return };
        let mesh = Mesh::load(&path).unwrap();
        for bent in bend_limbs(file, &mesh, limbs) {
            let limb = &bent.limb;
            assert!(
                bent.bend.0 <= SLACK * bent.least,
                "{file} {limb}: stretch {:.3}, bound {:.3}",
                bent.bend.0,
                bent.least
            );
            assert!(
                bent.bend.0 < bent.one_key.0,
                "{file} {limb}: bend {:.3}, one key {:.3}",
                bent.bend.0,
                bent.one_key.0
            );
            // A bend whose inside folds over (w·κ ≥ 1) is warned of; one well short of it is not.
            if bent.least >= 2.0 {
                assert!(bent.folds, "{file} {limb}: w·κ = {:.2} and no warning", bent.least - 1.0);
            } else if bent.least <= 1.7 {
                assert!(!bent.folds, "{file} {limb}: w·κ = {:.2} and a warning", bent.least - 1.0);
            }
            // Where w·κ < 1 (a bend that does not fold its inside over) on a dense fit.
            if bent.keys >= 15 && bent.least < 2.0 {
                assert!(bent.one_key.0 > SLACK * bent.least, "{file} {limb}: the key turned alone meets the bound");
            }
        }
    }
}

/// The cubic rotation interpolation (C¹ frames) against the paper's linear one, on the same
/// limbs: the 60° bend over a fifth and the key nearest the middle turned 60° alone. The linear
/// interpolation turns each knot interval at a constant rate, the least peak rate that turns it
/// by its angle; a turning rate continuous across the keys must peak higher within the same
/// keys, so the cubic stretches the longest edge further: a key turned alone more than under
/// the linear frames, and the bend, whose rate is already spread over the span, within 10%.
/// That is why the linear interpolation stays the default.
#[test]
fn cubic_frames_against_linear_frames_on_bent_limbs() {
    for (file, limbs) in [
        ("bunny_stanford_zipper.obj", &["limb0", "limb1"][..]),
        ("armadillo_50k.obj", &["limb0", "limb1", "limb2", "limb3", "limb4", "limb5"][..]),
    ] {
        let Some(path) = common::shared_mesh(file) else { return };
        let mesh = Mesh::load(&path).unwrap();
        let linear = bend_limbs_with(file, &mesh, limbs, RotationInterpolation::Linear);
        let cubic = bend_limbs_with(file, &mesh, limbs, RotationInterpolation::Cubic);
        for (linear, cubic) in linear.iter().zip(&cubic) {
            eprintln!(
                "{file} {}: one key, longest edge {:.3} linear, {:.3} cubic, largest crease {:.1}° linear, {:.1}° cubic; \
                 bend, longest edge {:.3} linear, {:.3} cubic, largest crease {:.1}° linear, {:.1}° cubic",
                linear.limb,
                linear.one_key.0,
                cubic.one_key.0,
                linear.creases.1,
                cubic.creases.1,
                linear.bend.0,
                cubic.bend.0,
                linear.creases.0,
                cubic.creases.0
            );
            assert!(cubic.one_key.0 > linear.one_key.0, "{file} {}: the cubic's turn peaks lower", linear.limb);
            assert!(
                cubic.bend.0 <= 1.1 * linear.bend.0,
                "{file} {}: the cubic's bend stretches past 110%",
                linear.limb
            );
        }
    }
}
