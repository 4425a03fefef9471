//! Drawing a frame: the deformed mesh straight from the deformer's position and normal buffers
//! (the buffers a host application draws; nothing is read back), the selected part over it, the
//! key rings and the translucent sweep surfaces. Buffers are created once and rewritten in
//! place; the overlay's grow only when an edit makes them larger. The weight paint's per-vertex
//! colours are uploaded when first shown and again only when the weights change.

use glam::Vec3;
use wgpu::util::DeviceExt;

use super::ViewError;
use crate::render::{BACKGROUND, Layer, Pipelines, Scene, ViewUniform};
use sweepffd::bind::falloff::BandWeight;
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer};
use sweepffd::mesh::Mesh;
use sweepffd::normals::{NormalAdjacency, vertex_normals};
use sweepffd::rig::Rig;

/// Colour of a part selected for fitting (linear RGBA).
pub const SELECTED_PART: [f32; 4] = [0.12, 0.55, 0.25, 1.0];
/// Colour of the selected key's ring (linear RGBA).
pub const SELECTED_RING: [f32; 4] = [0.95, 0.55, 0.02, 1.0];
/// Colour of the rings at the ends of a bend drag's span (linear RGBA).
pub const BEND_SPAN_RING: [f32; 4] = [0.95, 0.75, 0.02, 1.0];
/// Colour of the rings across a stretch of a sweep that folds (linear RGBA).
pub const FOLD_RING: [f32; 4] = [0.9, 0.02, 0.02, 1.0];
/// Rings drawn across each stretch that folds.
pub const FOLD_RINGS: usize = 7;

/// Where the mesh's vertices come from.
pub enum MeshSource {
    /// Deformed on the GPU by the rig's pose.
    Deformed(Box<GpuDeformer>),
    /// No rig yet: the rest mesh, uploaded once.
    Rest { positions: wgpu::Buffer, normals: wgpu::Buffer },
}

/// The mesh's GPU buffers.
pub struct MeshDraw {
    /// The vertex source.
    pub source: MeshSource,
    indices: wgpu::Buffer,
    index_count: u32,
    clay: wgpu::Buffer,
    highlight: wgpu::Buffer,
    selection: GrowingBuffer,
    /// One colour per vertex (the weight paint), made the first time it is shown.
    weight_colours: Option<wgpu::Buffer>,
    /// The weights changed since the colours were written.
    weights_stale: bool,
    /// Whether the mesh is drawn in its weight colours rather than in clay.
    painting: bool,
}

impl MeshDraw {
    /// Uploads `mesh`'s triangles once and, with a rig, binds its vertices on the GPU (`owners`
    /// from [`Rig::owners`], `bands` from [`Rig::band_weights`]).
    pub fn new(
        context: &GpuContext,
        mesh: &Mesh,
        rig: Option<(&Rig, &[u32], &[BandWeight])>,
    ) -> Result<MeshDraw, ViewError> {
        let device = &context.device;
        let source = match rig {
            Some((rig, owners, bands)) => {
                let bindings = BindingSource::Bind { owners, bands };
                let positions = sweepffd::gpu::rest_positions(&mesh.positions);
                let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
                let descriptor = DeformerDescriptor::new(rig.rest(), &positions, bindings).with_triangles(&triangles);
                let deformer = GpuDeformer::new(context, &descriptor).map_err(|e| ViewError::Gpu(e.to_string()))?;
                MeshSource::Deformed(Box::new(deformer))
            }
            None => {
                let adjacency = NormalAdjacency::new(&mesh.faces, mesh.positions.len());
                let normals: Vec<[f32; 3]> =
                    vertex_normals(&mesh.positions, &adjacency).iter().map(|n| n.as_vec3().to_array()).collect();
                let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.as_vec3().to_array()).collect();
                MeshSource::Rest {
                    positions: vertex_buffer(device, "sweepffd rest positions", bytemuck::cast_slice(&positions)),
                    normals: vertex_buffer(device, "sweepffd rest normals", bytemuck::cast_slice(&normals)),
                }
            }
        };
        let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd mesh indices"),
            contents: bytemuck::cast_slice(&triangles),
            usage: wgpu::BufferUsages::INDEX,
        });
        let colour = |c: [f32; 4]| vertex_buffer(device, "sweepffd mesh colour", bytemuck::cast_slice(&c));
        Ok(MeshDraw {
            source,
            indices,
            index_count: triangles.len() as u32,
            clay: colour(crate::render::CLAY),
            highlight: colour(SELECTED_PART),
            selection: GrowingBuffer::new("sweepffd selected part", wgpu::BufferUsages::INDEX),
            weight_colours: None,
            weights_stale: true,
            painting: false,
        })
    }

    /// Draws the mesh in its weight colours if `show` (`colours` gives one linear RGBA colour per
    /// vertex; it is called, and its result uploaded, only when the weights changed since they
    /// were last shown), or in clay.
    pub fn show_weights(&mut self, context: &GpuContext, show: bool, colours: impl FnOnce() -> Vec<[u8; 4]>) {
        self.painting = show;
        if !show || (!self.weights_stale && self.weight_colours.is_some()) {
            return;
        }
        let colours = colours();
        let bytes: &[u8] = bytemuck::cast_slice(&colours);
        match &self.weight_colours {
            Some(buffer) => context.queue.write_buffer(buffer, 0, bytes),
            None => self.weight_colours = Some(vertex_buffer(&context.device, "sweepffd weight colours", bytes)),
        }
        self.weights_stale = false;
    }

    /// The weights changed (a new falloff): the colours are written again when next shown.
    pub fn weights_changed(&mut self) {
        self.weights_stale = true;
    }

    /// The deformer, when there is a rig.
    pub fn deformer(&mut self) -> Option<&mut GpuDeformer> {
        match &mut self.source {
            MeshSource::Deformed(deformer) => Some(deformer),
            MeshSource::Rest { .. } => None,
        }
    }

    fn buffers(&self) -> (&wgpu::Buffer, &wgpu::Buffer) {
        match &self.source {
            MeshSource::Deformed(deformer) => {
                (deformer.positions(), deformer.normals().expect("the deformer was given the faces"))
            }
            MeshSource::Rest { positions, normals } => (positions, normals),
        }
    }

    /// The positions drawn now: read back from the deformer (an explicit, blocking call made
    /// on a click, never per frame), or the rest positions.
    pub fn current_positions(&self, mesh: &Mesh) -> Result<Vec<Vec3>, ViewError> {
        match &self.source {
            MeshSource::Deformed(deformer) => {
                let flat = deformer.read_positions().map_err(|e| ViewError::Gpu(e.to_string()))?;
                Ok(flat.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])).collect())
            }
            MeshSource::Rest { .. } => Ok(mesh.positions.iter().map(|p| p.as_vec3()).collect()),
        }
    }

    /// Shows these triangles (three vertex indices each) in the selection colour.
    pub fn set_selection(&mut self, context: &GpuContext, triangles: &[u32]) {
        self.selection.write(context, bytemuck::cast_slice(triangles));
    }
}

fn vertex_buffer(device: &wgpu::Device, label: &str, contents: &[u8]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
    })
}

/// A buffer rewritten in place, reallocated (to the next power of two) only when it must grow.
pub struct GrowingBuffer {
    label: &'static str,
    usage: wgpu::BufferUsages,
    buffer: Option<wgpu::Buffer>,
    len: u64,
}

impl GrowingBuffer {
    /// An empty buffer of `usage` (COPY_DST is added).
    pub fn new(label: &'static str, usage: wgpu::BufferUsages) -> GrowingBuffer {
        GrowingBuffer { label, usage: usage | wgpu::BufferUsages::COPY_DST, buffer: None, len: 0 }
    }

    /// Replaces the contents with `bytes` (a multiple of 4 bytes long).
    pub fn write(&mut self, context: &GpuContext, bytes: &[u8]) {
        self.len = bytes.len() as u64;
        if bytes.is_empty() {
            return;
        }
        if self.buffer.as_ref().is_none_or(|b| b.size() < self.len) {
            self.buffer = Some(context.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(self.label),
                size: self.len.next_power_of_two(),
                usage: self.usage,
                mapped_at_creation: false,
            }));
        }
        context.queue.write_buffer(self.buffer.as_ref().expect("allocated above"), 0, bytes);
    }

    /// The filled part of the buffer, if any.
    fn filled(&self) -> Option<wgpu::BufferSlice<'_>> {
        self.buffer.as_ref().filter(|_| self.len > 0).map(|b| b.slice(..self.len))
    }
}

/// The sweeps' layers on the GPU.
pub struct Overlay {
    layers: [(GrowingBuffer, GrowingBuffer, u32); 2],
}

impl Default for Overlay {
    /// Empty layers.
    fn default() -> Overlay {
        let layer = || {
            (
                GrowingBuffer::new("sweepffd overlay vertices", wgpu::BufferUsages::VERTEX),
                GrowingBuffer::new("sweepffd overlay indices", wgpu::BufferUsages::INDEX),
                0,
            )
        };
        Overlay { layers: [layer(), layer()] }
    }
}

impl Overlay {
    /// Uploads `scene`'s opaque layer (rings) and translucent layer (surfaces).
    pub fn upload(&mut self, context: &GpuContext, scene: &Scene) {
        for ((vertices, indices, count), layer) in self.layers.iter_mut().zip([&scene.opaque, &scene.translucent]) {
            let Layer { vertices: v, indices: i } = layer;
            vertices.write(context, bytemuck::cast_slice(v));
            indices.write(context, bytemuck::cast_slice(i));
            *count = i.len() as u32;
        }
    }
}

/// The pipelines and the per-frame view uniform, created once.
pub struct Drawing {
    /// The render pipelines for the window's format.
    pub pipelines: Pipelines,
    uniform: wgpu::Buffer,
    group: wgpu::BindGroup,
}

impl Drawing {
    /// Builds the pipelines for `format`.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Drawing {
        let pipelines = Pipelines::for_target(device, format);
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd viewer view"),
            size: std::mem::size_of::<ViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sweepffd viewer view"),
            layout: &pipelines.view_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() }],
        });
        Drawing { pipelines, uniform, group }
    }

    /// Records the scene's render pass: clear, mesh, selected part, rings, then the
    /// translucent surfaces, in the `viewport` (width, height from the top left); multisampled
    /// into `colour`/`depth`, resolved into `target`.
    #[expect(clippy::too_many_arguments, reason = "the frame's targets and the two things drawn, each used once")]
    pub fn encode(
        &self,
        context: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        view: &ViewUniform,
        viewport: glam::Vec2,
        (colour, depth, target): (&wgpu::TextureView, &wgpu::TextureView, &wgpu::TextureView),
        mesh: &MeshDraw,
        overlay: &Overlay,
    ) {
        context.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(view));
        let [r, g, b, a] = BACKGROUND.map(|c| f64::from(c) / 255.0);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("sweepffd viewer scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: colour,
                depth_slice: None,
                resolve_target: Some(target),
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                    store: wgpu::StoreOp::Discard,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_viewport(0.0, 0.0, viewport.x, viewport.y, 0.0, 1.0);
        pass.set_bind_group(0, &self.group, &[]);
        let (positions, normals) = mesh.buffers();
        pass.set_vertex_buffer(0, positions.slice(..));
        pass.set_vertex_buffer(1, normals.slice(..));
        pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
        match mesh.weight_colours.as_ref().filter(|_| mesh.painting) {
            Some(colours) => {
                pass.set_pipeline(&self.pipelines.mesh_painted);
                pass.set_vertex_buffer(2, colours.slice(..));
            }
            None => {
                pass.set_pipeline(&self.pipelines.mesh);
                pass.set_vertex_buffer(2, mesh.clay.slice(..));
            }
        }
        pass.draw_indexed(0..mesh.index_count, 0, 0..1);
        if let Some(selection) = mesh.selection.filled() {
            pass.set_pipeline(&self.pipelines.mesh);
            pass.set_vertex_buffer(2, mesh.highlight.slice(..));
            pass.set_index_buffer(selection, wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..(mesh.selection.len / 4) as u32, 0, 0..1);
        }
        let pipelines = [&self.pipelines.opaque, &self.pipelines.translucent];
        for ((vertices, indices, count), pipeline) in overlay.layers.iter().zip(pipelines) {
            if let (Some(vertices), Some(indices), true) = (vertices.filled(), indices.filled(), *count > 0) {
                pass.set_pipeline(pipeline);
                pass.set_vertex_buffer(0, vertices);
                pass.set_index_buffer(indices, wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..*count, 0, 0..1);
            }
        }
    }
}
