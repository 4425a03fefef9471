//! Pictures of meshes and their control sweeps, drawn headless with a wgpu render pipeline
//! (works on software Vulkan such as Mesa's lavapipe).
//!
//! Data flow: rig → sweep → bind → deform → **render** (a side branch for looking at results;
//! nothing else depends on it).
//!
//! - [`Scene`]: what is drawn, an opaque layer (meshes with smooth area-weighted normals,
//!   key rings) and a translucent one (sweep surfaces); [`add_sweeps`] tessellates sweeps.
//! - [`Camera`], [`ViewAngles`]: an orbit camera framing a bounding box, Y-up.
//! - [`Renderer`]: the device and pipelines; [`Renderer::render_panels`] draws one or more
//!   scenes side by side with one camera, [`save_png`] writes the picture atomically.
//!
//! ```no_run
//! use sweepffd::mesh::Mesh;
//! use sweepffd_cli::render::{CLAY, Renderer, Scene, ViewAngles, save_png};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let mesh = Mesh::load("bunny.obj".as_ref())?; // the mesh data, without its file
//! let mut scene = Scene::new();
//! scene.add_mesh(&mesh, &mesh.positions, CLAY);
//! let renderer = Renderer::new()?;
//! let picture = renderer.render_panels(&[scene], ViewAngles::default(), 640, 480)?;
//! save_png(&picture, "bunny.png".as_ref())?;
//! # Ok(())
//! # }
//! ```

mod camera;
mod error;
mod pipeline;
mod scene;
mod sweeps;
mod target;

use std::path::Path;

use image::{ImageEncoder, RgbaImage};
use wgpu::util::DeviceExt;

pub use camera::{Camera, FIELD_OF_VIEW_DEGREES, ViewAngles};
pub use error::RenderError;
pub use pipeline::{COLOUR_FORMAT, DEPTH_FORMAT, Pipelines, SAMPLES, SHADE_WGSL, ViewUniform};
pub use scene::{CLAY, Layer, RING, RenderVertex, SWEEP_SURFACE, Scene, union_bounds};
pub use sweeps::{SweepStyle, add_key_ring, add_sweep_surface, add_sweeps};

use sweepffd::atomic_file::write_atomically;
use sweepffd::gpu::GpuContext;
use target::Target;
pub use target::TextureReadback;

/// The background colour of every picture (8-bit RGBA, as stored in the PNG).
pub const BACKGROUND: [u8; 4] = [245, 245, 247, 255];

/// A device with the render pipelines built on it.
#[derive(Debug)]
pub struct Renderer {
    context: GpuContext,
    pipelines: Pipelines,
}

impl Renderer {
    /// A renderer on a device of its own ([`GpuContext::new`]); `Err(NoAdapter)` when no GPU
    /// device can be created.
    pub fn new() -> Result<Renderer, RenderError> {
        let context = GpuContext::new().map_err(RenderError::NoAdapter)?;
        Ok(Renderer::with_context(context))
    }

    /// A renderer on the given device.
    pub fn with_context(context: GpuContext) -> Renderer {
        let pipelines = Pipelines::new(&context.device);
        Renderer { context, pipelines }
    }

    /// The device the renderer draws on.
    pub fn context(&self) -> &GpuContext {
        &self.context
    }

    /// Draws `scenes` side by side, each in a panel of `width` × `height`, into one picture of
    /// `scenes.len()·width` × `height`. One camera from `angles` frames the union of all the
    /// scenes' bounds, so the panels compare like for like.
    pub fn render_panels(
        &self,
        scenes: &[Scene],
        angles: ViewAngles,
        width: u32,
        height: u32,
    ) -> Result<RgbaImage, RenderError> {
        self.render_panels_zoomed(scenes, angles, width, height, None)
    }

    /// [`Renderer::render_panels`] with the camera framing, where `zoom` is `Some((center,
    /// factor))`, the box centred on `center` (scene coordinates) whose sides are the scenes'
    /// bounds divided by `factor` (at least 1): a close-up of one place, the same in every panel.
    pub fn render_panels_zoomed(
        &self,
        scenes: &[Scene],
        angles: ViewAngles,
        width: u32,
        height: u32,
        zoom: Option<(glam::Vec3, f32)>,
    ) -> Result<RgbaImage, RenderError> {
        let panels = scenes.len().max(1) as u32;
        self.check_size(width.saturating_mul(panels), height)?;
        let (min, max) = union_bounds(scenes).ok_or_else(|| RenderError::EmptyScene("the scene is empty".into()))?;
        let (min, max) = match zoom {
            Some((center, factor)) => {
                let half = 0.5 * (max - min) / factor.max(1.0);
                (center - half, center + half)
            }
            None => (min, max),
        };
        let aspect = width as f32 / height as f32;
        let camera = Camera::framing(min, max, angles, aspect);
        let mut picture = RgbaImage::new(width * panels, height);
        for (i, scene) in scenes.iter().enumerate() {
            let panel = self.render(scene, &camera, width, height)?;
            image::imageops::replace(&mut picture, &panel, i64::from(width) * i as i64, 0);
        }
        Ok(picture)
    }

    /// Draws `scene` seen by `camera` into a picture of `width` × `height`: clears to
    /// [`BACKGROUND`], draws the opaque layer, then blends the translucent one over it,
    /// resolves the 4× multisampling and reads the pixels back. Blocks until done.
    pub fn render(&self, scene: &Scene, camera: &Camera, width: u32, height: u32) -> Result<RgbaImage, RenderError> {
        self.check_size(width, height)?;
        if scene.opaque.indices.is_empty() && scene.translucent.indices.is_empty() {
            return Err(RenderError::EmptyScene("the scene has no triangles".into()));
        }
        if scene.has_non_finite() {
            return Err(RenderError::EmptyScene("the scene has a non-finite position".into()));
        }
        let device = &self.context.device;
        let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let target = Target::new(device, width, height);
        self.draw(scene, camera, &target);
        let validation_error = pollster::block_on(validation.pop());
        let memory_error = pollster::block_on(out_of_memory.pop());
        if let Some(error) = validation_error.or(memory_error) {
            return Err(sweepffd::gpu::GpuError::from(error).into());
        }
        target.read(&self.context)
    }

    /// Records and submits the render pass of `scene` into `target`.
    fn draw(&self, scene: &Scene, camera: &Camera, target: &Target) {
        let device = &self.context.device;
        let aspect = target.width as f32 / target.height as f32;
        let uniform = ViewUniform::of(camera, aspect);
        let uniform_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd view"),
            contents: bytemuck::bytes_of(&uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let view_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sweepffd view"),
            layout: &self.pipelines.view_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniform_buffer.as_entire_binding() }],
        });
        let layers = [(&scene.opaque, &self.pipelines.opaque), (&scene.translucent, &self.pipelines.translucent)];
        let buffers: Vec<_> = layers
            .iter()
            .filter(|(layer, _)| !layer.indices.is_empty())
            .map(|(layer, pipeline)| (upload(device, layer), layer.indices.len() as u32, *pipeline))
            .collect();
        let [r, g, b, a] = BACKGROUND.map(|c| f64::from(c) / 255.0);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("render") });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("sweepffd picture"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target.colour,
                    depth_slice: None,
                    resolve_target: Some(&target.resolved_view),
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                        store: wgpu::StoreOp::Discard,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &target.depth,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &view_group, &[]);
            for ((vertices, indices), count, pipeline) in &buffers {
                pass.set_pipeline(pipeline);
                pass.set_vertex_buffer(0, vertices.slice(..));
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..*count, 0, 0..1);
            }
        }
        self.context.queue.submit([encoder.finish()]);
    }

    /// `Err(Size)` unless 1 ≤ width, height ≤ the device's largest 2D texture; `Err(Readback)`
    /// when the picture's readback buffer is larger than the device's largest buffer.
    fn check_size(&self, width: u32, height: u32) -> Result<(), RenderError> {
        let limits = self.context.device.limits();
        let limit = limits.max_texture_dimension_2d;
        if width == 0 || height == 0 || width > limit || height > limit {
            return Err(RenderError::Size { width, height, limit });
        }
        let bytes = target::readback_bytes(width, height);
        if bytes > limits.max_buffer_size {
            return Err(RenderError::Readback { width, height, bytes, limit: limits.max_buffer_size });
        }
        Ok(())
    }
}

/// The vertex and index buffers of a layer.
fn upload(device: &wgpu::Device, layer: &Layer) -> (wgpu::Buffer, wgpu::Buffer) {
    let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sweepffd render vertices"),
        contents: bytemuck::cast_slice(&layer.vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sweepffd render indices"),
        contents: bytemuck::cast_slice(&layer.indices),
        usage: wgpu::BufferUsages::INDEX,
    });
    (vertices, indices)
}

/// Writes `picture` as a PNG file, atomically ([`write_atomically`]): on any error `path` is
/// left as it was.
pub fn save_png(picture: &RgbaImage, path: &Path) -> Result<(), RenderError> {
    write_atomically(path, |out| {
        image::codecs::png::PngEncoder::new(out)
            .write_image(picture.as_raw(), picture.width(), picture.height(), image::ExtendedColorType::Rgba8)
            .map_err(std::io::Error::other)
    })
    .map_err(|e| RenderError::Write { path: path.to_path_buf(), reason: e.to_string() })
}
