// The deform kernel over cell groups (src/gpu/deformer/cell_groups.rs): each invocation deforms
// the CELL_GROUP vertices of one group, which share a cell, reading that cell's record once for
// them all. On a CPU adapter an invocation is a SIMD lane and every record is gathered lane by
// lane, 37 floats a vertex; in groups it is 37 floats per CELL_GROUP vertices. The arithmetic is
// deform.wgsl's, vertex for vertex (deform_in_cell), so the positions are the same to the bit.
// Composed after deform.wgsl. Twin: src/cpu/deform.rs, as deform.wgsl's.

// The chunk's groups: entry CELL_GROUP * g + k is the chunk-relative vertex k of group g (a
// group's vertices share the cell of its first, none is in a falloff band, and a group of fewer
// vertices repeats its first), or UNOWNED in every slot of a free group; the free groups come
// after the params.vertex_count in use, which are all the kernels read.
@group(0) @binding(4) var<storage, read> groups_order: array<u32>;

// One invocation per group, workgroup layer z the dispatch's instance z (as deform_main);
// params.vertex_count counts the chunk's groups in use (copied in by the sort), fewer than the
// dispatch's invocations.
@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_groups_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let g = invocation_index(group, groups, lane);
    if (g >= params.vertex_count) {
        return;
    }
    let first = groups_order[CELL_GROUP * g];
    let z = group.z;
    let cell = cells[(params.first_instance + z) * params.cells_per_instance + plain_cell(bindings[first].x)];
    for (var k = 0u; k < CELL_GROUP; k++) {
        let i = groups_order[CELL_GROUP * g + k];
        deform_in_cell(i, z, unpack_plain(bindings[i]), cell);
    }
}

// Several instances numbered flat, as deform_instances_main: invocation w * group_count + g
// deforms group g of instances w * INSTANCES_PER_INVOCATION onwards, reading the group's
// vertices and bindings once for them all and each instance's cell record once.
@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_groups_instances_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    // No group in use (every vertex in a band): the numbering below would not end.
    if (params.vertex_count == 0u) {
        return;
    }
    let first_invocation = invocation_index(group, groups, 0u);
    var w = first_invocation / params.vertex_count;
    var g = first_invocation - w * params.vertex_count + lane;
    while (g >= params.vertex_count) {
        g -= params.vertex_count;
        w += 1u;
    }
    let z0 = w * INSTANCES_PER_INVOCATION;
    if (z0 >= params.instance_count) {
        return;
    }
    var vertices: array<u32, CELL_GROUP>;
    var members: array<GpuBinding, CELL_GROUP>;
    for (var k = 0u; k < CELL_GROUP; k++) {
        vertices[k] = groups_order[CELL_GROUP * g + k];
        members[k] = unpack_plain(bindings[vertices[k]]);
    }
    let last = min(z0 + INSTANCES_PER_INVOCATION, params.instance_count);
    for (var z = z0; z < last; z++) {
        let cell = cells[(params.first_instance + z) * params.cells_per_instance + members[0].cell];
        for (var k = 0u; k < CELL_GROUP; k++) {
            deform_in_cell(vertices[k], z, members[k], cell);
        }
    }
}
