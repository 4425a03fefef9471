// position(v) for the normals kernel when every position fits one storage binding.
// Composed between layout.wgsl and normals.wgsl, which declares the windows.
fn position(v: u32) -> vec3<f32> {
    return vec3<f32>(positions_low[3u * v], positions_low[3u * v + 1u], positions_low[3u * v + 2u]);
}
