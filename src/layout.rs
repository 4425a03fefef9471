//! Buffer layouts shared by the WGSL kernels (`shaders/layout.wgsl`) and their CPU twins.
//!
//! Every struct here is `#[repr(C)]` and `Pod`, has its WGSL twin of the same name in
//! `shaders/layout.wgsl`, and a test parses the shaders with naga and checks that sizes and
//! member offsets agree. No `vec3` in storage: three-component values are stored as
//! `[f32; 4]` / `vec4<f32>` with an unused `w`.

use bytemuck::{Pod, Zeroable};

/// Threads per workgroup of every compute kernel; the shaders' `@workgroup_size` must match.
pub const WORKGROUP_SIZE: u32 = 128;

/// Marks a vertex that no sweep owns, as an owner index or a `GpuBinding::cell`; the kernels
/// leave it in place.
pub const UNOWNED: u32 = u32::MAX;

/// Set in `GpuBinding::cell` (and in the owner given to the bind kernel) for a vertex in a
/// falloff band: the deform kernel leaves it to the band kernel, which reads its cell as
/// `cell & !BAND_FLAG`. Rigs have fewer than 2³¹ cells.
pub const BAND_FLAG: u32 = 1 << 31;

/// Set in [`BandFlag::vertex`] for a vertex that keeps its rest position in the new bands (w = 0
/// against the rest position): the band-flags kernel writes that position, which the band kernel
/// never does. Dispatches hold fewer than 2³⁰ vertices.
pub const KEEPS_REST: u32 = 1 << 30;

/// Most cells a rig may have for the deform kernel to read them from a uniform buffer (64 KiB,
/// the portable limit); larger rigs use the storage-buffer variant of the kernel.
pub const UNIFORM_CELL_CAPACITY: u32 = 409;

/// Instances one invocation of the instanced deform kernel (`deform_instances_main`) deforms:
/// it reads each binding once for them all.
pub const INSTANCES_PER_INVOCATION: u32 = 4;

/// Vertices of one cell group: the deform kernel over cell groups deforms a group's vertices,
/// which share a cell, reading that cell's record once (`src/gpu/deformer/cell_groups.rs`).
pub const CELL_GROUP: u32 = 4;

/// Buckets a run of the cell groups' scan (`shaders/cell_order.wgsl`): no invocation of the
/// sort loops more than a few thousand times (llvmpipe ends an invocation's loops after 65,535
/// iterations in all).
pub const SCAN_RUN: u32 = 64;

/// Everything a vertex needs to follow its posed sweep, for one cell: knot interval k of a
/// sweep and angular interval j of its radius function (§3). Rebuilt every frame; 160 bytes.
///
/// - `radius`: the bicubic r(s, φ) = Σ_p Σ_q c_pq·s^p·φ^q, stored by powers of φ:
///   `radius[q][p]` = c_pq.
/// - `curve[i].xyz`: C(s) = c0 + c1·s + c2·s² + c3·s³ on the interval (c0 = p_k); `curve[0].w`
///   is π/M (half the cell's angle); the other `w` are unused.
/// - `q0`, `dq`: R(t)·Rz(θ_mid) is the quaternion q0 + s·dq normalized, with q0 = q_k ⊗ qz(θ_mid)
///   and dq = q̃_{k+1} ⊗ qz(θ_mid) − q0, as (x, y, z, w); θ_mid = θ_j + π/M is the cell's middle
///   angle: a vertex at angle θ_mid + δ turns by δ about z and then by that quaternion.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct CellCoeffs {
    /// Power-basis coefficients of r, `[power of φ][power of s]`.
    pub radius: [[f32; 4]; 4],
    /// The curve's coefficients in xyz; π/M in `curve[0].w`; which ends of the sweep the knot
    /// interval holds in `curve[1].w` ([`CellCoeffs::ends`]).
    pub curve: [[f32; 4]; 4],
    /// q_k ⊗ qz(θ_mid).
    pub q0: [f32; 4],
    /// q̃_{k+1} ⊗ qz(θ_mid) − q0.
    pub dq: [f32; 4],
}

impl CellCoeffs {
    /// Half the angular step, π/M.
    pub fn half_step(&self) -> f32 {
        self.curve[0][3]
    }

    /// The `curve[1].w` of knot interval `k` of `segments`: 1 on the first, plus 2 on the last
    /// (binding beyond an end happens there, `crate::cpu::jacobian::is_beyond_end`).
    pub fn ends(k: usize, segments: usize) -> f32 {
        (u32::from(k == 0) + 2 * u32::from(k + 1 == segments)) as f32
    }
}

/// Where one sweep's knot intervals and cells start; used by binding. 16 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct SweepInfo {
    /// Index of the sweep's first knot interval in the [`BindSegment`] array.
    pub first_segment: u32,
    /// Number of knot intervals n.
    pub segment_count: u32,
    /// Index of the sweep's first cell; cell (k, j) is `first_cell + k·M + j`.
    pub first_cell: u32,
    /// M, the number of radii per key.
    pub samples: u32,
}

/// The binding quintic of one rest knot interval (see [`crate::bind`]): with w = v − origin,
/// g(s) = w·n0 + (w·n1 − e1)·s + (w·n2 − e2)·s² − e3·s³ − e4·s⁴ − e5·s⁵. 96 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BindSegment {
    /// p_k in xyz; w unused.
    pub origin: [f32; 4],
    /// n0, n1, n2 (the unnormalized normal's coefficients) in xyz; w unused.
    pub normal: [[f32; 4]; 3],
    /// e1, e2, e3, e4.
    pub e_low: [f32; 4],
    /// e5.
    pub e5: f32,
    /// u_k.
    pub t0: f32,
    /// u_{k+1}.
    pub t1: f32,
    /// Unused.
    pub _pad: f32,
}

/// A vertex's binding as the GPU stores it: the cell it lies in, local parameters in that
/// cell, and (d, h). 20 bytes, so positions (12) and bindings fit in 32 bytes a vertex.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuBinding {
    /// Global cell index, or [`UNOWNED`]; with [`BAND_FLAG`] set for a vertex in a falloff band.
    pub cell: u32,
    /// Local axis parameter s ∈ [0, 1] in the cell's knot interval.
    pub s: f32,
    /// Local angle parameter φ ∈ [0, 1] in the cell's angular interval: θ = θ_j + φ·2π/M.
    pub phi: f32,
    /// Signed distance d from the sweep surface.
    pub d: f32,
    /// Axial offset h.
    pub h: f32,
}

/// A vertex in a falloff band, for the band kernel: its weight and its second influence. 16
/// bytes, only for vertices with w < 1.
///
/// The second influence is the rest position (`cell` = [`UNOWNED`]) or a neighbouring sweep's
/// frame at the vertex: the cell and local (s, φ) of the vertex's binding to that sweep, as
/// unorm16 (s in the low half). The band kernel rebuilds the vertex's rest position from its own
/// binding and takes its offset in that frame, so d and h of the second binding need no storage;
/// the 16-bit (s, φ) only choose the frame (within 1.5e-5 of the cell) and moving it is exact at
/// rest and under rigid motion.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BandRecord {
    /// The vertex, relative to the first vertex of its dispatch.
    pub vertex: u32,
    /// w ∈ [0, 1): the share of its own sweep's deformation it follows.
    pub weight: f32,
    /// The second influence's global cell, or [`UNOWNED`] for the rest position.
    pub cell: u32,
    /// The second influence's (s, φ) packed as two unorm16, s in bits 0..16.
    pub s_phi: u32,
}

/// A change of one vertex's band membership when the falloff bands are replaced
/// ([`GpuDeformer::set_bands`](crate::gpu::GpuDeformer::set_bands)), for the band-flags kernel.
/// 16 bytes, only for the vertices whose membership changes.
///
/// `vertex` is the vertex relative to the first vertex of its dispatch, with [`BAND_FLAG`] set if
/// it enters the bands (clear: it leaves them and the deform kernel moves it again) and
/// [`KEEPS_REST`] set if it keeps its rest position there, which `x, y, z` then hold (f32, as
/// the deformer uploaded it). The position is three scalars rather than a `[f32; 4]` so that the
/// record packs into 16 bytes with its vertex.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BandFlag {
    /// The vertex, relative to the first vertex of its dispatch, with [`BAND_FLAG`] and
    /// [`KEEPS_REST`] as flags.
    pub vertex: u32,
    /// Rest position x, for a vertex with [`KEEPS_REST`].
    pub x: f32,
    /// Rest position y.
    pub y: f32,
    /// Rest position z.
    pub z: f32,
}

/// Per-dispatch constants of every kernel: one dispatch covers one chunk of vertices. 16 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct DispatchParams {
    /// Number of vertices in this dispatch; threads at or past it return at once.
    pub vertex_count: u32,
    /// Global index of the dispatch's first vertex (used by the normals kernel, whose position
    /// reads reach any vertex).
    pub first_vertex: u32,
    /// Global index of the first vertex read through the second positions window (normals).
    pub window_split: u32,
    /// Unused.
    pub _pad: u32,
}

/// Per-dispatch constants of the deform and band kernels, which run over every instance of a
/// mesh at once (one workgroup layer z per instance, or `instance_count` instances numbered
/// flat for the instanced deform kernel): instance `first_instance + z` reads its cell records
/// at `(first_instance + z) · cells_per_instance` and writes its positions
/// `z · instance_stride` floats into the dispatch's window. 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct InstanceParams {
    /// Number of vertices (band records for the band kernel) in this dispatch.
    pub vertex_count: u32,
    /// Cell records of one instance's pose.
    pub cells_per_instance: u32,
    /// Floats from one instance's positions to the next's (3 × the instance stride in vertices).
    pub instance_stride: u32,
    /// The instance of workgroup layer z = 0.
    pub first_instance: u32,
    /// Instances in this dispatch (read by the flat-numbered instanced deform kernel).
    pub instance_count: u32,
    /// Unused.
    pub _pad0: u32,
    /// Unused.
    pub _pad1: u32,
    /// Unused.
    pub _pad2: u32,
}

/// The cell groups of one chunk of vertices, for the counting sort by (block, cell) that makes
/// them (`shaders/cell_order.wgsl`). 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct CellOrderParams {
    /// Vertices of the chunk.
    pub vertex_count: u32,
    /// Cell records of one instance.
    pub cell_count: u32,
    /// Slots of the chunk's groups, [`CELL_GROUP`] a group.
    pub slot_count: u32,
    /// Consecutive vertices of one block: the vertices are sorted by cell within each block.
    pub block_size: u32,
    /// The device's most workgroups in one dimension of a dispatch.
    pub max_workgroups: u32,
    /// Deform dispatches whose indirect arguments the sort writes.
    pub dispatch_count: u32,
    /// Unused.
    pub _pad0: u32,
    /// Unused.
    pub _pad1: u32,
}

/// One vertex's skinning influences for the linear-blend-skinning baseline: four joint
/// indices and four weights, each packed as bytes (weights as unorm8, summing to 255). 8 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct SkinInfluence {
    /// Joint indices, one per byte, lowest byte first.
    pub joints: u32,
    /// Weights as unorm8, one per byte, lowest byte first.
    pub weights: u32,
}

/// A joint's skinning matrix for the baseline: the top three rows of a 4×4 affine transform. 48
/// bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Joint {
    /// Rows 0..3 of the affine matrix.
    pub rows: [[f32; 4]; 3],
}

const _: () = assert!(size_of::<CellCoeffs>() == 160);
const _: () = assert!(UNIFORM_CELL_CAPACITY as usize * size_of::<CellCoeffs>() <= 65536);
const _: () = assert!(size_of::<SweepInfo>() == 16);
const _: () = assert!(size_of::<BindSegment>() == 96);
const _: () = assert!(size_of::<GpuBinding>() == 20);
const _: () = assert!(size_of::<DispatchParams>() == 16);
const _: () = assert!(size_of::<InstanceParams>() == 32);
const _: () = assert!(size_of::<CellOrderParams>() == 32);
const _: () = assert!(size_of::<BandRecord>() == 16);
const _: () = assert!(size_of::<BandFlag>() == 16);
const _: () = assert!(size_of::<SkinInfluence>() == 8);
const _: () = assert!(size_of::<Joint>() == 48);
