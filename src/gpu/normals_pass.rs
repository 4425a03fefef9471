//! The normals pass: area-weighted vertex normals of the deformed mesh, gathered per vertex
//! from its incident triangles (`shaders/normals.wgsl`), in chunks that respect the device's
//! binding limits.
//!
//! Every normal is computed once at creation, from the rest positions; per frame the pass
//! recomputes only the vertices with a vertex in their one-ring that a sweep owns
//! ([`dirty_vertices`]): the others cannot move, so their rest normals stay exact (to the bit:
//! the kernel and its inputs are the same). The stage serves `instances` copies of one mesh laid
//! out one after another in the position and normal buffers: instance k's vertex v is at
//! `k · vertex_count + v`.

use std::borrow::Cow;
use std::ops::Range;

use wgpu::util::DeviceExt;

use std::sync::Arc;

use super::InputError;
use super::buffers::{POSITION_STRIDE, check_fits, params_buffer, window};
use super::chunks::{ChunkLimits, dispatch_grid};
use super::kernels::Kernel;
use super::{GpuContext, GpuError};
use crate::coeffs::DispatchParams;
use crate::normals::{FAN_INDEX, NormalAdjacency, dirty_vertices, instanced};
use crate::parallel::prelude::*;

/// Vertices of a list whose fan rows one parallel task copies.
const LIST_BLOCK: usize = 8192;

/// One dispatch: its bind group and workgroup grid.
pub(crate) type Dispatch = (wgpu::BindGroup, (u32, u32));

/// A run of an ascending vertex list dispatched at once: `items` index the list, and `span` is
/// the window of the per-vertex buffers it reads and writes (starting on an aligned vertex,
/// ending after its last vertex).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ListChunk {
    pub(crate) items: Range<usize>,
    pub(crate) span: Range<u32>,
}

/// Splits `vertices` (ascending) into consecutive chunks such that in each, the window `span`
/// of a per-vertex stream of `stride` bytes, the chunk's list (4 bytes an entry), its rows of
/// offsets (one more) and its `row_entries` adjacency entries (4 bytes each) each fit one
/// binding, with `span` starting on an offset aligned for any stride that is a multiple of 4.
/// `None` if a single vertex does not fit.
pub(crate) fn list_chunks(
    vertices: &[u32],
    stride: u64,
    row_entries: impl Fn(u32) -> u64,
    limits: &ChunkLimits,
) -> Option<Vec<ListChunk>> {
    let granule = (limits.offset_alignment / 4).max(1) as u32;
    let budget = limits.max_binding.min(limits.max_buffer);
    let mut chunks = Vec::new();
    let mut a = 0;
    while a < vertices.len() {
        let lo = vertices[a] / granule * granule;
        let (mut b, mut entries) = (a, 0u64);
        while b < vertices.len() {
            let more = entries + row_entries(vertices[b]);
            let fits = (vertices[b] - lo + 1) as u64 * stride <= budget
                && (b - a + 2) as u64 * 4 <= budget
                && more * 4 <= budget;
            if !fits {
                break;
            }
            entries = more;
            b += 1;
        }
        if b == a {
            return None;
        }
        chunks.push(ListChunk { items: a..b, span: lo..vertices[b - 1] + 1 });
        a = b;
    }
    Some(chunks)
}

/// A storage buffer holding `bytes` (one unused word if empty: a binding may not be empty).
pub(crate) fn storage_init(device: &wgpu::Device, label: &str, words: &[u32]) -> wgpu::Buffer {
    let words: &[u32] = if words.is_empty() { &[0] } else { words };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::cast_slice(words),
        usage: wgpu::BufferUsages::STORAGE,
    })
}

/// Records `dispatches` of `kernel` into a compute pass of their own named `label`.
pub(crate) fn record(encoder: &mut wgpu::CommandEncoder, label: &str, kernel: &Kernel, dispatches: &[Dispatch]) {
    let mut pass =
        encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes: None });
    pass.set_pipeline(&kernel.pipeline);
    for (group, grid) in dispatches {
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(grid.0, grid.1, 1);
    }
}

/// The normals pass: its kernel, output buffer and per-frame dispatches over the vertices whose
/// one-ring moves.
#[derive(Debug)]
pub(crate) struct NormalsStage {
    pub(crate) kernel: Arc<Kernel>,
    pub(crate) buffer: wgpu::Buffer,
    /// The per-frame dispatches, over [`dirty`](Self::dirty) (less the vertices the deform
    /// kernel writes, with Jacobian normals).
    pub(crate) dispatches: Vec<Dispatch>,
    /// The vertices (all instances) recomputed per frame, ascending.
    pub(crate) dirty: Vec<u32>,
    /// The mesh's vertices whose normals can move, ascending (instance 0's `dirty`).
    moving: Vec<u32>,
    instances: u32,
    shape: NormalsShape,
    /// Device memory the stage keeps: the normals and the per-frame dispatches' lists.
    pub(crate) device_bytes: u64,
}

/// What the normal dispatches of one stage share.
struct NormalsPlan<'a> {
    kernel: &'a Kernel,
    adjacency: &'a NormalAdjacency,
    /// Vertices from one instance to the next.
    stride: u32,
    low: wgpu::BindingResource<'a>,
    high: wgpu::BindingResource<'a>,
    split: u32,
    normals: &'a wgpu::Buffer,
    limits: &'a ChunkLimits,
}

impl NormalsStage {
    /// Plans the normals of `instances` copies of the mesh of `adjacency` over `vertex_count`
    /// vertices each, `stride` vertices apart (instance k's vertex v at k · stride + v), read
    /// from `positions` from byte `positions_base` on; `moves[v]` says whether vertex v of the
    /// mesh can move (a sweep owns it). Records the pass over every vertex (the rest normals)
    /// into `encoder`; the stage's own dispatches then cover only the vertices whose normal can
    /// change, less those for which `by_deform` is true (the deform kernel writes their normals
    /// through its Jacobian; [`restrict`](Self::restrict) changes them).
    #[expect(clippy::too_many_arguments, reason = "the stage's inputs, each used once")]
    pub(crate) fn new(
        context: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        adjacency: &NormalAdjacency,
        (positions, positions_base): (&wgpu::Buffer, u64),
        (vertex_count, stride): (u32, u32),
        instances: u32,
        (moves, by_deform): (&[bool], Option<&[bool]>),
        limits: &ChunkLimits,
    ) -> Result<NormalsStage, GpuError> {
        let device = &context.device;
        let total = (instances.max(1) as u64 - 1) * stride as u64 + vertex_count as u64;
        if total > FAN_INDEX as u64 {
            return Err(InputError::TooManyNormalVertices { vertices: total }.into());
        }
        let total = total as u32;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd normals"),
            size: total as u64 * POSITION_STRIDE,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let shape = NormalsShape { positions: positions.clone(), positions_base, stride, total, limits: *limits };
        let kernel = context.kernels().normals(device, shape.split() < total);
        let plan = shape.plan(&kernel, adjacency, &buffer)?;
        // A vertex without incident triangles keeps the zero the buffer starts with; the kernel
        // reads a row up to its FAN_END, so it is given only non-empty rows.
        let with_triangles: Vec<u32> =
            (0..vertex_count).filter(|&v| !adjacency.fans_of(v as usize).is_empty()).collect();
        let every = instanced(&with_triangles, stride, instances.max(1));
        let moving = dirty_vertices(adjacency, |v| moves[v]);
        let dirty = instanced(&moving, stride, instances.max(1));
        let (dispatches, list_bytes) = match by_deform {
            None => plan.dispatches(device, &dirty)?,
            Some(by_deform) => {
                let faced: Vec<u32> = moving.iter().copied().filter(|&v| !by_deform[v as usize]).collect();
                plan.dispatches(device, &instanced(&faced, stride, instances.max(1)))?
            }
        };
        // A rig moving every vertex recomputes the rest pass's list each frame: its dispatches
        // serve both, their lists built and uploaded once.
        match by_deform.is_none() && dirty == every {
            true => record(encoder, "sweepffd rest normals", &kernel, &dispatches),
            false => record(encoder, "sweepffd rest normals", &kernel, &plan.dispatches(device, &every)?.0),
        }
        let device_bytes = buffer.size() + list_bytes;
        Ok(NormalsStage { kernel, buffer, dispatches, dirty, moving, instances, shape, device_bytes })
    }

    /// Makes the per-frame dispatches cover the moving vertices less those for which
    /// `by_deform` is true (decided after creation, by the Jacobian probe on the GPU).
    pub(crate) fn restrict(
        &mut self,
        device: &wgpu::Device,
        adjacency: &NormalAdjacency,
        by_deform: &[bool],
    ) -> Result<(), GpuError> {
        let plan = self.shape.plan(&self.kernel, adjacency, &self.buffer)?;
        let faced: Vec<u32> = self.moving.iter().copied().filter(|&v| !by_deform[v as usize]).collect();
        let (dispatches, list_bytes) =
            plan.dispatches(device, &instanced(&faced, self.shape.stride, self.instances.max(1)))?;
        self.dispatches = dispatches;
        self.device_bytes = self.buffer.size() + list_bytes;
        Ok(())
    }

    /// Bytes a frame's pass reads and writes, each buffer counted once: its lists, and the
    /// position read and the normal written of each vertex it recomputes.
    #[cfg(feature = "bench")]
    pub(crate) fn frame_bytes(&self) -> u64 {
        let lists = self.device_bytes - self.buffer.size();
        lists + self.dirty.len() as u64 * 2 * POSITION_STRIDE
    }
}

/// Where a normals pass reads its positions, and how its vertices are laid out.
#[derive(Clone, Debug)]
pub(crate) struct NormalsShape {
    pub(crate) positions: wgpu::Buffer,
    /// Byte of vertex 0 in `positions`.
    pub(crate) positions_base: u64,
    /// Vertices from one instance to the next.
    pub(crate) stride: u32,
    /// Vertices of every instance.
    pub(crate) total: u32,
    pub(crate) limits: ChunkLimits,
}

impl NormalsShape {
    /// The first vertex read through the second position window: positions are read at any
    /// index, through two windows of at most one binding each; the second starts at a multiple
    /// of 64 vertices (768 bytes), aligned for any device.
    fn split(&self) -> u32 {
        let limits = &self.limits;
        (limits.max_binding.min(limits.max_buffer) / POSITION_STRIDE / 64 * 64).min(self.total as u64) as u32
    }

    /// The plan of dispatches of `kernel` over `adjacency` writing `normals`.
    fn plan<'a>(
        &'a self,
        kernel: &'a Kernel,
        adjacency: &'a NormalAdjacency,
        normals: &'a wgpu::Buffer,
    ) -> Result<NormalsPlan<'a>, GpuError> {
        let (split, total) = (self.split(), self.total);
        check_fits(
            "the normals' second position window",
            (total - split) as u64 * POSITION_STRIDE,
            self.limits.max_binding,
        )?;
        let (positions, base) = (&self.positions, self.positions_base);
        Ok(NormalsPlan {
            kernel,
            adjacency,
            stride: self.stride,
            low: based(positions, base, 0..split.max(1)),
            high: if split < total {
                based(positions, base, split..total)
            } else {
                based(positions, base, 0..split.max(1))
            },
            split,
            normals,
            limits: &self.limits,
        })
    }

    /// Records the normals kernel over `vertices` (ascending, each with an incident triangle)
    /// of these positions into `normals`, laid out as the positions from byte 0.
    pub(crate) fn record(
        &self,
        context: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        adjacency: &NormalAdjacency,
        normals: &wgpu::Buffer,
        vertices: &[u32],
    ) -> Result<(), GpuError> {
        let kernel = context.kernels().normals(&context.device, self.split() < self.total);
        let plan = self.plan(&kernel, adjacency, normals)?;
        record(encoder, "sweepffd normals", &kernel, &plan.dispatches(&context.device, vertices)?.0);
        Ok(())
    }
}

impl NormalsPlan<'_> {
    /// The dispatches computing the normals of `vertices` (ascending, over all instances, each
    /// with at least one incident triangle), and the bytes of the vertex, offset and fan lists
    /// they bind.
    fn dispatches(&self, device: &wgpu::Device, vertices: &[u32]) -> Result<(Vec<Dispatch>, u64), GpuError> {
        let n = self.stride;
        let row = |g: u32| self.adjacency.fans_of((g % n) as usize).len() as u64;
        let chunks = list_chunks(vertices, POSITION_STRIDE, row, self.limits).ok_or(InputError::TriangleFanTooLarge)?;
        let mut list_bytes = 0u64;
        let dispatches = chunks
            .iter()
            .map(|chunk| {
                let list = &vertices[chunk.items.clone()];
                let (offsets, fans) = self.rows(list);
                list_bytes += 4 * (list.len() + offsets.len() + fans.len()) as u64;
                let params = params_buffer(
                    device,
                    DispatchParams {
                        vertex_count: list.len() as u32,
                        first_vertex: chunk.span.start,
                        window_split: self.split,
                        _pad: 0,
                    },
                );
                let group = self.kernel.bind_group(
                    device,
                    "sweepffd normals",
                    &[
                        params.as_entire_binding(),
                        self.low.clone(),
                        self.high.clone(),
                        storage_init(device, "sweepffd normal vertices", list).as_entire_binding(),
                        storage_init(device, "sweepffd normal offsets", &offsets).as_entire_binding(),
                        storage_init(device, "sweepffd normal fans", &fans).as_entire_binding(),
                        window(self.normals, &chunk.span, POSITION_STRIDE),
                    ],
                );
                (group, dispatch_grid(list.len() as u32, self.limits))
            })
            .collect();
        Ok((dispatches, list_bytes))
    }

    /// The row starts and fan entries of the vertices `list` (ascending, over all instances):
    /// each row ends with the entry carrying FAN_END, so only its start is listed. A run of
    /// consecutive vertices of the first instance takes its rows from the adjacency as they are.
    fn rows<'b>(&'b self, list: &[u32]) -> (Vec<u32>, Cow<'b, [u32]>) {
        let n = self.stride;
        let adjacency = self.adjacency;
        if let (Some(&first), Some(&last)) = (list.first(), list.last())
            && last < n
            && (last - first) as usize + 1 == list.len()
        {
            let rows = &adjacency.offsets[first as usize..last as usize + 2];
            let offsets = rows[..list.len()].iter().map(|&start| start - rows[0]).collect();
            return (offsets, Cow::Borrowed(&adjacency.fans[rows[0] as usize..rows[list.len()] as usize]));
        }
        let mut offsets = Vec::with_capacity(list.len());
        let mut start = 0u32;
        for &g in list {
            offsets.push(start);
            start += self.adjacency.fans_of((g % n) as usize).len() as u32;
        }
        // The rows are copied in blocks of vertices in parallel, then joined in order.
        let blocks: Vec<Vec<u32>> = list
            .par_chunks(LIST_BLOCK)
            .map(|block| {
                let mut fans = Vec::new();
                for &g in block {
                    // Instance k's copy of a fan entry is the same neighbour in instance k.
                    let base = g / n * n;
                    let entries = self.adjacency.fans_of((g % n) as usize);
                    debug_assert!(!entries.is_empty(), "vertex {g} has no row for the kernel to end");
                    fans.extend(entries.iter().map(|&e| ((e & FAN_INDEX) + base) | (e & !FAN_INDEX)));
                }
                fans
            })
            .collect();
        (offsets, Cow::Owned(blocks.concat()))
    }
}

/// The window of the positions `vertices` of `buffer`, whose vertex 0 is at byte `base`.
fn based(buffer: &wgpu::Buffer, base: u64, vertices: Range<u32>) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: base + vertices.start as u64 * POSITION_STRIDE,
        size: wgpu::BufferSize::new(vertices.len() as u64 * POSITION_STRIDE),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SMALL: ChunkLimits =
        ChunkLimits { max_binding: 1024, max_buffer: u32::MAX as u64, offset_alignment: 256, max_workgroups: 65535 };

    /// Checks that `chunks` cover `vertices` in order, each within the limits of [`list_chunks`].
    fn check(vertices: &[u32], stride: u64, entries: impl Fn(u32) -> u64, chunks: &[ListChunk]) {
        assert_eq!(chunks.first().map(|c| c.items.start), Some(0));
        assert_eq!(chunks.last().map(|c| c.items.end), Some(vertices.len()));
        for pair in chunks.windows(2) {
            assert_eq!(pair[0].items.end, pair[1].items.start);
        }
        for chunk in chunks {
            let list = &vertices[chunk.items.clone()];
            assert!(list.iter().all(|v| chunk.span.contains(v)), "{chunk:?}");
            assert_eq!(chunk.span.start as u64 * stride % 256, 0, "{chunk:?}");
            assert!(chunk.span.len() as u64 * stride <= 1024, "{chunk:?}");
            assert!((list.len() + 1) * 4 <= 1024, "{chunk:?}");
            assert!(list.iter().map(|&v| entries(v)).sum::<u64>() * 4 <= 1024, "{chunk:?}");
        }
    }

    #[test]
    fn sparse_lists_split_by_the_span_of_their_windows() {
        let vertices: Vec<u32> = (0..2000).filter(|v| v % 7 == 0 || (500..560).contains(v)).collect();
        for stride in [12, 16] {
            let chunks = list_chunks(&vertices, stride, |_| 0, &SMALL).unwrap();
            assert!(chunks.len() > 1);
            check(&vertices, stride, |_| 0, &chunks);
        }
    }

    #[test]
    fn dense_rows_split_by_their_adjacency_entries() {
        let vertices: Vec<u32> = (0..300).collect();
        let entries = |v: u32| (v % 9) as u64;
        let chunks = list_chunks(&vertices, 12, entries, &SMALL).unwrap();
        check(&vertices, 12, entries, &chunks);
    }

    #[test]
    fn empty_list_has_no_chunk_and_an_oversized_row_none() {
        assert_eq!(list_chunks(&[], 12, |_| 0, &SMALL), Some(Vec::new()));
        assert_eq!(list_chunks(&[3], 12, |_| 1000, &SMALL), None);
    }
}
