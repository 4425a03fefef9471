//! Bindings of a whole mesh with falloff bands (rig field `falloff`): one [`Binding`] per
//! vertex, plus, for each vertex in a band, its weight w and its second influence (the
//! neighbouring sweep's binding of the same vertex, or the rest position).
//!
//! A vertex with weight w follows its own sweep part of the way, w = 1 being Eq. 2 exactly and
//! w = 0 its second influence exactly; [`crate::deform`] blends the two influences' frames.

use glam::DVec3;

use super::falloff::{BandWeight, band_weights};
use super::{Binding, SweepBinder, UNOWNED, bind_vertices};
use crate::mesh::Faces;
use crate::sweep::Sweep;

/// A vertex in a falloff band: how much of its own sweep it follows, and what else.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandBinding {
    /// The vertex, an index into the mesh's positions; its own binding is the mesh's.
    pub vertex: u32,
    /// w ∈ [0, 1): the share of its own sweep's deformation it follows.
    pub weight: f64,
    /// The second influence: the vertex bound to the neighbouring sweep, or
    /// [`Binding::UNOWNED`] for the rest position.
    pub second: Binding,
}

/// Every vertex's binding and the falloff bands, sorted by vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshBindings {
    /// One binding per vertex, in mesh order.
    pub vertices: Vec<Binding>,
    /// The vertices with w < 1, sorted by vertex, each listed once.
    pub bands: Vec<BandBinding>,
}

impl MeshBindings {
    /// Bindings without falloff: every owned vertex follows its sweep fully.
    pub fn hard(vertices: Vec<Binding>) -> MeshBindings {
        MeshBindings { vertices, bands: Vec::new() }
    }

    /// Binds every owned vertex (`owners[i]` indexes `rest`, or is [`UNOWNED`]) and computes the
    /// falloff bands of the sweeps with `falloff[s] > 0` along the surface of `faces`; a band
    /// vertex that fades into a neighbouring sweep is bound to that sweep too. `progress` is
    /// called with the number of vertices just bound, as in [`bind_vertices`].
    pub fn bind(
        rest: &[Sweep],
        falloff: &[f64],
        owners: &[u32],
        positions: &[DVec3],
        faces: &Faces,
        progress: &(dyn Fn(usize) + Sync),
    ) -> MeshBindings {
        let vertices = bind_vertices(rest, owners, positions, progress);
        let weights = band_weights(faces, positions, owners, falloff);
        MeshBindings { vertices, bands: bind_bands(rest, positions, &weights) }
    }

    /// Whether vertex `i` keeps its rest position exactly: unowned, or in a band at weight 0
    /// against the rest position.
    pub fn keeps_rest(&self) -> Vec<bool> {
        let mut keeps: Vec<bool> = self.vertices.iter().map(|b| b.sweep == UNOWNED).collect();
        for band in &self.bands {
            keeps[band.vertex as usize] = band.weight == 0.0 && band.second.sweep == UNOWNED;
        }
        keeps
    }

    /// Whether some vertex is in a falloff band.
    pub fn has_bands(&self) -> bool {
        !self.bands.is_empty()
    }

    /// Each vertex's weight w: 1 for owned vertices outside bands, 0 for unowned vertices.
    pub fn weights(&self) -> Vec<f64> {
        let mut weights: Vec<f64> = self.vertices.iter().map(|b| if b.sweep == UNOWNED { 0.0 } else { 1.0 }).collect();
        for band in &self.bands {
            weights[band.vertex as usize] = band.weight;
        }
        weights
    }
}

/// The band bindings of `weights` ([`band_weights`]): each band vertex that fades into a
/// neighbouring sweep bound to that sweep (f64 reference).
pub fn bind_bands(rest: &[Sweep], positions: &[DVec3], weights: &[BandWeight]) -> Vec<BandBinding> {
    let mut binders: Vec<Option<SweepBinder>> = vec![None; rest.len()];
    weights
        .iter()
        .map(|band| {
            let second = if band.fades_to_rest() {
                Binding::UNOWNED
            } else {
                let s = band.neighbour as usize;
                let binder = binders[s].get_or_insert_with(|| SweepBinder::new(&rest[s]));
                Binding { sweep: band.neighbour, params: binder.bind(positions[band.vertex as usize]) }
            };
            BandBinding { vertex: band.vertex, weight: band.weight, second }
        })
        .collect()
}
