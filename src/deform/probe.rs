//! Which vertices of the Jacobian reach ([`jacobian_reach`]) keep Jacobian normals: those whose
//! normal through the Jacobian of Eq. 2 ([`crate::deform::jacobian`]) matches the normal of
//! their deformed one-ring under a probe pose, decided once at bind time.
//!
//! The Jacobian normal is the limit of the normals of vanishing facets; the area-weighted
//! normal of finite facets sums cof(J(c_f))·A_f·n_f over the ring's triangles f, with J
//! evaluated where each triangle lies. The two differ by ∇J·(c_f − x) ⊗ n_f terms, which are
//! small only where J varies little across the ring. On coarse or thin parts it does not: a
//! thin sheet seen from its sweep's axis (the rays meet its faces at a grazing angle, so a
//! taper shears them by r_θ/ρ, which changes across a ring spanning a good part of a radius
//! sample), and a ring that straddles an end plane (where Eq. 2 extended by h changes from
//! (θ, t, d) to (θ, h, d), continuous but with a kink). There the deformed triangles, which
//! renderers and the normals pass agree on, are kept: the probe bends, twists and tapers each
//! rest sweep ([`PROBE`]), and a vertex whose Jacobian normal misses its probed facets' normal
//! by more than [`PROBE_TOLERANCE_DEG`] leaves the reach, for every pose.
//!
//! Data flow: rig → sweep → bind → deform, with **this check, once** at bind time → normals.

use std::f64::consts::TAU;

use glam::{DVec3, Vec3};

use super::deform_vertex;
use super::jacobian::{deformed_normal, normal_coordinates};
use crate::bind::{SweepBinder, VertexBinding};
use crate::normals::{NormalAdjacency, fan_normal, jacobian_reach};
use crate::parallel::prelude::*;
use crate::rig::BendTwistTaper;
use crate::sweep::{Key, Sweep};

/// The probe pose: each sweep bent by about 30°, twisted by about 30° and tapered to 0.8 along
/// its knots (§4, Fig. 7), a moderate animator's pose.
pub const PROBE: BendTwistTaper = BendTwistTaper { bend: 0.5, twist: 0.5, taper: 0.8 };
/// The largest angle between a vertex's Jacobian normal and the normal of its deformed
/// triangles under [`PROBE`] for which it keeps the Jacobian normal, degrees.
pub const PROBE_TOLERANCE_DEG: f64 = 1.5;

/// For each vertex, whether the deform kernel writes its normal through the Jacobian: it is in
/// [`jacobian_reach`] of `triangles` and `influence`, and under [`PROBE`] its Jacobian normal
/// lies within [`PROBE_TOLERANCE_DEG`] of the area-weighted normal of its deformed one-ring
/// (`adjacency` of the same triangles, rest `positions`, each vertex bound to the rest sweep of
/// its influence in `rest`). A sweep whose probe cannot be built keeps its whole reach; a
/// vertex whose rest normal is zero keeps its answer from the reach, one whose probed normals
/// vanish (a ring the probe collapses) keeps the Jacobian, and a NaN leaves the reach.
pub fn jacobian_normal_vertices(
    rest: &[Sweep],
    positions: &[[f32; 3]],
    adjacency: &NormalAdjacency,
    triangles: &[u32],
    influence: &[u32],
) -> Vec<bool> {
    let reach = jacobian_reach(triangles, influence);
    let probes: Vec<Option<Sweep>> = rest.iter().map(probe_sweep).collect();
    let binders: Vec<SweepBinder> = rest.iter().map(SweepBinder::new).collect();
    let rest_at = |v: usize| Vec3::from_array(positions[v]).as_dvec3();
    let bindings: Vec<Option<VertexBinding>> = (0..influence.len())
        .into_par_iter()
        .map(|v| binders.get(influence[v] as usize).map(|binder| binder.bind(rest_at(v))))
        .collect();
    (0..reach.len())
        .into_par_iter()
        .map(|i| {
            let (true, Some(binding)) = (reach[i], bindings[i]) else { return reach[i] };
            let sweep = influence[i] as usize;
            let Some(Some(probe)) = probes.get(sweep) else { return true };
            let normal = fan_normal(adjacency, i, rest_at);
            if normal == DVec3::ZERO {
                return true;
            }
            // The ring of a vertex in the reach is bound to its own sweep, wholly.
            let probed = |v: usize| bindings[v].map_or(rest_at(v), |b| deform_vertex(probe, &b));
            let facets = fan_normal(adjacency, i, probed);
            let coordinates = normal_coordinates(&rest[sweep], &binding, normal);
            let jacobian = deformed_normal(probe, &binding, &coordinates);
            let angle = jacobian.cross(facets).length().atan2(jacobian.dot(facets));
            angle.to_degrees() <= PROBE_TOLERANCE_DEG
        })
        .collect()
}

/// `rest` under [`PROBE`]: its keys read back at its knots (centers, frames and radii at
/// θ_j = 2πj/M, a zero radius's round-off below zero clamped), bent, twisted and tapered; `None` if the probed keys make no valid sweep.
pub(crate) fn probe_sweep(rest: &Sweep) -> Option<Sweep> {
    let samples = rest.radius_samples();
    let keys: Vec<Key> = rest
        .knots()
        .iter()
        .map(|&t| Key {
            center: rest.center(t),
            rotation: rest.orientation(t),
            radii: (0..samples).map(|j| rest.radius(TAU * j as f64 / samples as f64, t).max(0.0)).collect(),
        })
        .collect();
    Sweep::try_new(&PROBE.sweep_keys(&keys, rest.knots()), Some(rest.knots())).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coeffs::UNOWNED;
    use crate::synthetic::{Tube, tube_rig};

    #[test]
    fn a_fine_tube_keeps_its_reach() {
        // A fine tube bound to a sweep that fits it: the Jacobian predicts its facets.
        let tube = Tube { rings: 65, around: 48, length: 4.0, radius: 0.5 };
        let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
        let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.as_vec3().to_array()).collect();
        let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
        let adjacency = NormalAdjacency::new(&mesh.faces, positions.len());
        let influence = vec![0; positions.len()];
        let kept = jacobian_normal_vertices(rig.rest(), &positions, &adjacency, &triangles, &influence);
        let reach = jacobian_reach(&triangles, &influence);
        assert!(kept.iter().zip(&reach).all(|(&k, &r)| !k || r), "a vertex outside the reach was kept");
        let share = kept.iter().filter(|&&k| k).count() as f64 / reach.iter().filter(|&&r| r).count() as f64;
        assert!(share > 0.95, "only {share} of the reach kept");
    }

    #[test]
    fn a_coarse_tube_leaves_the_rings_the_jacobian_misses() {
        // Eight facets around: each ring spans a quarter turn of the sweep's radius field.
        let tube = Tube { rings: 6, around: 8, length: 4.0, radius: 0.5 };
        let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 4, 8));
        let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.as_vec3().to_array()).collect();
        let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
        let adjacency = NormalAdjacency::new(&mesh.faces, positions.len());
        let influence = vec![0; positions.len()];
        let kept = jacobian_normal_vertices(rig.rest(), &positions, &adjacency, &triangles, &influence);
        // The same decision from the whole mesh's normals, rest and probed.
        let rest: Vec<DVec3> = positions.iter().map(|&p| Vec3::from_array(p).as_dvec3()).collect();
        let (sweep, binder) = (&rig.rest()[0], SweepBinder::new(&rig.rest()[0]));
        let probe = probe_sweep(sweep).unwrap();
        let bindings: Vec<VertexBinding> = rest.iter().map(|&p| binder.bind(p)).collect();
        let probed: Vec<DVec3> = bindings.iter().map(|b| deform_vertex(&probe, b)).collect();
        let (rest_normals, facets) =
            (crate::normals::vertex_normals(&rest, &adjacency), crate::normals::vertex_normals(&probed, &adjacency));
        let mut left = 0;
        for i in 0..positions.len() {
            let coordinates = normal_coordinates(sweep, &bindings[i], rest_normals[i]);
            let jacobian = deformed_normal(&probe, &bindings[i], &coordinates);
            let degrees = jacobian.cross(facets[i]).length().atan2(jacobian.dot(facets[i])).to_degrees();
            assert_eq!(kept[i], degrees <= PROBE_TOLERANCE_DEG, "vertex {i}: {degrees}°");
            left += usize::from(!kept[i]);
        }
        assert!(left > 0, "no ring of the coarse tube left to the triangles");
    }

    #[test]
    fn unowned_vertices_stay_out() {
        let tube = Tube { rings: 9, around: 12, length: 4.0, radius: 0.5 };
        let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 4, 12));
        let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.as_vec3().to_array()).collect();
        let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
        let adjacency = NormalAdjacency::new(&mesh.faces, positions.len());
        let influence = vec![UNOWNED; positions.len()];
        let kept = jacobian_normal_vertices(rig.rest(), &positions, &adjacency, &triangles, &influence);
        assert!(kept.iter().all(|&k| !k));
    }
}
