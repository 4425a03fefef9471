// Benchmark baseline: four-influence linear-blend skinning, what real-time applications run
// today. Reads a 12-byte rest position and 8 bytes of packed joints and weights (20 bytes; deform
// reads a 16-byte binding), writes 12 bytes: p' = sum_k w_k M_k (p, 1).
// Joint matrices in a uniform buffer, as engines keep them. Composed after layout.wgsl.
// Twin: src/cpu/skinning.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(1) var<uniform> joints: array<Joint, 64>;
@group(0) @binding(2) var<storage, read> rest: array<f32>;
@group(0) @binding(3) var<storage, read> influences: array<SkinInfluence>;
@group(0) @binding(4) var<storage, read_write> positions: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn skinning_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let p = vec4<f32>(rest[3u * i], rest[3u * i + 1u], rest[3u * i + 2u], 1.0);
    let influence = influences[i];
    let weights = unpack4x8unorm(influence.weights);
    var skinned = vec3<f32>(0.0);
    for (var k = 0u; k < 4u; k++) {
        let joint = joints[(influence.joints >> (8u * k)) & 0xffu];
        skinned += weights[k] * vec3<f32>(dot(joint.rows[0], p), dot(joint.rows[1], p), dot(joint.rows[2], p));
    }
    positions[3u * i] = skinned.x;
    positions[3u * i + 1u] = skinned.y;
    positions[3u * i + 2u] = skinned.z;
}
