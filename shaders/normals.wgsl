// Area-weighted vertex normals of the deformed mesh: for vertex i, the normalized sum of
// (p_j - p_i) x (p_k - p_i) over its incident triangles (i, j, k), gathered per vertex from a
// precomputed adjacency, so no atomics are needed.
// Composed after layout.wgsl. Twin: src/cpu/normals.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
// All positions through two windows, each within the storage binding limit: vertices below
// params.window_split are read from the first, the others from the second.
@group(0) @binding(1) var<storage, read> positions_low: array<f32>;
@group(0) @binding(2) var<storage, read> positions_high: array<f32>;
// This chunk's rows: vertex first_vertex + l has corner pairs offsets[l] .. offsets[l + 1].
@group(0) @binding(3) var<storage, read> offsets: array<u32>;
@group(0) @binding(4) var<storage, read> corners: array<vec2<u32>>;
// This chunk's window of the normals buffer, tightly packed xyz.
@group(0) @binding(5) var<storage, read_write> normals: array<f32>;

fn position(v: u32) -> vec3<f32> {
    if (v < params.window_split) {
        return vec3<f32>(positions_low[3u * v], positions_low[3u * v + 1u], positions_low[3u * v + 2u]);
    }
    let w = v - params.window_split;
    return vec3<f32>(positions_high[3u * w], positions_high[3u * w + 1u], positions_high[3u * w + 2u]);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn normals_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let l = invocation_index(group, groups, lane);
    if (l >= params.vertex_count) {
        return;
    }
    let p = position(params.first_vertex + l);
    var sum = vec3<f32>(0.0);
    for (var c = offsets[l]; c < offsets[l + 1u]; c++) {
        let corner = corners[c];
        sum += cross(position(corner.x) - p, position(corner.y) - p);
    }
    var n = vec3<f32>(0.0);
    let length2 = dot(sum, sum);
    if (length2 > 0.0) {
        n = sum * inverseSqrt(length2);
    }
    normals[3u * l] = n.x;
    normals[3u * l + 1u] = n.y;
    normals[3u * l + 2u] = n.z;
}
