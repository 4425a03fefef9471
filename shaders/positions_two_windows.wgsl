// position(v) for the normals kernel when the positions need two storage bindings: vertices
// below params.window_split come from the first window, the others from the second.
// Composed between layout.wgsl and normals.wgsl, which declares the windows.
fn position(v: u32) -> vec3<f32> {
    if (v < params.window_split) {
        return vec3<f32>(positions_low[3u * v], positions_low[3u * v + 1u], positions_low[3u * v + 2u]);
    }
    let w = v - params.window_split;
    return vec3<f32>(positions_high[3u * w], positions_high[3u * w + 1u], positions_high[3u * w + 2u]);
}
