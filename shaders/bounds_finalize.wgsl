// Per-instance bounds as f32: decodes the order-preserving u32 extremes of bounds.wgsl into
// min.xyz, 0, max.xyz, 0 (32 bytes an instance). One thread per instance. Twin:
// src/cpu/bounds.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(1) var<storage, read> extremes: array<u32>;
@group(0) @binding(2) var<storage, read_write> bounds: array<f32>;

// The f32 that ordered() (bounds.wgsl) encodes as u.
fn unordered(u: u32) -> f32 {
    return bitcast<f32>(select(~u, u & 0x7fffffffu, (u & 0x80000000u) != 0u));
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn bounds_finalize_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    for (var c = 0u; c < 3u; c++) {
        bounds[8u * i + c] = unordered(extremes[8u * i + c]);
        bounds[8u * i + 4u + c] = unordered(extremes[8u * i + 4u + c]);
    }
    bounds[8u * i + 3u] = 0.0;
    bounds[8u * i + 7u] = 0.0;
}
