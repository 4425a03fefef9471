// The shading of `sweepffd render` pictures and of the viewer's window. Its pipelines are built
// in src/render/pipeline.rs (vertex layout `RenderVertex`, uniform `ViewUniform` in
// src/render/scene.rs and src/render/pipeline.rs); the same entry points draw the opaque and the
// translucent layers, and the deformed mesh from the deformer's separate position and normal
// buffers with its colour per instance, or per vertex (8-bit unorm, read as the same vec4).
//
// Two-sided Lambert: the normal is flipped towards the eye, so faces wound either way and open
// surfaces light the same from both sides. Light = ambient + a key light + a headlight; colours
// are linear and the result is gamma-encoded (1/2.2) for the 8-bit, non-sRGB target.

struct View {
    // Clip from world (wgpu depth 0..1).
    view_proj: mat4x4<f32>,
    // The camera position (xyz, w = 1).
    eye: vec4<f32>,
    // The unit direction towards the key light (xyz, w = 0).
    light: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: View;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec4<f32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec4<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = view.view_proj * vec4<f32>(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.colour = v.colour;
    return out;
}

const AMBIENT: f32 = 0.12;
const KEY: f32 = 0.75;
const HEAD: f32 = 0.28;

@fragment
fn fs_main(f: VertexOut) -> @location(0) vec4<f32> {
    let to_eye = normalize(view.eye.xyz - f.world);
    // A zero normal (a vertex with no area around it) is lit as if it faced the eye.
    var n = to_eye;
    if dot(f.normal, f.normal) > 1e-20 {
        n = normalize(f.normal);
    }
    if dot(n, to_eye) < 0.0 {
        n = -n;
    }
    let key = max(dot(n, view.light.xyz), 0.0);
    let head = max(dot(n, to_eye), 0.0);
    let lit = f.colour.rgb * (AMBIENT + KEY * key + HEAD * head);
    let encoded = pow(clamp(lit, vec3<f32>(0.0), vec3<f32>(1.0)), vec3<f32>(1.0 / 2.2));
    return vec4<f32>(encoded, f.colour.a);
}
