// The fused deform + Jacobian normals kernel over cell groups (src/gpu/deformer/cell_groups.rs),
// as deform_groups.wgsl is the deform kernel's: each invocation deforms the CELL_GROUP vertices of
// one group, reading their cell's record once, and writes each one's position and normal as
// deform_normals_main does, vertex for vertex (deform_with_normal_in_cell).
// Composed after deform_normals.wgsl. Twin: src/cpu/deform.rs (deform_with_normals).

// The chunk's groups, laid out as deform_groups.wgsl's.
@group(0) @binding(6) var<storage, read> normal_groups: array<u32>;

// One invocation per group, workgroup layer z the dispatch's instance z; params.vertex_count
// counts the chunk's groups in use (copied in by the sort).
@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_normals_groups_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let g = invocation_index(group, groups, lane);
    if (g >= params.vertex_count) {
        return;
    }
    let z = group.z;
    let first = normal_groups[CELL_GROUP * g];
    let cell = cells[(params.first_instance + z) * params.cells_per_instance + plain_cell(bindings[first].x)];
    for (var k = 0u; k < CELL_GROUP; k++) {
        let i = normal_groups[CELL_GROUP * g + k];
        deform_with_normal_in_cell(i, z, unpack_plain(bindings[i]), cell);
    }
}
