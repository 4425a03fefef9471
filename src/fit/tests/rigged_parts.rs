//! Reading a rig's parts in the autorig tests on characters: chains, their points, and the
//! mesh's own components.

use glam::DVec3;
use sweepffd::fit::autorig::{Autorig, RiggedPart};
use sweepffd::fit::disjoint_sets::DisjointSets;
use sweepffd::mesh::Mesh;

/// The chain of `limb`, a root part of `rigged`: the limb and its links, named after it.
pub(super) fn chain_of<'a>(rigged: &'a Autorig, limb: &RiggedPart) -> Vec<&'a RiggedPart> {
    let prefix = format!("{}.", limb.name);
    rigged.parts.iter().filter(|p| p.name == limb.name || p.name.starts_with(&prefix)).collect()
}

/// The positions of the vertices of every link of `chain`.
pub(super) fn chain_points(mesh: &Mesh, chain: &[&RiggedPart]) -> Vec<DVec3> {
    chain.iter().flat_map(|p| p.vertices.iter().map(|&v| mesh.positions[v as usize])).collect()
}

/// The mesh's components (joined by its faces, not welded), each its vertices increasing.
pub(super) fn components(mesh: &Mesh) -> Vec<Vec<u32>> {
    let mut sets = DisjointSets::new(mesh.positions.len());
    for t in mesh.faces.triangles() {
        for k in 1..3 {
            let (a, b) = (sets.root(t[0]), sets.root(t[k]));
            if a != b {
                sets.attach(b, a);
            }
        }
    }
    let mut by_root: std::collections::BTreeMap<u32, Vec<u32>> = Default::default();
    for v in 0..mesh.positions.len() as u32 {
        by_root.entry(sets.root(v)).or_default().push(v);
    }
    by_root.into_values().collect()
}
