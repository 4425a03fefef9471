// Benchmark baseline: the memory ceiling of the fused deform + Jacobian normals kernel. Reads
// each vertex's 16-byte binding and 16-byte normal coordinates record and writes 12 bytes of
// position and 12 of normal, as deform_normals.wgsl does, with no arithmetic to speak of.
// Composed after layout.wgsl. The CPU bench's twin, src/cpu/copy.rs (copy_wide),
// reads the f32 bindings instead.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(1) var<storage, read> bindings: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read> records: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> positions: array<f32>;
@group(0) @binding(4) var<storage, read_write> normals: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn copy_wide_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let b = bindings[i];
    let r = records[i];
    positions[3u * i] = bitcast<f32>(b.x ^ b.y);
    positions[3u * i + 1u] = bitcast<f32>(b.w);
    positions[3u * i + 2u] = bitcast<f32>(b.z);
    normals[3u * i] = r.x + r.w;
    normals[3u * i + 1u] = r.y;
    normals[3u * i + 2u] = r.z;
}
