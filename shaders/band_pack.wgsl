// Packs the bind kernel's bindings of band vertices to their neighbouring sweeps into the band
// records' second influence: the cell (UNOWNED: the rest position) and (s, phi) as two unorm16.
// Composed after layout.wgsl. Twin: src/cpu/band_pack.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(1) var<storage, read> second_bindings: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read_write> bands: array<BandRecord>;

// x in [0, 1] as a 16-bit fixed-point value, rounded to nearest.
fn unorm16(x: f32) -> u32 {
    return u32(floor(clamp(x, 0.0, 1.0) * 65535.0 + 0.5));
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn band_pack_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let second = unpack_binding(second_bindings[i]);
    bands[i].cell = second.cell;
    bands[i].s_phi = unorm16(second.s) | (unorm16(second.phi) << 16u);
}
