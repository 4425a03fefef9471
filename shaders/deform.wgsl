// Deformation (paper Eq. 2, extended by the axial offset h) of every bound vertex:
// v = C(t) + R(t) ((r(theta, t) + d) cos theta, (r(theta, t) + d) sin theta, h).
// Composed after layout.wgsl, cells_uniform.wgsl or cells_storage.wgsl (binding 1: the cell
// records) and sweep_eval.wgsl. Twin: src/cpu/deform.rs (run once per instance, with that
// instance's cells).
// Every instance in one dispatch: workgroup layer z is instance params.first_instance + z
// (deform_main), or instances numbered flat (deform_instances_main).

@group(0) @binding(0) var<uniform> params: InstanceParams;
@group(0) @binding(2) var<storage, read> bindings: array<GpuBinding>;
// Tightly packed xyz, instance z at z * params.instance_stride floats; unbound vertices keep the
// rest position written at creation.
@group(0) @binding(3) var<storage, read_write> positions: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    deform_vertex(i, group.z);
}

// Several instances numbered flat, vertex i of instance z at invocation z * vertex_count + i, so
// that every workgroup but the dispatch's last is full however few vertices an instance has (one
// workgroup layer per instance leaves the last workgroup of every instance nearly empty). The
// division runs once per workgroup; a workgroup spans at most 128 / vertex_count + 2 instances.
@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_instances_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let first = invocation_index(group, groups, 0u);
    var z = first / params.vertex_count;
    var i = first - z * params.vertex_count + lane;
    while (i >= params.vertex_count) {
        i -= params.vertex_count;
        z += 1u;
    }
    if (z >= params.instance_count) {
        return;
    }
    deform_vertex(i, z);
}

// Vertex i of the dispatch's instance z.
fn deform_vertex(i: u32, z: u32) {
    let binding = bindings[i];
    // Unbound vertices keep their rest position; vertices in falloff bands (BAND_FLAG, which
    // UNOWNED also has) are moved by the band kernel.
    if (binding.cell >= BAND_FLAG) {
        return;
    }
    let cell = cells[(params.first_instance + z) * params.cells_per_instance + binding.cell];
    let rho = radius_at(cell, binding.s, binding.phi) + binding.d;
    let direction = direction_at(cell, binding.phi);
    let local = vec3<f32>(rho * direction.x, rho * direction.y, binding.h);
    let p = curve_at(cell, binding.s) + rotate(quat_at(cell, binding.s), local);
    let o = z * params.instance_stride + 3u * i;
    positions[o] = p.x;
    positions[o + 1u] = p.y;
    positions[o + 2u] = p.z;
}
