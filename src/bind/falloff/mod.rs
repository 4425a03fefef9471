//! Falloff weights (rig field `falloff`): how much of its own sweep's deformation each owned
//! vertex near its part's boundary follows, computed once at bind time.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind** (falloff weights) → deform → normals
//! → output.

use crate::bind::UNOWNED;

/// A vertex in a falloff band and what its deformation fades into.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandWeight {
    /// The vertex, an index into the mesh's positions.
    pub vertex: u32,
    /// w ∈ [0, 1): the share of its own sweep's deformation the vertex follows.
    pub weight: f64,
    /// The sweep whose deformation the rest (1 − w) comes from, or [`UNOWNED`]: the rest position.
    pub neighbour: u32,
}

impl BandWeight {
    /// Whether the vertex fades into the rest position rather than a neighbouring sweep.
    pub fn fades_to_rest(&self) -> bool {
        self.neighbour == UNOWNED
    }
}
