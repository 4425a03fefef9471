//! The copies of a vertex along an unwelded seam: vertices at one position (bit for bit) that
//! no edge joins, as along the patch seams of the Newell teapot or the UV seams an exporter
//! splits a mesh at. The march sees only edges, so without this each copy would take its
//! distance from its own side alone, and a part whose selection ends along a seam would find
//! no boundary there: the copies would get different weights and part when deformed.
//!
//! - Copies owned by one banded sweep march as one vertex, the first of them, and share its
//!   distance and label.
//! - A copy whose twin at its position has another owner (the part's selection ends along the
//!   seam) is a boundary vertex of its part facing that owner, as if an edge joined them.
//!
//! Such copies lie on an open boundary of the mesh ([`Corners::on_open_boundary`]), so only
//! the banded vertices there are looked up, then every vertex at their positions.

use std::collections::HashMap;

use glam::DVec3;

use super::corners::Corners;
use crate::mesh::weld::{PositionMap, position_key};

/// The seams of a mesh's banded parts.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct Seams {
    /// For each vertex, the vertex it marches as: itself, or the first banded copy at its
    /// position with its owner.
    pub first: Vec<u32>,
    /// For a vertex that marches (a `first`), the owners of the copies at its position that
    /// have another owner, each copy once, increasing.
    pub across: HashMap<u32, Vec<u32>>,
}

impl Seams {
    /// Whether some copies march as one.
    pub(super) fn joins(&self) -> bool {
        self.first.iter().enumerate().any(|(v, &first)| first as usize != v)
    }
}

/// The seams among the `active` (banded) vertices; `None` where no banded vertex on an open
/// boundary shares its position with another vertex.
pub(super) fn seams(corners: &Corners, positions: &[DVec3], owners: &[u32], active: &[bool]) -> Option<Seams> {
    let open: Vec<bool> = (0..active.len()).map(|v| active[v] && corners.on_open_boundary(v)).collect();
    if !open.contains(&true) {
        return None;
    }
    let mut at: PositionMap<[u64; 3], Vec<u32>> = PositionMap::default();
    for v in (0..open.len()).filter(|&v| open[v]) {
        at.entry(position_key(positions[v])).or_default().push(v as u32);
    }
    for (v, &p) in positions.iter().enumerate() {
        if !open[v]
            && let Some(copies) = at.get_mut(&position_key(p))
        {
            copies.push(v as u32);
        }
    }
    let mut first: Vec<u32> = (0..positions.len() as u32).collect();
    let mut across: HashMap<u32, Vec<u32>> = HashMap::new();
    for copies in at.values_mut().filter(|copies| copies.len() > 1) {
        copies.sort_unstable();
        for &v in copies.iter().filter(|&&v| active[v as usize]) {
            let owner = owners[v as usize];
            let same = copies.iter().copied().find(|&u| active[u as usize] && owners[u as usize] == owner);
            first[v as usize] = same.unwrap_or(v);
            if first[v as usize] == v {
                let mut others: Vec<u32> =
                    copies.iter().map(|&u| owners[u as usize]).filter(|&other| other != owner).collect();
                others.sort_unstable();
                if !others.is_empty() {
                    across.insert(v, others);
                }
            }
        }
    }
    let seams = Seams { first, across };
    (seams.joins() || !seams.across.is_empty()).then_some(seams)
}
