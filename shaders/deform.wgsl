// Deformation (paper Eq. 2, extended by the axial offset h) of every bound vertex:
// v = C(t) + R(t) ((r(theta, t) + d) cos theta, (r(theta, t) + d) sin theta, h).
// Composed after layout.wgsl, cells_uniform.wgsl or cells_storage.wgsl (binding 1: the cell
// records) and sweep_eval.wgsl. Twin: src/cpu/deform.rs (run once per instance, with that
// instance's cells).
// Every instance in one dispatch: workgroup layer z is instance params.first_instance + z
// (deform_main), or instances numbered flat (deform_instances_main).

@group(0) @binding(0) var<uniform> params: InstanceParams;
@group(0) @binding(2) var<storage, read> bindings: array<vec4<u32>>;
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

// Several instances numbered flat, each invocation deforming one vertex of INSTANCES_PER_INVOCATION
// consecutive instances: invocation g = w * vertex_count + i deforms vertex i of instances
// w * INSTANCES_PER_INVOCATION onwards. Each binding is read once for those instances (the
// instances share it), and every workgroup but the dispatch's last is full however few vertices
// an instance has (one workgroup layer per instance leaves the last workgroup of every instance
// nearly empty). The division runs once per workgroup.
@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_instances_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let first = invocation_index(group, groups, 0u);
    var w = first / params.vertex_count;
    var i = first - w * params.vertex_count + lane;
    while (i >= params.vertex_count) {
        i -= params.vertex_count;
        w += 1u;
    }
    let z0 = w * INSTANCES_PER_INVOCATION;
    if (z0 >= params.instance_count) {
        return;
    }
    let packed = bindings[i];
    if (!is_plain(packed.x)) {
        return;
    }
    let binding = unpack_plain(packed);
    let last = min(z0 + INSTANCES_PER_INVOCATION, params.instance_count);
    for (var z = z0; z < last; z++) {
        deform_bound_vertex(i, z, binding);
    }
}

// Vertex i of the dispatch's instance z.
fn deform_vertex(i: u32, z: u32) {
    let packed = bindings[i];
    // Unbound vertices keep their rest position; vertices in falloff bands (BAND_FLAG, which
    // UNOWNED also has) are moved by the band kernel.
    if (!is_plain(packed.x)) {
        return;
    }
    deform_bound_vertex(i, z, unpack_plain(packed));
}

// Vertex i of the dispatch's instance z, bound by `binding` (no falloff band).
fn deform_bound_vertex(i: u32, z: u32, binding: GpuBinding) {
    deform_in_cell(i, z, binding, posed_cell(z, binding.cell));
}

// The record of `cell` in the pose of the dispatch's instance z.
fn posed_cell(z: u32, cell: u32) -> CellCoeffs {
    return cells[(params.first_instance + z) * params.cells_per_instance + cell];
}

// The deformed position of a vertex bound by `binding` in `cell` (its cell's record).
fn position_in_cell(binding: GpuBinding, cell: CellCoeffs) -> vec3<f32> {
    let rho = radius_at(cell, binding.s, binding.phi) + binding.d;
    let direction = direction_at(cell, binding.phi);
    let local = vec3<f32>(rho * direction.x, rho * direction.y, binding.h);
    return curve_at(cell, binding.s) + rotate(quat_at(cell, binding.s), local);
}

// One workgroup's positions, staged by deform_staged_main to be stored as whole words.
var<workgroup> staged: array<f32, 3u * WORKGROUP_SIZE>;

// deform_main with the workgroup's positions stored whole: each invocation deforms its vertex
// into workgroup memory (an unbound or band vertex reads its current position there, which the
// band kernel, dispatched after, overwrites in a band), then the workgroup stores its
// 3 * WORKGROUP_SIZE consecutive floats in three runs of consecutive words, so that a warp's
// stores fill whole cache lines rather than every third word of three lines (12-byte stride).
@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_staged_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let first = invocation_index(group, groups, 0u);
    if (first >= params.vertex_count) {
        return;
    }
    let count = min(WORKGROUP_SIZE, params.vertex_count - first);
    let base = group.z * params.instance_stride + 3u * first;
    if (lane < count) {
        let packed = bindings[first + lane];
        var p: vec3<f32>;
        if (is_plain(packed.x)) {
            let binding = unpack_plain(packed);
            p = position_in_cell(binding, posed_cell(group.z, binding.cell));
        } else {
            let o = base + 3u * lane;
            p = vec3<f32>(positions[o], positions[o + 1u], positions[o + 2u]);
        }
        staged[3u * lane] = p.x;
        staged[3u * lane + 1u] = p.y;
        staged[3u * lane + 2u] = p.z;
    }
    workgroupBarrier();
    for (var k = 0u; k < 3u; k++) {
        let e = k * WORKGROUP_SIZE + lane;
        if (e < 3u * count) {
            positions[base + e] = staged[e];
        }
    }
}

// Vertex i of the dispatch's instance z, bound by `binding` in `cell` (its cell's record).
fn deform_in_cell(i: u32, z: u32, binding: GpuBinding, cell: CellCoeffs) {
    let p = position_in_cell(binding, cell);
    let o = z * params.instance_stride + 3u * i;
    positions[o] = p.x;
    positions[o + 1u] = p.y;
    positions[o + 2u] = p.z;
}
