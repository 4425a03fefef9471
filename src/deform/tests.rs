//! The Jacobian normals of the f64 reference ([`super::jacobian`]): the parameter Jacobian
//! against central differences, the cofactor identity, and deformed normals against the
//! normals of tiny facets carried through binding and Eq. 2.

use glam::{DMat3, DQuat, DVec3};

use super::deform_vertex;
use super::jacobian::{
    NormalCoordinates, cofactor_times, deformed_normal, is_beyond_end, normal_coordinates, parameter_jacobian,
};
use crate::bind::{SweepBinder, VertexBinding};
use crate::sweep::{Key, Sweep};

const KEYS: usize = 6;

/// Keys along a gentle bend in the xz plane with wavy, uneven radii; `posed` bends it further,
/// twists and tapers it and moves it, keeping the knots.
fn keys(posed: bool) -> Vec<Key> {
    (0..=KEYS)
        .map(|i| {
            let u = i as f64 / KEYS as f64;
            let bend = if posed { 1.4 } else { 0.6 };
            let a = bend * u;
            let center = DVec3::new(3.0 * (1.0 - a.cos()), 0.2 * u, 3.0 * a.sin());
            let twist = if posed { DQuat::from_rotation_z(0.9 * u) } else { DQuat::IDENTITY };
            let rotation = DQuat::from_rotation_y(a) * twist;
            let scale = if posed { 1.0 - 0.4 * u } else { 1.0 };
            let radii = (0..8).map(|j| scale * (0.5 + 0.08 * ((j + i) % 3) as f64)).collect();
            let offset = if posed { DVec3::new(0.5, -0.3, 0.2) } else { DVec3::ZERO };
            Key { center: center + offset, rotation, radii }
        })
        .collect()
}

fn sweeps() -> (Sweep, Sweep) {
    let rest = Sweep::try_new(&keys(false), None).unwrap();
    let posed = Sweep::try_new(&keys(true), Some(rest.knots())).unwrap();
    (rest, posed)
}

/// Bindings inside the sweep, off its surface and beyond both ends.
fn bindings() -> Vec<VertexBinding> {
    let mut out = Vec::new();
    for i in 0..7 {
        for j in 0..5 {
            let theta = 0.37 + 0.91 * i as f64;
            let t = 0.03 + 0.19 * j as f64;
            out.push(VertexBinding { theta, t, d: -0.1 + 0.05 * i as f64, h: 0.0 });
        }
        out.push(VertexBinding { theta: 0.2 + 0.8 * i as f64, t: 0.0, d: 0.03, h: -0.2 });
        out.push(VertexBinding { theta: 0.5 + 0.8 * i as f64, t: 1.0, d: -0.02, h: 0.15 });
    }
    out
}

/// Central differences of the point in (θ, t, d), or (θ, h, d) beyond an end.
fn differences(sweep: &Sweep, b: &VertexBinding) -> DMat3 {
    let e = 1e-6;
    let at = |dtheta: f64, daxis: f64, dd: f64| {
        if is_beyond_end(b) {
            sweep.point(b.theta + dtheta, b.t, b.d + dd, b.h + daxis)
        } else {
            sweep.point(b.theta + dtheta, b.t + daxis, b.d + dd, b.h)
        }
    };
    DMat3::from_cols(
        (at(e, 0.0, 0.0) - at(-e, 0.0, 0.0)) / (2.0 * e),
        (at(0.0, e, 0.0) - at(0.0, -e, 0.0)) / (2.0 * e),
        (at(0.0, 0.0, e) - at(0.0, 0.0, -e)) / (2.0 * e),
    )
}

#[test]
fn parameter_jacobian_matches_central_differences() {
    let (rest, posed) = sweeps();
    let mut worst = 0.0f64;
    for sweep in [&rest, &posed] {
        for b in bindings() {
            let (analytic, numeric) = (parameter_jacobian(sweep, &b), differences(sweep, &b));
            for k in 0..3 {
                let (a, n) = (analytic.col(k), numeric.col(k));
                let error = (a - n).length() / n.length().max(1.0);
                if error > 1e-7 {
                    eprintln!("{b:?} column {k}: {a} vs {n}");
                }
                worst = worst.max(error);
            }
        }
    }
    eprintln!("parameter Jacobian vs central differences: worst relative error {worst:.2e}");
    assert!(worst < 1e-7, "{worst:e}");
}

#[test]
fn cofactor_product_is_det_times_inverse_transpose() {
    let a = DMat3::from_cols(DVec3::new(1.0, 0.2, -0.3), DVec3::new(0.1, 2.0, 0.4), DVec3::new(-0.5, 0.3, 1.5));
    let m = DVec3::new(0.3, -0.7, 0.2);
    let expected = a.determinant() * a.inverse().transpose() * m;
    assert!((cofactor_times(&a, m) - expected).length() < 1e-12);
}

/// A unit vector that varies with `i`.
fn direction(i: usize) -> DVec3 {
    DVec3::new((1.3 * i as f64).sin(), (0.7 * i as f64).cos(), 0.4 + 0.1 * i as f64).normalize()
}

#[test]
fn the_rest_pose_keeps_every_normal() {
    let (rest, _) = sweeps();
    for (i, b) in bindings().iter().enumerate() {
        let n = direction(i);
        let back = deformed_normal(&rest, b, &normal_coordinates(&rest, b, n));
        assert!((back - n).length() < 1e-12, "{b:?}: {back} vs {n}");
    }
}

#[test]
fn a_rigid_motion_turns_every_normal_with_it() {
    let (rest, _) = sweeps();
    let rotation = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.8);
    let moved: Vec<Key> = keys(false)
        .into_iter()
        .map(|k| Key { center: rotation * k.center + DVec3::new(4.0, -1.0, 2.0), rotation: rotation * k.rotation, ..k })
        .collect();
    let moved = Sweep::try_new(&moved, Some(rest.knots())).unwrap();
    for (i, b) in bindings().iter().enumerate() {
        let n = direction(i);
        let turned = deformed_normal(&moved, b, &normal_coordinates(&rest, b, n));
        assert!((turned - rotation * n).length() < 1e-10, "{b:?}");
    }
}

/// The normal of the facet spanned by `x ± ε·u` and `x ± ε·v` (u, v ⊥ n) after binding each
/// corner to `rest` and deforming it on `posed`.
fn facet_normal(rest: &Sweep, posed: &Sweep, x: DVec3, n: DVec3) -> DVec3 {
    let binder = SweepBinder::new(rest);
    let f = |y: DVec3| deform_vertex(posed, &binder.bind(y));
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let e = 1e-5;
    let du = f(x + e * u) - f(x - e * u);
    let dv = f(x + e * v) - f(x - e * v);
    du.cross(dv).normalize()
}

#[test]
fn deformed_normals_are_the_normals_of_vanishing_facets() {
    let (rest, posed) = sweeps();
    let binder = SweepBinder::new(&rest);
    let (mut worst, mut wrong) = (0.0f64, 0.0f64);
    for (i, b) in bindings().iter().enumerate() {
        let x = rest.point(b.theta, b.t, b.d, b.h);
        let b = binder.bind(x);
        let n = direction(i);
        let coordinates = normal_coordinates(&rest, &b, n);
        assert!(matches!(coordinates, NormalCoordinates::Jacobian(_)));
        let expected = facet_normal(&rest, &posed, x, n);
        let angle = deformed_normal(&posed, &b, &coordinates).angle_between(expected);
        worst = worst.max(angle);
        // Turning the normal with the frame alone (as for a rigid section) misses the stretch.
        let framed = posed.orientation(b.t) * (rest.orientation(b.t).inverse() * n);
        wrong = wrong.max(framed.angle_between(expected));
    }
    eprintln!("Jacobian normal vs facet normal: worst {worst:.2e} rad; frame rotation alone: {wrong:.2e} rad");
    assert!(worst < 1e-6, "{worst:e}");
    assert!(wrong > 1e-2, "{wrong:e}");
}

#[test]
fn a_vertex_on_the_axis_follows_the_frame() {
    let (rest, posed) = sweeps();
    let r = rest.radius(0.0, 0.5);
    let b = VertexBinding { theta: 0.0, t: 0.5, d: -r, h: 0.0 };
    let n = DVec3::new(0.3, 0.4, 0.5).normalize();
    let coordinates = normal_coordinates(&rest, &b, n);
    assert!(matches!(coordinates, NormalCoordinates::Frame(_)), "{coordinates:?}");
    let expected = posed.orientation(0.5) * (rest.orientation(0.5).inverse() * n);
    assert!((deformed_normal(&posed, &b, &coordinates) - expected).length() < 1e-12);
}
