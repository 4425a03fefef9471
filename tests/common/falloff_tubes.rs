//! Tubes with falloff bands for the falloff tests: an arm attached to an unowned base, and a tube
//! split into two sweeps that blend at their joint.

use glam::{DQuat, DVec3};
use sweepffd::mesh::Mesh;
use sweepffd::rig::{Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Key;
use sweepffd::synthetic::Tube;

/// 61 rings of 32 vertices, 6 long, radius 0.5, along z.
pub const TUBE: Tube = Tube { rings: 61, around: 32, length: 6.0, radius: 0.5 };

/// A sweep of six circular keys from z0 to z1 along the tube, owning `vertices`.
pub fn tube_sweep(name: &str, vertices: Vec<u32>, z0: f64, z1: f64, falloff: f64) -> RigSweep {
    let keys = (0..6)
        .map(|i| {
            let z = z0 + (z1 - z0) * i as f64 / 5.0;
            Key::circle(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY, TUBE.radius, 16)
        })
        .collect();
    RigSweep {
        name: name.to_string(),
        vertices: Some(VertexSelection::Indices(vertices)),
        keys,
        knots: None,
        parent: None,
        falloff,
        rotation: Default::default(),
    }
}

/// The vertices of the tube whose z satisfies `keep`.
pub fn tube_vertices(mesh: &Mesh, keep: impl Fn(f64) -> bool) -> Vec<u32> {
    (0..mesh.positions.len() as u32).filter(|&v| keep(mesh.positions[v as usize].z)).collect()
}

/// The tube's upper part (z ≥ 1) owned by one sweep, `arm`, whose band fades into the unowned
/// rest.
pub fn attached_arm(falloff: f64) -> (Mesh, Rig) {
    let mesh = TUBE.mesh();
    let owned = tube_vertices(&mesh, |z| z >= 1.0 - 1e-9);
    let rig = Rig::new(vec![tube_sweep("arm", owned, 0.95, 6.05, falloff)]).unwrap();
    (mesh, rig)
}

/// The tube split at z = 3 into two sweeps, `lower` and `upper`, that meet there: with falloff
/// the band vertices of each fade into the other.
pub fn split_tube(falloff: f64) -> (Mesh, Rig) {
    let mesh = TUBE.mesh();
    let lower = tube_vertices(&mesh, |z| z <= 3.0 + 1e-9);
    let upper = tube_vertices(&mesh, |z| z > 3.0 + 1e-9);
    let rig =
        Rig::new(vec![tube_sweep("lower", lower, -0.05, 3.0, falloff), tube_sweep("upper", upper, 3.0, 6.05, falloff)])
            .unwrap();
    (mesh, rig)
}
