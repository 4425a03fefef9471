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
const UNIFORM_CELL_CAPACITY: u32 = 409u;

// Everything a vertex needs to follow its posed sweep, for one cell (knot interval k, angular
// interval j): the bicubic r(s, phi) = sum c_pq s^p phi^q stored as radius[q][p]; C(s) = c0 + c1 s
// + c2 s^2 + c3 s^3 in curve[i].xyz, with pi / M in curve[0].w; and R(t) Rz(theta_mid) as the
// quaternion q0 + s dq (x, y, z, w) before normalization, theta_mid the cell's middle angle.
struct CellCoeffs {
    radius: array<vec4<f32>, 4>,
    curve: array<vec4<f32>, 4>,
    q0: vec4<f32>,
    dq: vec4<f32>,
}

// Where one sweep's knot intervals and cells start; cell (k, j) is first_cell + k * samples + j.
struct SweepInfo {
    first_segment: u32,
    segment_count: u32,
    first_cell: u32,
    samples: u32,
}

// The binding quintic of a rest knot interval, with w = v - origin:
// g(s) = w.n0 + (w.n1 - e1) s + (w.n2 - e2) s^2 - e3 s^3 - e4 s^4 - e5 s^5.
struct BindSegment {
    origin: vec4<f32>,
    normal: array<vec4<f32>, 3>,
    e_low: vec4<f32>,
    e5: f32,
    t0: f32,
    t1: f32,
    _pad: f32,
}

// A vertex's binding: its radius cell (or UNOWNED), local (s, phi) in that cell, d and h.
struct GpuBinding {
    cell: u32,
    s: f32,
    phi: f32,
    d: f32,
    h: f32,
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
