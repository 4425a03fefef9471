//! The fixed scene the rig-level targets run against: a small closed tube, the rig `family`
//! (the tube's sweep `tube` with a virtual `arm` hanging from it as a branch, as in the tests
//! of `sweepffd pose`), the tube's bindings and a bend-twist-taper pose.

use std::sync::OnceLock;

use glam::{DQuat, DVec3};
use sweepffd::bind::MeshBindings;
use sweepffd::bindings_file::BindingsFile;
use sweepffd::mesh::Mesh;
use sweepffd::rig::{LinkKind, ParentLink, Rig, RigSweep};
use sweepffd::sweep::{Key, Sweep};
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

/// The scene, built once.
pub struct Scene {
    /// The tube mesh (6 rings of 8 vertices and two cap centers).
    pub mesh: Mesh,
    /// The rig `family`.
    pub rig: Rig,
    /// The tube's vertices bound to `rig`.
    pub bindings: MeshBindings,
    /// The rig posed by [`BendTwistTaper`].
    pub posed: Vec<Sweep>,
}

/// The scene, built on first use.
pub fn scene() -> &'static Scene {
    static SCENE: OnceLock<Scene> = OnceLock::new();
    SCENE.get_or_init(|| {
        let tube = Tube { rings: 6, around: 8, length: 3.0, radius: 0.4 };
        let mesh = tube.mesh();
        let mut sweeps = tube_rig(&tube, 5, 8).sweeps().to_vec();
        sweeps.push(arm());
        let rig = Rig::new(sweeps).expect("the family rig is valid");
        let owners = rig.owners(&mesh, "tube.obj").expect("the tube sweep owns the tube");
        let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
        let keys = BendTwistTaper { bend: 0.6, twist: 0.3, taper: 0.8 }.keys(&rig);
        let posed = rig.pose(&keys).expect("the bend is a valid pose");
        Scene { mesh, rig, bindings, posed }
    })
}

/// A virtual arm leaving the tube sideways at height 1.5.
fn arm() -> RigSweep {
    let rotation = DQuat::from_rotation_arc(DVec3::Z, DVec3::X);
    RigSweep {
        name: "arm".into(),
        vertices: None,
        keys: (0..3).map(|i| Key::circle(DVec3::new(0.2 + 0.5 * i as f64, 0.0, 1.5), rotation, 0.1, 8)).collect(),
        knots: None,
        parent: Some(ParentLink { sweep: "tube".into(), kind: LinkKind::Branch }),
        falloff: 0.0,
        rotation: Default::default(),
    }
}

impl Scene {
    /// The bytes of the bindings file of the tube to the rig (a seed of the `bindings` target).
    pub fn bindings_file(&self) -> Vec<u8> {
        BindingsFile::new(&self.rig, &self.mesh.positions, self.bindings.clone()).to_bytes()
    }
}
