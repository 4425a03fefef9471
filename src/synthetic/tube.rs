//! A closed tube along +z, built from quads with triangle-fan caps, and a sweep rig for it.

use std::f64::consts::TAU;

use glam::{DQuat, DVec3};

use crate::mesh::{FaceGroup, Faces, Mesh};
use crate::rig::{Rig, RigSweep, VertexSelection};
use crate::sweep::Key;

/// A closed cylindrical tube: `rings` rings of `around` vertices from z = 0 to z = `length`,
/// plus one center vertex per cap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tube {
    /// Number of vertex rings along the axis, at least 2.
    pub rings: u32,
    /// Vertices per ring, at least 3.
    pub around: u32,
    /// Length along z.
    pub length: f64,
    /// Radius.
    pub radius: f64,
}

impl Tube {
    /// The tube with about `vertices` vertices, 256 per ring, and the given length and radius.
    pub fn with_vertex_count(vertices: usize, length: f64, radius: f64) -> Tube {
        let around = 256;
        let rings = (vertices.saturating_sub(2) / around as usize).max(2) as u32;
        Tube { rings, around, length, radius }
    }

    /// Number of vertices: `rings·around + 2`.
    pub fn vertex_count(&self) -> usize {
        self.rings as usize * self.around as usize + 2
    }

    /// The mesh: quads between rings (group `wall`), triangle fans at the caps (group `caps`),
    /// faces wound counter-clockwise seen from outside.
    pub fn mesh(&self) -> Mesh {
        let (rings, around) = (self.rings, self.around);
        let mut positions = Vec::with_capacity(self.vertex_count());
        for ring in 0..rings {
            let z = self.length * ring as f64 / (rings - 1) as f64;
            for k in 0..around {
                let angle = TAU * k as f64 / around as f64;
                positions.push(DVec3::new(self.radius * angle.cos(), self.radius * angle.sin(), z));
            }
        }
        let (bottom, top) = (rings * around, rings * around + 1);
        positions.push(DVec3::ZERO);
        positions.push(DVec3::new(0.0, 0.0, self.length));

        let vertex = |ring: u32, k: u32| ring * around + k % around;
        let mut faces = Faces::new();
        for ring in 0..rings - 1 {
            for k in 0..around {
                faces.push(&[vertex(ring, k), vertex(ring, k + 1), vertex(ring + 1, k + 1), vertex(ring + 1, k)]);
            }
        }
        let wall = (0..faces.len() as u32).collect();
        for k in 0..around {
            faces.push(&[bottom, vertex(0, k + 1), vertex(0, k)]);
            faces.push(&[top, vertex(rings - 1, k), vertex(rings - 1, k + 1)]);
        }
        let caps = (wall_len(rings, around)..faces.len() as u32).collect();
        let groups = vec![
            FaceGroup { name: "wall".to_string(), faces: wall },
            FaceGroup { name: "caps".to_string(), faces: caps },
        ];
        Mesh::from_parts(positions, faces, groups).expect("a tube with rings >= 2 and around >= 3 is a valid mesh")
    }
}

fn wall_len(rings: u32, around: u32) -> u32 {
    (rings - 1) * around
}

/// A rig with one sweep, `tube`, owning every vertex of `tube`: `keys` circular keys of
/// `samples` radii equal to the tube's radius, evenly spaced from z = 0 to z = length.
pub fn tube_rig(tube: &Tube, keys: usize, samples: usize) -> Rig {
    let keys = (0..keys)
        .map(|i| {
            let z = tube.length * i as f64 / (keys - 1) as f64;
            Key::circle(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY, tube.radius, samples)
        })
        .collect();
    let sweep = RigSweep::new("tube", keys).owning(VertexSelection::All);
    Rig::new(vec![sweep]).expect("a straight rig with distinct keys is valid")
}

/// A rig with one sweep, `tube`, owning every vertex of `tube` but its first ring and bottom
/// cap, which stay at rest: with `falloff` the sweep's deformation fades into them over a band of
/// that width. `keys` circular keys of `samples` radii from just below the second ring to the top.
pub fn attached_tube_rig(tube: &Tube, keys: usize, samples: usize, falloff: f64) -> Rig {
    let step = tube.length / (tube.rings - 1) as f64;
    let owned: Vec<u32> = (tube.around..tube.rings * tube.around).chain([tube.rings * tube.around + 1]).collect();
    let sweep = straight_sweep(tube, owned, (0.5 * step, tube.length), keys, samples, falloff);
    Rig::new(vec![sweep]).expect("a straight rig with distinct keys is valid")
}

/// A sweep named "tube" along `tube`'s axis owning the vertices `owned`: `keys` (at least two)
/// circular keys of `samples` radii, of the tube's radius, evenly spaced from z = `z0` to `z1`,
/// with falloff `falloff`.
pub fn straight_sweep(
    tube: &Tube,
    owned: Vec<u32>,
    (z0, z1): (f64, f64),
    keys: usize,
    samples: usize,
    falloff: f64,
) -> RigSweep {
    let keys = (0..keys)
        .map(|i| {
            let z = z0 + (z1 - z0) * i as f64 / (keys - 1) as f64;
            Key::circle(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY, tube.radius, samples)
        })
        .collect();
    RigSweep {
        name: "tube".to_string(),
        vertices: Some(VertexSelection::Indices(owned)),
        keys,
        knots: None,
        parent: None,
        falloff,
        rotation: Default::default(),
    }
}

/// A rig of two sweeps, `lower` and `upper`, splitting `tube` at its middle (the middle ring
/// and below to `lower`), each of `keys` circular keys over its half and with falloff
/// `falloff`: with falloff the two blend into each other over a band of that width on each
/// side of the joint.
pub fn split_tube_rig(tube: &Tube, keys: usize, samples: usize, falloff: f64) -> Rig {
    let middle = (tube.rings - 1) / 2;
    let z_middle = tube.length * middle as f64 / (tube.rings - 1) as f64;
    let (bottom, top) = (tube.rings * tube.around, tube.rings * tube.around + 1);
    let lower: Vec<u32> = (0..(middle + 1) * tube.around).chain([bottom]).collect();
    let upper: Vec<u32> = ((middle + 1) * tube.around..tube.rings * tube.around).chain([top]).collect();
    let half = |name: &str, vertices: Vec<u32>, z0: f64, z1: f64| {
        let keys = (0..keys)
            .map(|i| {
                let z = z0 + (z1 - z0) * i as f64 / (keys - 1) as f64;
                Key::circle(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY, tube.radius, samples)
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
    };
    Rig::new(vec![half("lower", lower, 0.0, z_middle), half("upper", upper, z_middle, tube.length)])
        .expect("two straight rigs with distinct keys are valid")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn tube_is_closed_and_outward() {
        let tube = Tube { rings: 40, around: 64, length: 3.0, radius: 0.5 };
        let mesh = tube.mesh();
        assert_eq!(mesh.positions.len(), tube.vertex_count());
        // The inscribed prism's volume: n/2·r²·sin(2π/n)·L.
        let exact = 64.0 / 2.0 * 0.25 * (TAU / 64.0).sin() * 3.0;
        let volume = mesh.enclosed_volume(&mesh.positions);
        assert!(((volume - exact) / exact).abs() < 1e-12, "{volume} vs {exact}");
        assert!(volume < PI * 0.25 * 3.0);
    }

    #[test]
    fn rig_owns_every_vertex() {
        let tube = Tube { rings: 4, around: 8, length: 1.0, radius: 0.2 };
        let rig = tube_rig(&tube, 3, 8);
        let owners = rig.owners(&tube.mesh(), "tube").unwrap();
        assert!(owners.iter().all(|&o| o == 0));
    }

    #[test]
    fn split_tube_rig_owns_every_vertex_once() {
        let tube = Tube { rings: 9, around: 8, length: 2.0, radius: 0.2 };
        let rig = split_tube_rig(&tube, 4, 8, 0.3);
        let owners = rig.owners(&tube.mesh(), "tube").unwrap();
        assert!(owners.iter().all(|&o| o == 0 || o == 1));
        assert_eq!(owners.iter().filter(|&&o| o == 0).count(), 5 * 8 + 1);
    }
}
