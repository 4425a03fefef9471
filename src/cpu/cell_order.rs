//! Twin of `shaders/cell_order.wgsl`: the cell groups of one chunk's vertices, sorted by cell
//! within blocks of consecutive vertices.

use crate::coeffs::{BAND_FLAG, CELL_GROUP, GpuBinding, UNOWNED};

/// The fewest vertices of a block. Within a block the groups leave the vertex order; across
/// blocks they keep it: on lavapipe, blocks of 256 vertices (3 KB of positions) deform a tube at
/// 1.3× the copy kernel's time against 1.8× for one block (each cell's vertices strided across
/// the whole mesh).
pub const MIN_BLOCK: u32 = 256;

/// Vertices of a block for a rig of `cells` cells a pose: at least [`MIN_BLOCK`], and at least
/// `cells` so that the buckets, `cells` a block, number about one a vertex at most.
pub fn block_size(cells: u32) -> u32 {
    cells.next_power_of_two().max(MIN_BLOCK)
}

/// Buckets (a block's cell each) of `vertices` vertices over `cells` cells, block-major.
pub fn bucket_count(vertices: u32, cells: u32) -> u64 {
    vertices.div_ceil(block_size(cells)) as u64 * cells as u64
}

/// Slots of the groups of `vertices` vertices over `cells` cells: every vertex, and at most
/// `CELL_GROUP − 1` free slots for each bucket (a block's cell) that has vertices.
pub fn group_slots(vertices: u32, cells: u32) -> u64 {
    let block = block_size(cells);
    let (full, rest) = (vertices / block, vertices % block);
    let buckets = full as u64 * cells.min(block) as u64 + cells.min(rest) as u64;
    let group = CELL_GROUP as u64;
    (vertices as u64 + buckets * (group - 1)).div_ceil(group) * group
}

/// The cell a vertex bound by `binding` is grouped under, or `None` for a vertex in a falloff
/// band ([`BAND_FLAG`] set: the band kernel moves it), an unbound one ([`UNOWNED`], which has
/// the flag too) or a cell past `cells`.
pub fn grouped_cell(binding: &GpuBinding, cells: u32) -> Option<u32> {
    debug_assert!(cells <= BAND_FLAG);
    (binding.cell < cells).then_some(binding.cell)
}

/// The kernels' groups, each bucket's vertices in ascending order (the GPU's scatter places a
/// bucket's vertices in its slots in whatever order its atomics run): [`group_slots`] entries,
/// the buckets (block-major, then cell) one after the other, each rounded up to a multiple of
/// [`CELL_GROUP`], the free slots of a group holding its first vertex, and the slots past the
/// last bucket's [`UNOWNED`].
pub fn cell_groups(bindings: &[GpuBinding], cells: u32) -> Vec<u32> {
    let block = block_size(cells) as usize;
    let bucket_of = |i: usize| grouped_cell(&bindings[i], cells).map(|cell| i / block * cells as usize + cell as usize);
    let mut counts = vec![0u32; bucket_count(bindings.len() as u32, cells) as usize];
    for i in 0..bindings.len() {
        if let Some(bucket) = bucket_of(i) {
            counts[bucket] += 1;
        }
    }
    let mut cursors = Vec::with_capacity(counts.len());
    let mut slot = 0;
    for &count in &counts {
        cursors.push(slot);
        slot += count.next_multiple_of(CELL_GROUP);
    }
    let mut groups = vec![UNOWNED; group_slots(bindings.len() as u32, cells) as usize];
    for i in 0..bindings.len() {
        if let Some(bucket) = bucket_of(i) {
            groups[cursors[bucket] as usize] = i as u32;
            cursors[bucket] += 1;
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
    fn blocks_keep_the_vertex_order_between_them() {
        // Two cells alternating over two blocks: each block's cell 0 vertices, then its cell 1
        // vertices; the second block's after the first's.
        let n = 2 * MIN_BLOCK;
        let bindings: Vec<GpuBinding> = (0..n).map(|i| bound(i % 2)).collect();
        let groups = cell_groups(&bindings, 2);
        let half = MIN_BLOCK as usize / 2;
        let expected: Vec<u32> = [0, 1, MIN_BLOCK, MIN_BLOCK + 1]
            .iter()
            .flat_map(|&start| (0..half as u32).map(move |k| start + 2 * k))
            .collect();
        assert_eq!(&groups[..expected.len()], &expected[..]);
        assert!(groups[expected.len()..].iter().all(|&v| v == UNOWNED));
    }

    #[test]
    fn slots_bound_the_padding_by_buckets() {
        assert_eq!(group_slots(0, 10), 0);
        // One vertex a cell, four cells: four groups.
        assert_eq!(group_slots(4, 4), 16);
        // Many vertices over few cells: the vertices and three free slots a bucket, two cells
        // in each of four blocks of 256 and in a fifth of 16 vertices, in whole groups.
        assert_eq!(group_slots(1040, 2), (1040 + 3 * 10usize).next_multiple_of(4) as u64);
        assert_eq!(block_size(1000), 1024);
        // A cell index past the rig's cells is in no group, nor is a band vertex.
        assert_eq!(cell_groups(&[bound(5), bound(1 | BAND_FLAG)], 3), vec![UNOWNED; 8]);
    }
}
