// Falloff bands: each vertex with weight w < 1 follows its own sweep part of the way, its frame
// blended with its second influence's (blend.wgsl): the rest position, or a neighbouring sweep's
// frame at the vertex. The deform kernel skips these vertices (BAND_FLAG); this kernel runs over
// the band records of one dispatch's vertices only.
// Every instance in one dispatch: workgroup layer z is instance params.first_instance + z, whose
// posed cells start at (first_instance + z) * cells_per_instance (the rest cells are shared).
// Composed after layout.wgsl, cells_*.wgsl (binding 1: the posed cells), rest_cells_*.wgsl
// (binding 4: the rest cells), sweep_eval.wgsl and blend.wgsl. Twin: src/cpu/band.rs.

@group(0) @binding(0) var<uniform> params: InstanceParams;
@group(0) @binding(2) var<storage, read> bindings: array<vec4<u32>>;
// Tightly packed xyz, instance z at z * params.instance_stride floats into the window.
@group(0) @binding(3) var<storage, read_write> positions: array<f32>;
@group(0) @binding(5) var<storage, read> bands: array<BandRecord>;

// (s, phi) of a band record's second influence, from two unorm16.
fn unpack_s_phi(packed: u32) -> vec2<f32> {
    return vec2<f32>(f32(packed & 0xffffu), f32(packed >> 16u)) * (1.0 / 65535.0);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn band_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let band = bands[i];
    // At weight 0 against the rest position the vertex keeps the rest position written at bind time.
    if (band.cell == UNOWNED && band.weight == 0.0) {
        return;
    }
    let binding = unpack_binding(bindings[band.vertex]);
    let cell = binding.cell & ~BAND_FLAG;
    let rest = rest_cells[cell];
    let frame = rest_frame(rest, binding.s, binding.phi);
    let local = (frame.radius + binding.d) * frame.direction + vec3<f32>(0.0, 0.0, binding.h);
    let rest_center = curve_at(rest, binding.s);
    let rest_offset = rotate(frame.turn, local);
    let base = (params.first_instance + group.z) * params.cells_per_instance;
    let own = sweep_influence(cells[base + cell], frame, binding.s, binding.phi, rest_offset);
    var second = Influence(rest_center, vec4<f32>(0.0, 0.0, 0.0, 1.0), rest_offset);
    if (band.cell != UNOWNED) {
        let at = unpack_s_phi(band.s_phi);
        let other = rest_cells[band.cell];
        let offset = rest_center + rest_offset - curve_at(other, at.x);
        second = sweep_influence(cells[base + band.cell], rest_frame(other, at.x, at.y), at.x, at.y, offset);
    }
    let p = blend(second, own, band.weight);
    let o = group.z * params.instance_stride + 3u * band.vertex;
    positions[o] = p.x;
    positions[o + 1u] = p.y;
    positions[o + 2u] = p.z;
}
