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
pub const UNIFORM_CELL_CAPACITY: u32 = 341;

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
/// sweep and angular interval j of its radius function (§3). Rebuilt every frame; 192 bytes.
///
/// - `radius`: the bicubic r(s, φ) = Σ_p Σ_q c_pq·s^p·φ^q, stored by powers of φ:
///   `radius[q][p]` = c_pq.
/// - `curve[i].xyz`: C(s) = c0 + c1·s + c2·s² + c3·s³ on the interval (c0 = p_k); `curve[0].w`
///   is π/M (half the cell's angle); `curve[2].w` is 1 where the rotations are cubic (a2 or a3
///   below may be non-zero), 0 where they are linear, so that the fast CPU path can skip a2 and
///   a3; `curve[3].w` is unused.
/// - `rotation[i]`: R(t)·Rz(θ_mid) is the quaternion a0 + a1·s + a2·s² + a3·s³ normalized, with
///   a_i the power coefficients of the interval's q(s) (`crate::sweep::orientation`) times
///   qz(θ_mid), as (x, y, z, w); a2 = a3 = 0 for the linear interpolation, where
///   a0 = q_k ⊗ qz(θ_mid) and a1 = q̃_{k+1} ⊗ qz(θ_mid) − a0. θ_mid = θ_j + π/M is the cell's
///   middle angle: a vertex at angle θ_mid + δ turns by δ about z and then by that quaternion.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct CellCoeffs {
    /// Power-basis coefficients of r, `[power of φ][power of s]`.
    pub radius: [[f32; 4]; 4],
    /// The curve's coefficients in xyz; π/M in `curve[0].w`; which ends of the sweep the knot
    /// interval holds in `curve[1].w` ([`CellCoeffs::ends`]); 1 in `curve[2].w` where the
    /// rotations are cubic.
    pub curve: [[f32; 4]; 4],
    /// Power coefficients a0 … a3 of the unnormalized R(t)·Rz(θ_mid) in s.
    pub rotation: [[f32; 4]; 4],
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

/// The binding polynomial of one rest knot interval (see [`crate::bind`]): with w = v − origin,
/// g(s) = Σ_m (w·n_m − e_m)·s^m (n_m = 0 past m = 6, e_0 = 0), of degree 5 for the linear
/// rotation interpolation (n3 … n6 and e6 … e9 are zero) and 9 for the cubic one. 176 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BindSegment {
    /// p_k in xyz; w unused.
    pub origin: [f32; 4],
    /// n0 … n6 (the unnormalized normal's coefficients) in xyz; w unused.
    pub normal: [[f32; 4]; 7],
    /// e1, e2, e3, e4.
    pub e_low: [f32; 4],
    /// e5, e6, e7, e8.
    pub e_high: [f32; 4],
    /// e9.
    pub e9: f32,
    /// u_k.
    pub t0: f32,
    /// u_{k+1}.
    pub t1: f32,
    /// The degree of g: 5 or 9.
    pub degree: u32,
}

/// A vertex's binding in f32: the cell it lies in, local parameters in that cell, and (d, h).
/// The CPU twins and the bindings file hold bindings in this form; the GPU stores each as a
/// 16-byte [`PackedBinding`] and the kernels unpack it to this.
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

/// Bits of a [`PackedBinding`]'s cell index: rigs of the GPU engine have fewer than
/// [`MAX_PACKED_CELLS`] cells.
pub const CELL_BITS: u32 = 20;

/// The cell bits of a [`PackedBinding`]'s first word; all set for an unbound vertex.
pub const CELL_MASK: u32 = (1 << CELL_BITS) - 1;

/// Most cells a rig may have on the GPU: [`CELL_MASK`] marks an unbound vertex.
pub const MAX_PACKED_CELLS: u32 = CELL_MASK;

/// Bits of s and of φ in a [`PackedBinding`]: each is stored as a 21-bit unsigned normalized
/// integer, so that it differs from its f32 by at most half a step, 2⁻²² of the cell.
pub const PARAMETER_BITS: u32 = 21;

/// The largest stored s or φ, which reads as 1.
pub const PARAMETER_MAX: u32 = (1 << PARAMETER_BITS) - 1;

/// The bits of s and of φ held in the first word, below the [`BAND_FLAG`].
const LOW_BITS: u32 = PARAMETER_BITS - 16;

/// A vertex's binding as the GPU stores it, 16 bytes (one aligned 16-byte load a vertex, so
/// that a bound vertex moves 28 bytes a frame: the binding read and its position written).
///
/// - `cell_low`: the cell in the low [`CELL_BITS`] bits (all set: unbound, which reads as
///   [`UNOWNED`]), the low bits of s and then of φ above them, and the [`BAND_FLAG`];
/// - `s_phi_high`: the high 16 bits of s (low half) and of φ (high half);
/// - `d` and `h` as f32.
///
/// s and φ are stored to 21 bits ([`PARAMETER_BITS`]): at most 2⁻²² off their f32 values
/// (which carry 24 bits), 0 and 1 exact. A deformed position moves by at most
/// 2⁻²² (|∂p/∂s| + |∂p/∂φ|): 2.4e-7 of a knot interval's length plus 2.4e-7 of the arc of an
/// angular interval (docs/engine.md, "Bindings on the GPU").
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PackedBinding {
    /// The cell, the low bits of s and φ and the band flag.
    pub cell_low: u32,
    /// The high 16 bits of s and φ.
    pub s_phi_high: u32,
    /// Signed distance d from the sweep surface.
    pub d: f32,
    /// Axial offset h.
    pub h: f32,
}

impl PackedBinding {
    /// The packed form of `binding`, whose cell (without [`BAND_FLAG`]) is below
    /// [`MAX_PACKED_CELLS`] or [`UNOWNED`]: s and φ clamped to [0, 1] and rounded to the
    /// nearest of [`PARAMETER_MAX`] + 1 steps, ties to even (as WGSL's `round`).
    pub fn pack(binding: &GpuBinding) -> PackedBinding {
        let quantize = |x: f32| (x.clamp(0.0, 1.0) * PARAMETER_MAX as f32).round_ties_even() as u32;
        let (s, phi) = (quantize(binding.s), quantize(binding.phi));
        let cell = match binding.cell {
            UNOWNED => return PackedBinding { cell_low: UNOWNED, s_phi_high: 0, d: 0.0, h: 0.0 },
            cell => (cell & CELL_MASK) | (cell & BAND_FLAG),
        };
        let low_mask = (1 << LOW_BITS) - 1;
        PackedBinding {
            cell_low: cell | (s & low_mask) << CELL_BITS | (phi & low_mask) << (CELL_BITS + LOW_BITS),
            s_phi_high: (s >> LOW_BITS) | (phi >> LOW_BITS) << 16,
            d: binding.d,
            h: binding.h,
        }
    }

    /// The binding this packs, as the kernels unpack it (`unpack_binding` in
    /// `shaders/layout.wgsl`), bit for bit; an unbound vertex's is [`UNOWNED`] and zeros.
    pub fn unpack(&self) -> GpuBinding {
        let cell = match self.cell_low & CELL_MASK {
            CELL_MASK => return GpuBinding { cell: UNOWNED, ..GpuBinding::default() },
            cell => cell | (self.cell_low & BAND_FLAG),
        };
        let low_mask = (1 << LOW_BITS) - 1;
        let s = (self.s_phi_high & 0xffff) << LOW_BITS | (self.cell_low >> CELL_BITS) & low_mask;
        let phi = (self.s_phi_high >> 16) << LOW_BITS | (self.cell_low >> (CELL_BITS + LOW_BITS)) & low_mask;
        GpuBinding { cell, s: unorm(s), phi: unorm(phi), d: self.d, h: self.h }
    }
}

/// A stored s or φ as f32: `q / PARAMETER_MAX` as one correctly rounded product (1 reads as
/// exactly 1: (2²¹ − 1)(1 + 2⁻²¹)2⁻²¹ = 1 − 2⁻⁴², which rounds to 1).
fn unorm(q: u32) -> f32 {
    q as f32 * PARAMETER_SCALE
}

/// 1 / [`PARAMETER_MAX`] in f32, (1 + 2⁻²¹)2⁻²¹ exactly (`PARAMETER_SCALE` in
/// `shaders/layout.wgsl`, spelled `0x1.000008p-21f`).
pub const PARAMETER_SCALE: f32 = 1.0 / PARAMETER_MAX as f32;

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

const _: () = assert!(size_of::<CellCoeffs>() == 192);
const _: () = assert!(size_of::<BindSegment>() == 176);
const _: () = assert!(UNIFORM_CELL_CAPACITY as usize * size_of::<CellCoeffs>() <= 65536);
const _: () = assert!(size_of::<SweepInfo>() == 16);
const _: () = assert!(size_of::<GpuBinding>() == 20);
const _: () = assert!(size_of::<PackedBinding>() == 16);
const _: () = assert!(CELL_BITS + 2 * LOW_BITS < 31);
const _: () = assert!(size_of::<DispatchParams>() == 16);
const _: () = assert!(size_of::<InstanceParams>() == 32);
const _: () = assert!(size_of::<CellOrderParams>() == 32);
const _: () = assert!(size_of::<BandRecord>() == 16);
const _: () = assert!(size_of::<BandFlag>() == 16);
const _: () = assert!(size_of::<SkinInfluence>() == 8);
const _: () = assert!(size_of::<Joint>() == 48);

#[cfg(test)]
mod tests {
    use super::*;

    fn binding(cell: u32, s: f32, phi: f32) -> GpuBinding {
        GpuBinding { cell, s, phi, d: -0.25, h: 1.5 }
    }

    #[test]
    fn packed_parameters_are_within_half_a_step_and_the_ends_exact() {
        let half_step = 0.5 / PARAMETER_MAX as f32;
        let mut worst = 0.0f32;
        for k in 0..=100_000u32 {
            let x = k as f32 / 100_000.0;
            let unpacked = PackedBinding::pack(&binding(7, x, 1.0 - x)).unpack();
            worst = worst.max((unpacked.s - x).abs()).max((unpacked.phi - (1.0 - x)).abs());
            assert_eq!((unpacked.cell, unpacked.d, unpacked.h), (7, -0.25, 1.5));
        }
        // Half a step, plus the rounding of the f32 product and of 1 − x.
        assert!(worst <= half_step * 1.001, "worst {worst:e} > half a step {half_step:e}");
        assert!(worst >= half_step * 0.5, "worst {worst:e}: the parameters are not quantized at all?");
        for end in [0.0, 1.0] {
            let unpacked = PackedBinding::pack(&binding(3, end, end)).unpack();
            assert_eq!((unpacked.s, unpacked.phi), (end, end));
        }
        assert_eq!(PARAMETER_MAX as f32 * PARAMETER_SCALE, 1.0);
        assert_eq!(PARAMETER_SCALE.to_bits(), 0x3500_0004, "0x1.000008p-21, as shaders/layout.wgsl spells it");
    }

    #[test]
    fn packing_keeps_the_cell_the_band_flag_and_unbound_vertices() {
        let last = MAX_PACKED_CELLS - 1;
        for cell in [0, 1, 409, last, last | BAND_FLAG, BAND_FLAG] {
            assert_eq!(PackedBinding::pack(&binding(cell, 0.3, 0.9)).unpack().cell, cell);
        }
        let unbound = PackedBinding::pack(&binding(UNOWNED, 0.5, 0.5));
        assert_eq!(unbound.cell_low, UNOWNED);
        assert_eq!(unbound.unpack(), GpuBinding { cell: UNOWNED, ..GpuBinding::default() });
        // The deform kernel skips exactly the flagged and unbound vertices: their first word is
        // at least BAND_FLAG, every plain one's below (whatever its s and φ).
        assert!(PackedBinding::pack(&binding(last, 1.0, 1.0)).cell_low < BAND_FLAG);
        assert!(PackedBinding::pack(&binding(0, 0.0, 0.0)).cell_low < BAND_FLAG);
        assert!(PackedBinding::pack(&binding(5 | BAND_FLAG, 0.0, 0.0)).cell_low >= BAND_FLAG);
    }

    #[test]
    fn packing_an_unpacked_binding_gives_it_back() {
        for k in 0..10_000u32 {
            let b = binding(k % 997, (k as f32 * 0.618).fract(), (k as f32 * 0.377).fract());
            let packed = PackedBinding::pack(&b);
            assert_eq!(PackedBinding::pack(&packed.unpack()), packed, "binding {b:?}");
        }
    }
}
