// Benchmark baseline: the memory ceiling of the deform kernel. Reads each vertex's 16-byte
// packed binding and writes 12 bytes of position, as deform does, with no arithmetic to speak of.
// Composed after layout.wgsl. The CPU bench's twin, src/cpu/copy.rs, reads the f32 bindings
// instead.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(1) var<storage, read> bindings: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read_write> positions: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn copy_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let b = bindings[i];
    positions[3u * i] = bitcast<f32>(b.x ^ b.y);
    positions[3u * i + 1u] = bitcast<f32>(b.w);
    positions[3u * i + 2u] = bitcast<f32>(b.z);
}
