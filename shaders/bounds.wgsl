// Per-instance axis-aligned bounds of the deformed positions: each workgroup reduces its
// vertices' coordinates in workgroup atomics, then one thread folds them into the instance's
// global atomics, all as order-preserving u32 encodings of f32 (ordered() below), so min and
// max are exact. Workgroup layer z is instance params.first_instance + z, as in deform.wgsl.
// The global atomics are seeded each frame (by a buffer copy) with the bounds of the vertices
// no dispatch covers; bounds_finalize.wgsl decodes them. Twin: src/cpu/bounds.rs.

@group(0) @binding(0) var<uniform> params: InstanceParams;
// This dispatch's window of the positions, instance z at z * params.instance_stride floats.
@group(0) @binding(1) var<storage, read> positions: array<f32>;
// Per instance: ordered min x, y, z, unused, ordered max x, y, z, unused.
@group(0) @binding(2) var<storage, read_write> extremes: array<atomic<u32>>;

var<workgroup> low: array<atomic<u32>, 3>;
var<workgroup> high: array<atomic<u32>, 3>;

// The u32 whose unsigned order is the f32 order of f (-0 below +0; no NaN reaches here).
fn ordered(f: f32) -> u32 {
    let bits = bitcast<u32>(f);
    return select(bits | 0x80000000u, ~bits, (bits & 0x80000000u) != 0u);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn bounds_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    if (lane < 3u) {
        atomicStore(&low[lane], 0xffffffffu);
        atomicStore(&high[lane], 0u);
    }
    workgroupBarrier();
    let i = invocation_index(group, groups, lane);
    if (i < params.vertex_count) {
        let o = group.z * params.instance_stride + 3u * i;
        for (var c = 0u; c < 3u; c++) {
            let u = ordered(positions[o + c]);
            atomicMin(&low[c], u);
            atomicMax(&high[c], u);
        }
    }
    workgroupBarrier();
    if (lane < 3u) {
        let at = 8u * (params.first_instance + group.z);
        atomicMin(&extremes[at + lane], atomicLoad(&low[lane]));
        atomicMax(&extremes[at + 4u + lane], atomicLoad(&high[lane]));
    }
}
