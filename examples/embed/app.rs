//! The host application's side of `embed.rs`: its own render pipeline drawing the deformer's
//! position and normal buffers as vertex buffers, one draw per instance, into an offscreen
//! colour and depth target, and the picture read back as a PNG.

use std::path::Path;

use sweepffd::{GpuDeformer, wgpu};
use wgpu::util::DeviceExt;

const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Instance i is drawn shifted by (i − 2)·2.2 along x; an orthographic camera looks down −z.
const SHADER: &str = "
struct Out { @builtin(position) clip: vec4<f32>, @location(0) normal: vec3<f32> }

@vertex
fn vs(@builtin(instance_index) i: u32, @location(0) p: vec3<f32>, @location(1) n: vec3<f32>) -> Out {
    let x = p.x + (f32(i) - 2.0) * 2.2;
    return Out(vec4<f32>(x / 5.5, (p.y - 1.0) / 5.5, 0.5 - p.z / 8.0, 1.0), n);
}

@fragment
fn fs(v: Out) -> @location(0) vec4<f32> {
    let light = max(dot(normalize(v.normal), normalize(vec3<f32>(0.4, 0.6, 0.7))), 0.0);
    return vec4<f32>(vec3<f32>(0.85, 0.62, 0.45) * (0.25 + 0.75 * light), 1.0);
}
";

pub struct App {
    pipeline: wgpu::RenderPipeline,
    indices: wgpu::Buffer,
    index_count: u32,
    color: wgpu::Texture,
    depth: wgpu::TextureView,
    size: u32,
}

impl App {
    pub fn new(device: &wgpu::Device, triangles: &[u32], size: u32) -> App {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("app shading"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        // Our position and normal buffers: tightly packed f32 xyz, 12 bytes a vertex.
        let layout = |attributes| wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes,
        };
        let buffers =
            [layout(&wgpu::vertex_attr_array![0 => Float32x3]), layout(&wgpu::vertex_attr_array![1 => Float32x3])];
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("app mesh"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &buffers.map(Some),
            },
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(COLOR.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("app indices"),
            contents: bytemuck::cast_slice(triangles),
            usage: wgpu::BufferUsages::INDEX,
        });
        let texture = |format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some("app target"),
                size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = texture(COLOR, wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC);
        let depth = texture(DEPTH, wgpu::TextureUsages::RENDER_ATTACHMENT).create_view(&Default::default());
        App { pipeline, indices, index_count: triangles.len() as u32, color, depth, size }
    }

    /// Records the app's render pass after the deformer's dispatches in the same encoder: every
    /// instance drawn from the deformer's buffers, instance i's vertices from i·n on.
    pub fn draw(&self, encoder: &mut wgpu::CommandEncoder, deformer: &GpuDeformer) {
        let view = self.color.create_view(&Default::default());
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("app mesh"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::WHITE), store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_vertex_buffer(0, deformer.positions().slice(..));
        pass.set_vertex_buffer(1, deformer.normals().expect("the deformer was given triangles").slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        for i in 0..deformer.instance_count() {
            let first_vertex = (i * deformer.vertex_count()) as i32;
            pass.draw_indexed(0..self.index_count, first_vertex, i..i + 1);
        }
    }

    /// Reads the last frame back and writes it as a PNG.
    pub fn save(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        path: &Path,
    ) -> Result<(), Box<dyn std::error::Error>> {
        let row = 4 * self.size; // a multiple of 256 for the sizes used here
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("app readback"),
            size: (row * self.size) as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            self.color.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None },
            },
            self.color.size(),
        );
        queue.submit([encoder.finish()]);
        staging.slice(..).map_async(wgpu::MapMode::Read, |_| {});
        device.poll(wgpu::PollType::wait_indefinitely())?;
        let pixels = staging.slice(..).get_mapped_range()?.to_vec();
        let picture = image::RgbaImage::from_raw(self.size, self.size, pixels).ok_or("a picture of the wrong size")?;
        picture.save_with_format(path, image::ImageFormat::Png)?;
        Ok(())
    }
}
