// The Jacobian probe's verdict (src/gpu/deformer/jacobian_probe.rs), once at creation: for each
// probed vertex, whether its Jacobian normal under the probe pose (the fused kernel's) lies
// within the probe's tolerance of the normal of its probed one-ring (the normals kernel's on the
// probed positions). A vertex whose rest normal is zero keeps the Jacobian, as one whose two
// probed normals are both zero or one is (a ring the probe collapses); a NaN does not.
// Twin: src/deform/probe.rs (jacobian_normal_vertices, in f64).
// Composed after layout.wgsl.

@group(0) @binding(0) var<uniform> params: DispatchParams;
// The probed vertices, ascending, each relative to params.first_vertex, the first vertex of the
// windows below.
@group(0) @binding(1) var<storage, read> probed: array<u32>;
@group(0) @binding(2) var<storage, read> jacobian_normals: array<f32>;
@group(0) @binding(3) var<storage, read> facet_normals: array<f32>;
@group(0) @binding(4) var<storage, read> rest_normals: array<f32>;
// 1 where the vertex keeps its Jacobian normal, 0 where the normals pass computes it, one word a
// vertex of the windows (written for the probed vertices only).
@group(0) @binding(5) var<storage, read_write> verdicts: array<u32>;

// tan of the probe's tolerance, 1.5 degrees (PROBE_TOLERANCE_DEG).
const TAN_TOLERANCE: f32 = 0.026185921569186;

@compute @workgroup_size(WORKGROUP_SIZE)
fn jacobian_probe_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let v = probed[i];
    let rest = vec3<f32>(rest_normals[3u * v], rest_normals[3u * v + 1u], rest_normals[3u * v + 2u]);
    let j = vec3<f32>(jacobian_normals[3u * v], jacobian_normals[3u * v + 1u], jacobian_normals[3u * v + 2u]);
    let f = vec3<f32>(facet_normals[3u * v], facet_normals[3u * v + 1u], facet_normals[3u * v + 2u]);
    // The angle atan2(|j x f|, j . f) is within the tolerance: both zero (atan2(0, 0) = 0), or
    // an acute angle whose tangent is within it. NaN fails every comparison.
    let across = length(cross(j, f));
    let along = dot(j, f);
    let within = (across == 0.0 && along == 0.0) || (along > 0.0 && across <= along * TAN_TOLERANCE);
    let keeps = all(rest == vec3<f32>(0.0)) || within;
    verdicts[v] = select(0u, 1u, keeps);
}
