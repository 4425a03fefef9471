// Replacing the falloff bands without binding again (GpuDeformer::set_bands): for each vertex
// whose membership changes, sets or clears BAND_FLAG in its binding's cell (the deform kernel
// skips flagged vertices and the band kernel moves them), and writes the rest position of a
// vertex that keeps it in the new bands (w = 0 against the rest position), which the band
// kernel never writes. Runs over one dispatch's changes; each vertex appears at most once.
// Composed after layout.wgsl. Twin: src/cpu/band_flags.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(1) var<storage, read> flags: array<BandFlag>;
@group(0) @binding(2) var<storage, read_write> bindings: array<vec4<u32>>;
// Tightly packed xyz; the window of the dispatch's vertices.
@group(0) @binding(3) var<storage, read_write> positions: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn band_flags_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let flag = flags[i];
    let v = flag.vertex & ~(BAND_FLAG | KEEPS_REST);
    let cell = bindings[v].x;
    // An unbound vertex is in no band (UNOWNED has BAND_FLAG set already and stays as it is).
    if (cell == UNOWNED) {
        return;
    }
    bindings[v].x = (cell & ~BAND_FLAG) | (flag.vertex & BAND_FLAG);
    if ((flag.vertex & KEEPS_REST) != 0u) {
        positions[3u * v] = flag.x;
        positions[3u * v + 1u] = flag.y;
        positions[3u * v + 2u] = flag.z;
    }
}
