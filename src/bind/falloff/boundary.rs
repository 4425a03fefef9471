//! The boundary of each part, where its falloff band starts (g = 0), and what lies beyond
//! each boundary vertex.

use std::collections::HashMap;

use super::corners::Corners;
use crate::bind::UNOWNED;

/// A boundary vertex of a part: g = 0 there, and `label` is what lies across the boundary,
/// [`UNOWNED`] (the rest position) or another sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Source {
    /// The boundary vertex.
    pub vertex: u32,
    /// The owner across the boundary.
    pub label: u32,
}

/// The boundary vertices of the parts of the `active` vertices, increasing: a vertex owned by
/// sweep s is on its part's boundary when it shares an edge of a triangle (of `corners`) with
/// a vertex not owned by s. Its label is [`boundary_label`] of the owners of those
/// neighbours, each neighbour counted once however many triangles share the edge, and of
/// `seam_owners[v]`: the other owners of its copies along an unwelded seam, which face it as
/// if an edge joined them.
pub(super) fn sources(
    corners: &Corners,
    owners: &[u32],
    active: &[bool],
    seam_owners: &HashMap<u32, Vec<u32>>,
) -> Vec<Source> {
    let mut sources = Vec::new();
    let mut across: Vec<u32> = Vec::new();
    for (v, _) in active.iter().enumerate().filter(|&(_, &active)| active) {
        let owner = owners[v];
        across.clear();
        for &pair in corners.of(v) {
            across.extend(pair.into_iter().filter(|&u| owners[u as usize] != owner));
        }
        across.sort_unstable();
        across.dedup();
        for u in &mut across {
            *u = owners[*u as usize];
        }
        across.extend(seam_owners.get(&(v as u32)).into_iter().flatten());
        if across.is_empty() {
            continue;
        }
        across.sort_unstable();
        sources.push(Source { vertex: v as u32, label: boundary_label(&across) });
    }
    sources
}

/// What a boundary vertex faces, from the owners of its neighbours across the boundary (one
/// entry per neighbour, sorted increasing, not empty): [`UNOWNED`] if any neighbour is
/// unowned, otherwise the sweep owning the most of them, the lower index on a tie.
pub(super) fn boundary_label(owners_across: &[u32]) -> u32 {
    if owners_across.last() == Some(&UNOWNED) {
        return UNOWNED;
    }
    let mut best = (UNOWNED, 0usize);
    for run in owners_across.chunk_by(|a, b| a == b) {
        if run.len() > best.1 {
            best = (run[0], run.len());
        }
    }
    best.0
}
