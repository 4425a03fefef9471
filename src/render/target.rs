//! The offscreen target of one picture (multisampled colour and depth, a resolved colour
//! texture) and its readback into an [`image::RgbaImage`] through rows padded to 256 bytes.

use image::RgbaImage;

use super::RenderError;
use super::pipeline::{COLOUR_FORMAT, DEPTH_FORMAT, SAMPLES};
use crate::gpu::{GpuContext, GpuError, read_staging};

/// The textures a picture of `width` × `height` is drawn into.
#[derive(Debug)]
pub struct Target {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The multisampled colour attachment.
    pub colour: wgpu::TextureView,
    /// The multisampled depth attachment.
    pub depth: wgpu::TextureView,
    /// The single-sample texture the colour is resolved into (`COPY_SRC`).
    pub resolved: wgpu::Texture,
    /// A view of `resolved`.
    pub resolved_view: wgpu::TextureView,
}

impl Target {
    /// Creates the textures; the size must have been checked against the device's limits.
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Target {
        let texture = |label: &str, format, samples, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let colour = texture("sweepffd colour", COLOUR_FORMAT, SAMPLES, attachment);
        let depth = texture("sweepffd depth", DEPTH_FORMAT, SAMPLES, attachment);
        let resolved = texture("sweepffd resolved", COLOUR_FORMAT, 1, attachment | wgpu::TextureUsages::COPY_SRC);
        let view = |t: &wgpu::Texture| t.create_view(&wgpu::TextureViewDescriptor::default());
        Target { width, height, colour: view(&colour), depth: view(&depth), resolved_view: view(&resolved), resolved }
    }

    /// Bytes per row of the readback buffer: 4·width rounded up to wgpu's 256-byte alignment.
    pub fn padded_row(&self) -> u32 {
        (4 * self.width).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
    }

    /// Copies the resolved texture to the CPU (after all submitted work) as an RGBA image.
    pub fn read(&self, context: &GpuContext) -> Result<RgbaImage, RenderError> {
        let (device, padded) = (&context.device, self.padded_row());
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd picture readback"),
            size: u64::from(padded) * u64::from(self.height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
        encoder.copy_texture_to_buffer(
            self.resolved.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d { width: self.width, height: self.height, depth_or_array_layers: 1 },
        );
        context.queue.submit([encoder.finish()]);
        let padded_rows = read_staging(context, &staging)?;
        let row = 4 * self.width as usize;
        let pixels: Vec<u8> = padded_rows.chunks_exact(padded as usize).flat_map(|r| &r[..row]).copied().collect();
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| GpuError::Validation("the picture readback has the wrong size".to_string()).into())
    }
}
