// The normal coordinates of every vertex of a deform chunk (jacobian.wgsl), made once at
// creation from the rest cells, the bindings and the rest normals: what deform_normals.wgsl
// carries to the deformed normal each frame. Band vertices get theirs too (their normals come
// from the normals pass, but new falloff bands may release them); unbound vertices get zero.
// Composed after layout.wgsl, cells_uniform.wgsl or cells_storage.wgsl (binding 1: the rest
// cell records), sweep_eval.wgsl and jacobian.wgsl. Twin: src/cpu/jacobian.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(2) var<storage, read> bindings: array<vec4<u32>>;
// The chunk's window of the rest normals, tightly packed xyz.
@group(0) @binding(3) var<storage, read> rest_normals: array<f32>;
@group(0) @binding(4) var<storage, read_write> coordinates: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn normal_coords_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let binding = unpack_binding(bindings[i]);
    if (binding.cell == UNOWNED) {
        coordinates[i] = vec4<f32>(0.0);
        return;
    }
    let n = vec3<f32>(rest_normals[3u * i], rest_normals[3u * i + 1u], rest_normals[3u * i + 2u]);
    var own = binding;
    own.cell = binding.cell & ~BAND_FLAG;
    coordinates[i] = normal_coordinates(cells[own.cell], own, n);
}
