//! Twin of `shaders/cell_order.wgsl`: the cell groups of one chunk's vertices.

use crate::coeffs::{BAND_FLAG, CELL_GROUP, GpuBinding, UNOWNED};

/// Slots of the groups of `vertices` vertices over `cells` cells: every vertex, and at most
/// `CELL_GROUP − 1` free slots for each cell that has vertices, rounded up to whole groups.
pub fn group_slots(vertices: u32, cells: u32) -> u64 {
    let group = CELL_GROUP as u64;
    (vertices as u64 + vertices.min(cells) as u64 * (group - 1)).div_ceil(group) * group
}

/// The cell a vertex bound by `binding` is grouped under, or `None` for a vertex in a falloff
/// band ([`BAND_FLAG`] set: the band kernel moves it), an unbound one ([`UNOWNED`], which has
/// the flag too) or a cell past `cells`.
pub fn grouped_cell(binding: &GpuBinding, cells: u32) -> Option<u32> {
    debug_assert!(cells <= BAND_FLAG);
    (binding.cell < cells).then_some(binding.cell)
}

/// The kernels' groups, each cell's vertices in ascending order (the GPU's scatter places a
/// cell's vertices in its slots in whatever order its atomics run): [`group_slots`] entries,
/// each cell's slots starting where the previous cell's end, each cell's rounded up to a multiple
/// of [`CELL_GROUP`], the free slots of a group holding its first vertex, and the slots past the
/// last cell's [`UNOWNED`].
pub fn cell_groups(bindings: &[GpuBinding], cells: u32) -> Vec<u32> {
    let mut counts = vec![0u32; cells as usize];
    for binding in bindings {
        if let Some(cell) = grouped_cell(binding, cells) {
            counts[cell as usize] += 1;
        }
    }
    let mut cursors = Vec::with_capacity(counts.len());
    let mut slot = 0;
    for &count in &counts {
        cursors.push(slot);
        slot += count.next_multiple_of(CELL_GROUP);
    }
    let mut groups = vec![UNOWNED; group_slots(bindings.len() as u32, cells) as usize];
    for (i, binding) in bindings.iter().enumerate() {
        if let Some(cell) = grouped_cell(binding, cells) {
            groups[cursors[cell as usize] as usize] = i as u32;
            cursors[cell as usize] += 1;
        }
    }
    for group in groups.chunks_mut(CELL_GROUP as usize) {
        let first = group[0];
        for slot in group.iter_mut().filter(|slot| **slot == UNOWNED) {
            *slot = first;
        }
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bound(cell: u32) -> GpuBinding {
        GpuBinding { cell, s: 0.5, phi: 0.5, d: 0.0, h: 0.0 }
    }

    #[test]
    fn groups_hold_each_cell_s_vertices_padded_to_whole_groups() {
        // Cell 2: five vertices and one in a band; cell 0: one; cell 1: none; one unbound vertex.
        let cells = [2, 0, 2, UNOWNED, 2 | BAND_FLAG, 2, 2, 2];
        let bindings: Vec<GpuBinding> = cells.iter().map(|&c| bound(c)).collect();
        let groups = cell_groups(&bindings, 3);
        assert_eq!(groups.len() as u64, group_slots(8, 3));
        assert_eq!(&groups[..12], &[1, 1, 1, 1, 0, 2, 5, 6, 7, 7, 7, 7]);
        assert!(groups[12..].iter().all(|&v| v == UNOWNED));
        // Every group's vertices share its first vertex's cell.
        for group in groups.chunks(CELL_GROUP as usize).filter(|g| g[0] != UNOWNED) {
            let cell = grouped_cell(&bindings[group[0] as usize], 3);
            assert!(cell.is_some());
            assert!(group.iter().all(|&v| grouped_cell(&bindings[v as usize], 3) == cell));
        }
    }

    #[test]
    fn slots_bound_the_padding_by_vertices_and_cells() {
        assert_eq!(group_slots(0, 10), 0);
        // One vertex a cell, four cells: four groups.
        assert_eq!(group_slots(4, 4), 16);
        // Many vertices over few cells: the vertices and three free slots a cell.
        assert_eq!(group_slots(1000, 2), 1008);
        // A cell index past the rig's cells is in no group, nor is a band vertex.
        assert_eq!(cell_groups(&[bound(5), bound(1 | BAND_FLAG)], 3), vec![UNOWNED; 8]);
    }
}
