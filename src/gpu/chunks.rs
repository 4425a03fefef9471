//! Splitting a mesh's vertices into dispatches that respect the device's limits: no storage
//! binding larger than `max_storage_buffer_binding_size` (128 MiB on lavapipe), no buffer larger
//! than `max_buffer_size`, binding offsets aligned to `min_storage_buffer_offset_alignment`,
//! and at most `max_compute_workgroups_per_dimension` workgroups along x (the rest go along y).

use std::ops::Range;

use crate::coeffs::WORKGROUP_SIZE;

/// The device limits that shape the chunks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkLimits {
    /// Largest storage binding, bytes.
    pub max_binding: u64,
    /// Largest buffer, bytes.
    pub max_buffer: u64,
    /// Required alignment of storage binding offsets, bytes.
    pub offset_alignment: u64,
    /// Largest workgroup count along one dimension.
    pub max_workgroups: u32,
}

impl ChunkLimits {
    /// The limits of a device.
    pub fn of(limits: &wgpu::Limits) -> ChunkLimits {
        ChunkLimits {
            max_binding: limits.max_storage_buffer_binding_size,
            max_buffer: limits.max_buffer_size,
            offset_alignment: limits.min_storage_buffer_offset_alignment as u64,
            max_workgroups: limits.max_compute_workgroups_per_dimension,
        }
    }

    /// Chunk starts are multiples of this many vertices, so that a window of any per-vertex
    /// stream whose stride is a multiple of 4 bytes starts on an aligned offset.
    fn granule(&self) -> u32 {
        (self.offset_alignment / 4).max(1) as u32
    }

    /// The most bytes one per-chunk buffer or binding may hold.
    fn max_chunk_bytes(&self) -> u64 {
        self.max_binding.min(self.max_buffer)
    }
}

/// Consecutive vertex ranges covering `0..vertex_count`, each small enough that a per-vertex
/// stream of `stride` bytes fits one binding, and starting on aligned offsets.
pub fn uniform_chunks(vertex_count: u32, stride: u64, limits: &ChunkLimits) -> Vec<Range<u32>> {
    let granule = limits.granule();
    let fit = (limits.max_chunk_bytes() / stride).min(u32::MAX as u64) as u32;
    let cap = (fit / granule * granule).max(granule);
    (0..vertex_count.div_ceil(cap)).map(|c| c * cap..((c + 1) * cap).min(vertex_count)).collect()
}

/// Bound vertices closer than this are dispatched together (the unbound ones between them are
/// skipped by the kernel), so that a scattered rig does not make many tiny dispatches.
pub const MERGE_GAP: u32 = 4096;

/// Vertex ranges covering every vertex with `bound[v]` and as few others as alignment and
/// [`MERGE_GAP`] allow, sorted, each starting on an aligned offset and small enough that a stream
/// of `stride` bytes a vertex fits one binding, as [`uniform_chunks`]'. Empty if nothing is
/// bound.
pub fn bound_chunks(bound: &[bool], stride: u64, limits: &ChunkLimits) -> Vec<Range<u32>> {
    let granule = limits.granule();
    let n = bound.len() as u32;
    let mut runs: Vec<Range<u32>> = Vec::new();
    let mut v = 0u32;
    while v < n {
        if !bound[v as usize] {
            v += 1;
            continue;
        }
        let start = v;
        while v < n && bound[v as usize] {
            v += 1;
        }
        let (start, end) = (start / granule * granule, v.next_multiple_of(granule).min(n));
        match runs.last_mut() {
            Some(last) if start <= last.end.saturating_add(MERGE_GAP) => last.end = end,
            _ => runs.push(start..end),
        }
    }
    let fit = (limits.max_chunk_bytes() / stride).min(u32::MAX as u64) as u32;
    let cap = (fit / granule * granule).max(granule);
    runs.into_iter()
        .flat_map(|run| {
            (0..run.len().div_ceil(cap as usize) as u32)
                .map(move |c| run.start + c * cap..(run.start + (c + 1) * cap).min(run.end))
        })
        .collect()
}

/// Consecutive vertex ranges for the normals kernel: each chunk's rows of the adjacency
/// (`offsets`, one more entry than vertices; `entry_bytes` per adjacency entry), its own
/// offsets and its window of the normals (12 bytes a vertex) each fit one binding. `None` if a
/// single vertex has more adjacency entries than one binding holds.
pub fn normal_chunks(offsets: &[u32], entry_bytes: u64, limits: &ChunkLimits) -> Option<Vec<Range<u32>>> {
    let vertex_count = (offsets.len() - 1) as u32;
    let granule = limits.granule();
    let budget = limits.max_chunk_bytes();
    let vertex_cap = (budget / 12).min((budget / 4).saturating_sub(1)).min(u32::MAX as u64) as u32;
    let mut chunks = Vec::new();
    let mut start = 0u32;
    while start < vertex_count {
        let limit = start.saturating_add(vertex_cap).min(vertex_count);
        let max_entry = offsets[start as usize] as u64 + budget / entry_bytes;
        // The last end ≤ limit whose rows still fit: offsets is non-decreasing.
        let fitting = offsets[start as usize..=limit as usize].partition_point(|&o| o as u64 <= max_entry) as u32;
        let mut end = start + fitting.saturating_sub(1);
        if end < vertex_count {
            end = start + (end - start) / granule * granule;
        }
        if end == start {
            return None;
        }
        chunks.push(start..end);
        start = end;
    }
    Some(chunks)
}

/// The workgroup grid `(x, y)` covering `vertices` threads: x up to the device's limit, y as
/// many rows as needed. The kernels recover the linear index as (y·x_count + x)·size + lane.
pub fn dispatch_grid(vertices: u32, limits: &ChunkLimits) -> (u32, u32) {
    let groups = vertices.div_ceil(WORKGROUP_SIZE).max(1);
    let x = groups.min(limits.max_workgroups);
    (x, groups.div_ceil(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAVAPIPE: ChunkLimits = ChunkLimits {
        max_binding: 128 << 20,
        max_buffer: u32::MAX as u64,
        offset_alignment: 256,
        max_workgroups: 65535,
    };

    #[test]
    fn sixteen_million_vertices_split_into_aligned_chunks_within_the_binding_limit() {
        let n = 16 << 20;
        let chunks = uniform_chunks(n, 20, &LAVAPIPE);
        assert!(chunks.len() >= 3);
        assert_eq!(chunks.first().unwrap().start, 0);
        assert_eq!(chunks.last().unwrap().end, n);
        for pair in chunks.windows(2) {
            assert_eq!(pair[0].end, pair[1].start);
        }
        for chunk in &chunks {
            assert!((chunk.len() as u64) * 20 <= LAVAPIPE.max_binding);
            assert_eq!((chunk.start as u64 * 12) % 256, 0, "positions window offset");
        }
    }

    #[test]
    fn bound_chunks_cover_the_bound_runs_aligned_and_merge_close_ones() {
        let limits = ChunkLimits { offset_alignment: 256, ..LAVAPIPE };
        let mut bound = vec![false; 100_000];
        bound[1000..1100].fill(true);
        bound[3000..3010].fill(true); // within MERGE_GAP of the first run
        bound[50_000..50_001].fill(true);
        let chunks = bound_chunks(&bound, 20, &limits);
        assert_eq!(chunks, vec![960..3008 + 64, 49_984..50_048]);
        for (v, _) in bound.iter().enumerate().filter(|(_, b)| **b) {
            assert!(chunks.iter().any(|c| c.contains(&(v as u32))), "vertex {v}");
        }
        assert!(bound_chunks(&[false; 10], 20, &limits).is_empty());
        assert_eq!(bound_chunks(&[true; 10], 20, &limits), vec![0..10]);
    }

    #[test]
    fn bound_chunks_split_a_long_run_within_the_binding_limit() {
        let limits = ChunkLimits { max_binding: 64 * 20 * 10, ..LAVAPIPE };
        let chunks = bound_chunks(&vec![true; 10_000], 20, &limits);
        assert_eq!(chunks.first().unwrap().start, 0);
        assert_eq!(chunks.last().unwrap().end, 10_000);
        assert!(chunks.iter().all(|c| c.len() as u64 * 20 <= limits.max_binding && c.start % 64 == 0));
    }

    #[test]
    fn small_mesh_is_one_chunk() {
        assert_eq!(uniform_chunks(1000, 20, &LAVAPIPE), vec![0..1000]);
    }

    #[test]
    fn grid_goes_two_dimensional_past_the_workgroup_limit() {
        let (x, y) = dispatch_grid(16 << 20, &LAVAPIPE);
        assert_eq!(x, 65535);
        assert!(x as u64 * y as u64 * WORKGROUP_SIZE as u64 >= 16 << 20);
        assert_eq!(dispatch_grid(WORKGROUP_SIZE + 1, &LAVAPIPE), (2, 1));
    }

    #[test]
    fn normal_chunks_respect_the_adjacency_budget() {
        // Six entries per vertex, 8 bytes each, with a 4 KiB binding limit.
        let limits = ChunkLimits { max_binding: 4096, ..LAVAPIPE };
        let offsets: Vec<u32> = (0..=1000).map(|i| 6 * i).collect();
        let chunks = normal_chunks(&offsets, 8, &limits).unwrap();
        assert_eq!(chunks.last().unwrap().end, 1000);
        for chunk in &chunks {
            let entries = (offsets[chunk.end as usize] - offsets[chunk.start as usize]) as u64;
            assert!(entries * 8 <= 4096, "{chunk:?}");
            assert_eq!(chunk.start % 64, 0);
        }
    }

    #[test]
    fn vertex_with_more_entries_than_a_binding_holds_is_refused() {
        let limits = ChunkLimits { max_binding: 64, ..LAVAPIPE };
        assert!(normal_chunks(&[0, 100], 8, &limits).is_none());
    }
}
