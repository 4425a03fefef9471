// Buffer layouts shared by every kernel.
// Twin: src/layout.rs (sizes and member offsets are checked against it by a test).

const WORKGROUP_SIZE: u32 = 128u;
const UNOWNED: u32 = 0xffffffffu;
// Set in a binding's cell (and a bind kernel owner) for a vertex in a falloff band.
const BAND_FLAG: u32 = 0x80000000u;
// Set in a BandFlag's vertex for a vertex that keeps its rest position in the new bands.
const KEEPS_REST: u32 = 0x40000000u;

// Instances one invocation of the instanced deform kernel deforms (deform_instances_main).
const INSTANCES_PER_INVOCATION: u32 = 4u;

// Vertices of one cell group (deform_groups.wgsl, cell_order.wgsl).
const CELL_GROUP: u32 = 4u;

// Most cells a rig may have for the deform kernel to read them from a uniform buffer (64 KiB).
const UNIFORM_CELL_CAPACITY: u32 = 341u;

// Everything a vertex needs to follow its posed sweep, for one cell (knot interval k, angular
// interval j): the bicubic r(s, phi) = sum c_pq s^p phi^q stored as radius[q][p]; C(s) = c0 + c1 s
// + c2 s^2 + c3 s^3 in curve[i].xyz, with pi / M in curve[0].w; and R(t) Rz(theta_mid) as the
// quaternion a0 + a1 s + a2 s^2 + a3 s^3 (x, y, z, w; a2 = a3 = 0 for the linear rotation
// interpolation) in rotation[i], before normalization, theta_mid the cell's middle angle.
struct CellCoeffs {
    radius: array<vec4<f32>, 4>,
    curve: array<vec4<f32>, 4>,
    rotation: array<vec4<f32>, 4>,
}

// Where one sweep's knot intervals and cells start; cell (k, j) is first_cell + k * samples + j.
struct SweepInfo {
    first_segment: u32,
    segment_count: u32,
    first_cell: u32,
    samples: u32,
}

// The binding polynomial of a rest knot interval, with w = v - origin:
// g(s) = sum_m (w.n_m - e_m) s^m (n_m = 0 past m = 6, e_0 = 0), of degree 5 (linear rotation
// interpolation: n3..n6 and e6..e9 are zero) or 9 (cubic).
struct BindSegment {
    origin: vec4<f32>,
    normal: array<vec4<f32>, 7>,
    e_low: vec4<f32>,
    e_high: vec4<f32>,
    e9: f32,
    t0: f32,
    t1: f32,
    degree: u32,
}

// A vertex's binding, unpacked: its radius cell (or UNOWNED; BAND_FLAG set in a falloff band),
// local (s, phi) in that cell, d and h.
struct GpuBinding {
    cell: u32,
    s: f32,
    phi: f32,
    d: f32,
    h: f32,
}

// A binding as the buffers store it (PackedBinding in src/layout.rs), one vec4<u32> so that it
// is read in one aligned 16-byte load: x holds the cell in its low CELL_BITS bits (all set: unbound),
// the low LOW_BITS bits of s and of phi above them and BAND_FLAG; y the high 16 bits of s (low
// half) and of phi (high half); z and w the bits of d and h. s and phi are 21-bit unorms.
const CELL_BITS: u32 = 20u;
const CELL_MASK: u32 = 0xfffffu;
const LOW_BITS: u32 = 5u;
const LOW_MASK: u32 = 0x1fu;
const PARAMETER_MAX: f32 = 2097151.0;
// 1 / PARAMETER_MAX in f32, (1 + 2^-21) 2^-21 exactly; PARAMETER_MAX * PARAMETER_SCALE rounds to 1.
const PARAMETER_SCALE: f32 = 0x1.000008p-21f;

// Whether a packed binding's vertex is deformed by the deform kernel: bound, outside the bands.
fn is_plain(x: u32) -> bool {
    return x < BAND_FLAG;
}

// The cell of a plain packed binding (is_plain).
fn plain_cell(x: u32) -> u32 {
    return x & CELL_MASK;
}

// A packed binding unpacked, its cell without BAND_FLAG: for plain bindings (is_plain).
fn unpack_plain(w: vec4<u32>) -> GpuBinding {
    let s = ((w.y & 0xffffu) << LOW_BITS) | ((w.x >> CELL_BITS) & LOW_MASK);
    let phi = ((w.y >> 16u) << LOW_BITS) | ((w.x >> (CELL_BITS + LOW_BITS)) & LOW_MASK);
    return GpuBinding(plain_cell(w.x), f32(s) * PARAMETER_SCALE, f32(phi) * PARAMETER_SCALE, bitcast<f32>(w.z), bitcast<f32>(w.w));
}

// A packed binding unpacked: UNOWNED and zeros if unbound, BAND_FLAG in its cell in a falloff
// band.
fn unpack_binding(w: vec4<u32>) -> GpuBinding {
    if ((w.x & CELL_MASK) == CELL_MASK) {
        return GpuBinding(UNOWNED, 0.0, 0.0, 0.0, 0.0);
    }
    var binding = unpack_plain(w);
    binding.cell |= w.x & BAND_FLAG;
    return binding;
}

// The packed form of b (s and phi in [0, 1], rounded to the nearest step, ties to even).
fn pack_binding(b: GpuBinding) -> vec4<u32> {
    if (b.cell == UNOWNED) {
        return vec4<u32>(UNOWNED, 0u, 0u, 0u);
    }
    let s = u32(round(clamp(b.s, 0.0, 1.0) * PARAMETER_MAX));
    let phi = u32(round(clamp(b.phi, 0.0, 1.0) * PARAMETER_MAX));
    let x = (b.cell & CELL_MASK) | (b.cell & BAND_FLAG) | ((s & LOW_MASK) << CELL_BITS)
        | ((phi & LOW_MASK) << (CELL_BITS + LOW_BITS));
    return vec4<u32>(x, (s >> LOW_BITS) | ((phi >> LOW_BITS) << 16u), bitcast<u32>(b.d), bitcast<u32>(b.h));
}

// A vertex in a falloff band: its vertex (relative to the dispatch's first), weight w, and second
// influence: UNOWNED (the rest position) or a neighbouring sweep's cell with (s, phi) as two
// unorm16 (s low).
struct BandRecord {
    vertex: u32,
    weight: f32,
    cell: u32,
    s_phi: u32,
}

// A change of one vertex's band membership (set_bands): the vertex (relative to the dispatch's
// first) with BAND_FLAG set if it enters the bands (clear: it leaves them) and KEEPS_REST set if
// it keeps its rest position there, which x, y, z then hold.
struct BandFlag {
    vertex: u32,
    x: f32,
    y: f32,
    z: f32,
}

// One dispatch covers one chunk of vertices: its count, the global index of its first vertex,
// and (normals) the first vertex read through the second positions window.
struct DispatchParams {
    vertex_count: u32,
    first_vertex: u32,
    window_split: u32,
    _pad: u32,
}

// The deform and band kernels run over every instance at once, one workgroup layer z each (or
// instance_count instances numbered flat, deform_instances_main): instance first_instance + z
// reads its cells at (first_instance + z) * cells_per_instance and writes its positions
// z * instance_stride floats into the dispatch's window.
struct InstanceParams {
    vertex_count: u32,
    cells_per_instance: u32,
    instance_stride: u32,
    first_instance: u32,
    instance_count: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// The cell groups of one chunk (cell_order.wgsl): its vertices, the cells of one instance, the
// slots of its groups (CELL_GROUP a group), the vertices of a block (sorted by cell within), and
// for the deform dispatches' indirect arguments the device's most workgroups in a dimension and
// the number of dispatches.
struct CellOrderParams {
    vertex_count: u32,
    cell_count: u32,
    slot_count: u32,
    block_size: u32,
    max_workgroups: u32,
    dispatch_count: u32,
    _pad0: u32,
    _pad1: u32,
}

// Linear-blend-skinning baseline: four joint indices and four unorm8 weights, packed in bytes.
struct SkinInfluence {
    joints: u32,
    weights: u32,
}

// A joint's matrix: the top three rows of a 4x4 affine transform.
struct Joint {
    rows: array<vec4<f32>, 3>,
}

// The linear invocation index of a dispatch of (x, y, 1) workgroups: large meshes need more
// than 65,535 workgroups, so dispatches are two-dimensional.
fn invocation_index(group: vec3<u32>, groups: vec3<u32>, lane: u32) -> u32 {
    return (group.y * groups.x + group.x) * WORKGROUP_SIZE + lane;
}
