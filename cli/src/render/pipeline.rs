//! The render pipelines, all from `shaders/shade.wgsl`: the opaque one (depth test and
//! write, back faces kept for two-sided shading), the translucent one (depth test without write,
//! alpha blending over what is drawn), and the deformed-mesh one, which reads positions and
//! normals from two separate buffers (a [`GpuDeformer`](sweepffd::gpu::GpuDeformer)'s outputs) and
//! one colour per instance. All render 4× multisampled with a 32-bit float depth buffer, into an
//! 8-bit RGBA picture or an application's window.

use std::borrow::Cow;

use bytemuck::{Pod, Zeroable};

use super::camera::Camera;
use super::scene::RenderVertex;

/// The composed render shader, validated with naga at build time (`build.rs`).
pub const SHADE_WGSL: &str = include_str!(concat!(env!("OUT_DIR"), "/shade.wgsl"));

/// Samples per pixel of the colour and depth targets (resolved before readback).
pub const SAMPLES: u32 = 4;
/// The colour target: 8-bit RGBA holding gamma-encoded values (the shader encodes).
pub const COLOUR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// The depth target.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The uniform the shader reads as `View` (group 0, binding 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ViewUniform {
    /// Clip from world, column-major.
    pub view_proj: [[f32; 4]; 4],
    /// Camera position, w = 1.
    pub eye: [f32; 4],
    /// Unit direction towards the key light, w = 0.
    pub light: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<ViewUniform>() == 96);

impl ViewUniform {
    /// The uniform of `camera` for a picture of width/height `aspect`.
    pub fn of(camera: &Camera, aspect: f32) -> ViewUniform {
        ViewUniform {
            view_proj: camera.view_projection(aspect).to_cols_array_2d(),
            eye: camera.eye.extend(1.0).to_array(),
            light: camera.key_light().extend(0.0).to_array(),
        }
    }
}

/// The pipelines and the layout of their view bind group, created once per renderer.
#[derive(Debug)]
pub struct Pipelines {
    /// Meshes and rings.
    pub opaque: wgpu::RenderPipeline,
    /// Sweep surfaces.
    pub translucent: wgpu::RenderPipeline,
    /// A deformed mesh: buffer 0 positions, buffer 1 normals (tightly packed f32 xyz each, as a
    /// [`GpuDeformer`](sweepffd::gpu::GpuDeformer) writes them), buffer 2 one linear RGBA colour
    /// per instance; opaque.
    pub mesh: wgpu::RenderPipeline,
    /// The same with one colour per vertex in buffer 2: linear RGBA as 8-bit unorm (4 bytes a
    /// vertex), e.g. the viewer's weight paint.
    pub mesh_painted: wgpu::RenderPipeline,
    /// Group 0: the [`ViewUniform`].
    pub view_layout: wgpu::BindGroupLayout,
}

impl Pipelines {
    /// Compiles the shader and builds the pipelines for pictures ([`COLOUR_FORMAT`]).
    pub fn new(device: &wgpu::Device) -> Pipelines {
        Pipelines::for_target(device, COLOUR_FORMAT)
    }

    /// Compiles the shader and builds the pipelines for a colour target of `format` (e.g. a
    /// window surface's). The shader gamma-encodes its output itself, so `format` should not be
    /// an sRGB one.
    pub fn for_target(device: &wgpu::Device, format: wgpu::TextureFormat) -> Pipelines {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("sweepffd render"),
            source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(SHADE_WGSL)),
        });
        let view_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sweepffd render view"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<ViewUniform>() as u64),
                },
                count: None,
            }],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("sweepffd render"),
            bind_group_layouts: &[Some(&view_layout)],
            immediate_size: 0,
        });
        let shade = Shade { device, layout: &layout, module: &module, format };
        let opaque = shade.pipeline("sweepffd opaque", &INTERLEAVED, true, None);
        let translucent =
            shade.pipeline("sweepffd translucent", &INTERLEAVED, false, Some(wgpu::BlendState::ALPHA_BLENDING));
        let mesh = shade.pipeline("sweepffd deformed mesh", &SPLIT, true, None);
        let mesh_painted = shade.pipeline("sweepffd painted mesh", &SPLIT_PAINTED, true, None);
        Pipelines { opaque, translucent, mesh, mesh_painted, view_layout }
    }
}

/// The vertex buffer layout of [`RenderVertex`]: position, normal, colour at locations 0–2.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4];

/// One interleaved [`RenderVertex`] buffer.
const INTERLEAVED: [Option<wgpu::VertexBufferLayout<'static>>; 1] = [Some(wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<RenderVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &VERTEX_ATTRIBUTES,
})];

/// Positions in a buffer of their own (12 bytes a vertex), at location 0.
const POSITION_STREAM: Option<wgpu::VertexBufferLayout<'static>> = Some(wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
});

/// Normals in a buffer of their own (12 bytes a vertex), at location 1.
const NORMAL_STREAM: Option<wgpu::VertexBufferLayout<'static>> = Some(wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![1 => Float32x3],
});

/// Positions and normals in buffers of their own, the colour per instance.
const SPLIT: [Option<wgpu::VertexBufferLayout<'static>>; 3] = [
    POSITION_STREAM,
    NORMAL_STREAM,
    Some(wgpu::VertexBufferLayout {
        array_stride: 16,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![2 => Float32x4],
    }),
];

/// Positions and normals as in [`SPLIT`], one 8-bit RGBA colour per vertex.
const SPLIT_PAINTED: [Option<wgpu::VertexBufferLayout<'static>>; 3] = [
    POSITION_STREAM,
    NORMAL_STREAM,
    Some(wgpu::VertexBufferLayout {
        array_stride: 4,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![2 => Unorm8x4],
    }),
];

/// What every pipeline of `shade.wgsl` shares.
struct Shade<'a> {
    device: &'a wgpu::Device,
    layout: &'a wgpu::PipelineLayout,
    module: &'a wgpu::ShaderModule,
    format: wgpu::TextureFormat,
}

impl Shade<'_> {
    /// One pipeline reading `buffers`: depth-tested, writing depth if `depth_write`, blending
    /// with `blend` (replacing without).
    fn pipeline(
        &self,
        label: &str,
        buffers: &[Option<wgpu::VertexBufferLayout>],
        depth_write: bool,
        blend: Option<wgpu::BlendState>,
    ) -> wgpu::RenderPipeline {
        self.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(self.layout),
            vertex: wgpu::VertexState {
                module: self.module,
                entry_point: Some("vs_main"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                buffers,
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(depth_write),
                depth_compare: Some(wgpu::CompareFunction::LessEqual),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState { count: SAMPLES, mask: !0, alpha_to_coverage_enabled: false },
            fragment: Some(wgpu::FragmentState {
                module: self.module,
                entry_point: Some("fs_main"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: self.format,
                    blend,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use std::mem::{offset_of, size_of};

    use super::SHADE_WGSL;
    use crate::render::{RenderVertex, ViewUniform};

    #[test]
    fn render_view_uniform_has_the_rust_layout() {
        let module =
            naga::front::wgsl::parse_str(SHADE_WGSL).unwrap_or_else(|e| panic!("{}", e.emit_to_string(SHADE_WGSL)));
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).unwrap();
        let (handle, ty) = module.types.iter().find(|(_, ty)| ty.name.as_deref() == Some("View")).unwrap();
        let naga::TypeInner::Struct { members, .. } = &ty.inner else {
            panic!("View is not a struct");
        };
        assert_eq!(layouter[handle].size as usize, size_of::<ViewUniform>());
        let wgsl: Vec<(&str, usize)> =
            members.iter().map(|m| (m.name.as_deref().unwrap_or("?"), m.offset as usize)).collect();
        let rust = [
            ("view_proj", offset_of!(ViewUniform, view_proj)),
            ("eye", offset_of!(ViewUniform, eye)),
            ("light", offset_of!(ViewUniform, light)),
        ];
        assert_eq!(wgsl, rust);
        // The vertex buffer layout packs position, normal and colour back to back (Float32x3,
        // Float32x3, Float32x4), which is RenderVertex's field order.
        assert_eq!(
            [offset_of!(RenderVertex, position), offset_of!(RenderVertex, normal), offset_of!(RenderVertex, colour)],
            [0, 12, 24]
        );
    }
}
