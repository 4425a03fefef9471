// Deformation (paper Eq. 2, extended by the axial offset h) fused with the vertex normals
// through its Jacobian: each bound vertex reads its binding and normal coordinates once and
// writes its position and its normal once (src/deform/jacobian.rs). The positions equal
// deform.wgsl's. Vertices whose one-ring two influences move (falloff bands, hard seams between
// sweeps, unbound vertices beside moving ones) and those whose rings are too coarse for the
// deformation get their normals from the normals pass, which runs after this one
// (src/normals/reach.rs, src/normals/probe.rs).
// Composed after layout.wgsl, cells_uniform.wgsl or cells_storage.wgsl (binding 1: the cell
// records), sweep_eval.wgsl and jacobian.wgsl. Twin: src/cpu/deform.rs (deform_with_normals).
// Every instance in one dispatch: workgroup layer z is instance params.first_instance + z.

@group(0) @binding(0) var<uniform> params: InstanceParams;
@group(0) @binding(2) var<storage, read> bindings: array<vec4<u32>>;
// Tightly packed xyz, instance z at z * params.instance_stride floats, as deform.wgsl's.
@group(0) @binding(3) var<storage, read_write> positions: array<f32>;
// The chunk's normal coordinates records (jacobian.wgsl), one per vertex, shared by instances.
@group(0) @binding(4) var<storage, read> coordinates: array<vec4<f32>>;
// Laid out as the positions.
@group(0) @binding(5) var<storage, read_write> normals: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn deform_normals_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let packed = bindings[i];
    if (!is_plain(packed.x)) {
        return;
    }
    let binding = unpack_plain(packed);
    deform_with_normal_in_cell(i, group.z, binding, cells[(params.first_instance + group.z) * params.cells_per_instance + binding.cell]);
}

// Vertex i of the dispatch's instance z, bound by `binding` in `cell` (its cell's record): its
// position and its normal.
fn deform_with_normal_in_cell(i: u32, z: u32, binding: GpuBinding, cell: CellCoeffs) {
    let record = coordinates[i];
    let frame = point_frame(cell, binding, record.w == NORMAL_BEYOND_END);
    let n = deformed_normal(cell, binding, frame, record);
    let o = z * params.instance_stride + 3u * i;
    positions[o] = frame.position.x;
    positions[o + 1u] = frame.position.y;
    positions[o + 2u] = frame.position.z;
    normals[o] = n.x;
    normals[o + 1u] = n.y;
    normals[o + 2u] = n.z;
}
