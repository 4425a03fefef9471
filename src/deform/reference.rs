//! The whole f64 reference path in one call, for checking another path against it: bind by
//! root-finding against the rest rig (§3), then Eq. 2 on the posed sweeps.

use glam::DVec3;

use super::deform_vertices;
use crate::bind::{MeshBindings, bind_vertices};
use crate::rig::Rig;
use crate::sweep::Sweep;

impl Rig {
    /// The f64 reference positions of `positions` deformed by the `posed` sweeps of this rig:
    /// every vertex owned per `owners` ([`Rig::vertex_owners`]) is bound to its rest sweep and
    /// follows its posed sweep by Eq. 2, unowned vertices stay at rest. Hard boundaries (the
    /// falloff bands need the faces: [`Rig::bind_mesh`]). Binds on every call; to pose one
    /// binding many times, keep [`MeshBindings`] and call [`deform_vertices`].
    pub fn deform_reference(&self, owners: &[u32], positions: &[DVec3], posed: &[Sweep]) -> Vec<DVec3> {
        let bindings = MeshBindings::hard(bind_vertices(self.rest(), owners, positions, &|_| {}));
        let mut deformed = vec![DVec3::ZERO; positions.len()];
        deform_vertices(self.rest(), posed, &bindings, positions, &mut deformed);
        deformed
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::bind::{MeshBindings, UNOWNED, bind_vertices};
    use crate::deform::deform_vertices;
    use crate::rig::{Rig, RigSweep, VertexSelection};
    use crate::synthetic::{BendTwistTaper, Tube, tube_rig};

    fn tube() -> (Tube, Rig, Vec<DVec3>) {
        let tube = Tube { rings: 12, around: 16, length: 2.0, radius: 0.4 };
        let rig = tube_rig(&tube, 5, 16);
        let positions = tube.mesh().positions;
        (tube, rig, positions)
    }

    #[test]
    fn the_reference_at_rest_leaves_every_vertex_in_place() {
        let (_, rig, positions) = tube();
        let owners = rig.vertex_owners(positions.len()).unwrap();
        assert!(owners.iter().all(|&o| o == 0));
        let deformed = rig.deform_reference(&owners, &positions, rig.rest());
        let worst = deformed.iter().zip(&positions).map(|(a, b)| (*a - *b).length()).fold(0.0, f64::max);
        assert!(worst < 1e-9, "a vertex moved by {worst} at rest");
    }

    #[test]
    fn the_reference_is_binding_then_eq_2_and_moves_the_owned_vertices() {
        let (_, rig, positions) = tube();
        let owners = rig.vertex_owners(positions.len()).unwrap();
        let posed = rig.pose(&BendTwistTaper { bend: 1.2, twist: 0.8, taper: 0.6 }.keys(&rig)).unwrap();
        let deformed = rig.deform_reference(&owners, &positions, &posed);
        let bindings = MeshBindings::hard(bind_vertices(rig.rest(), &owners, &positions, &|_| {}));
        let mut expected = vec![DVec3::ZERO; positions.len()];
        deform_vertices(rig.rest(), &posed, &bindings, &positions, &mut expected);
        assert_eq!(deformed, expected);
        let moved = deformed.iter().zip(&positions).map(|(a, b)| (*a - *b).length()).fold(0.0, f64::max);
        assert!(moved > 0.5, "the bend moved the tip by {moved} only");
    }

    #[test]
    fn a_sweep_built_in_code_owns_its_indices_and_errors_call_the_mesh_built_in_code() {
        let (_, rig, positions) = tube();
        let keys = rig.sweeps()[0].keys.clone();
        let partial =
            Rig::new(vec![RigSweep::new("tip", keys.clone()).owning(VertexSelection::Indices(vec![3, 1]))]).unwrap();
        let owners = partial.vertex_owners(positions.len()).unwrap();
        assert_eq!(owners.iter().filter(|&&o| o == 0).count(), 2);
        assert_eq!((owners[1], owners[3], owners[0]), (0, 0, UNOWNED));
        let beyond = Rig::new(vec![RigSweep::new("tip", keys).owning(VertexSelection::Indices(vec![5000]))]).unwrap();
        let message = beyond.vertex_owners(positions.len()).unwrap_err().to_string();
        assert!(message.contains("5000") && message.contains("built in code"), "{message}");
    }
}
