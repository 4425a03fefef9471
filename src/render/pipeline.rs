//! The two render pipelines of a picture, both from `shaders/render/shade.wgsl`: the opaque one
//! (depth test and write, back faces kept for two-sided shading) and the translucent one (depth
//! test without write, alpha blending over what is drawn). Both render 4× multisampled into an
//! 8-bit RGBA target with a 32-bit float depth buffer.

use std::borrow::Cow;

use bytemuck::{Pod, Zeroable};

use super::scene::RenderVertex;

/// The composed render shader, validated with naga at build time (`build.rs`).
pub const SHADE_WGSL: &str = include_str!(concat!(env!("OUT_DIR"), "/render_shade.wgsl"));

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

/// The pipelines and the layout of their view bind group, created once per renderer.
#[derive(Debug)]
pub struct Pipelines {
    /// Meshes and rings.
    pub opaque: wgpu::RenderPipeline,
    /// Sweep surfaces.
    pub translucent: wgpu::RenderPipeline,
    /// Group 0: the [`ViewUniform`].
    pub view_layout: wgpu::BindGroupLayout,
}

impl Pipelines {
    /// Compiles the shader and builds both pipelines.
    pub fn new(device: &wgpu::Device) -> Pipelines {
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
        let opaque = pipeline(device, &layout, &module, "sweepffd opaque", true, None);
        let translucent =
            pipeline(device, &layout, &module, "sweepffd translucent", false, Some(wgpu::BlendState::ALPHA_BLENDING));
        Pipelines { opaque, translucent, view_layout }
    }
}

/// The vertex buffer layout of [`RenderVertex`]: position, normal, colour at locations 0–2.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4];

/// One pipeline of `shade.wgsl`: depth-tested, writing depth if `depth_write`, blending with
/// `blend` (replacing without).
fn pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    label: &str,
    depth_write: bool,
    blend: Option<wgpu::BlendState>,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<RenderVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &VERTEX_ATTRIBUTES,
            })],
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
            module,
            entry_point: Some("fs_main"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: COLOUR_FORMAT,
                blend,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
