//! What a bench deforms: a mesh, its rig, the owners of its vertices and a pose.

use crate::mesh::Mesh;
use crate::rig::Rig;
use crate::sweep::{Key, Sweep};
use crate::synthetic::{BendTwistTaper, Tube, attached_tube_rig, split_tube_rig, tube_rig};

/// The pose every bench applies: a bend, a twist and a taper of every sweep.
pub const BENCH_POSE: BendTwistTaper = BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 };

/// A mesh bound to a rig, with the posed sweeps to deform it by.
#[derive(Clone, Debug)]
pub struct BenchScene {
    /// The mesh.
    pub mesh: Mesh,
    /// Its rest rig.
    pub rig: Rig,
    /// The owning sweep of each vertex.
    pub owners: Vec<u32>,
    /// The keys of the rig bent, twisted and tapered by `BENCH_POSE`.
    pub keys: Vec<Vec<Key>>,
    /// The posed sweeps of those keys.
    pub posed: Vec<Sweep>,
    /// The same mesh with falloff bands over [`BAND_FRACTION`] of it, deformed in the same run
    /// for the cost of the bands, each with what its bands fade into; only for the synthetic
    /// tube.
    pub with_falloff: Vec<(FalloffKind, BenchScene)>,
}

/// The share of the tube's vertices in falloff bands in the falloff comparison.
pub const BAND_FRACTION: f64 = 0.25;

/// What the bands of a falloff comparison fade into.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FalloffKind {
    /// The rest position: a part attached to a mesh it does not own (ears on a head).
    Rest,
    /// A neighbouring sweep: two sweeps meeting at a joint (the costlier band).
    Sweep,
}

impl BenchScene {
    /// A closed tube of about `vertices` vertices bound to one straight 8-key sweep (at least
    /// [`MIN_BENCH_VERTICES`], the smallest tube the falloff comparison can split at a middle
    /// ring; see [`tube_vertex_count`]).
    ///
    /// [`MIN_BENCH_VERTICES`]: super::MIN_BENCH_VERTICES
    /// [`tube_vertex_count`]: super::tube_vertex_count
    pub fn tube(vertices: usize) -> BenchScene {
        let tube = Tube::with_vertex_count(vertices.max(super::MIN_BENCH_VERTICES), 4.0, 0.5);
        let mut scene =
            BenchScene::new(tube.mesh(), tube_rig(&tube, 8, 16), "tube").expect("the tube rig owns the tube");
        // The tube attached at its first ring, fading to rest over BAND_FRACTION of its length;
        // and two sweeps meeting at the middle, each blending into the other over half that on
        // its side.
        let attached = attached_tube_rig(&tube, 8, 16, BAND_FRACTION * tube.length);
        let split = split_tube_rig(&tube, 4, 16, 0.5 * BAND_FRACTION * tube.length);
        for (kind, rig) in [(FalloffKind::Rest, attached), (FalloffKind::Sweep, split)] {
            let variant = BenchScene::new(tube.mesh(), rig, "tube").expect("the rig owns the tube");
            scene.with_falloff.push((kind, variant));
        }
        scene
    }

    /// `mesh` bound to `rig`; fails if the rig's vertex selection does not fit the mesh.
    pub fn new(mesh: Mesh, rig: Rig, mesh_name: &str) -> Result<BenchScene, crate::rig::RigError> {
        let owners = rig.owners(&mesh, mesh_name)?;
        let keys = BENCH_POSE.keys(&rig);
        let posed = rig.pose(&keys)?;
        Ok(BenchScene { mesh, rig, owners, keys, posed, with_falloff: Vec::new() })
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.mesh.positions.len()
    }
}
