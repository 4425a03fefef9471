//! The offscreen target of one picture (multisampled colour and depth, a resolved colour
//! texture) and its readback into an [`image::RgbaImage`] through rows padded to 256 bytes.

use image::RgbaImage;

use super::RenderError;
use super::pipeline::{COLOUR_FORMAT, DEPTH_FORMAT, SAMPLES};
use sweepffd::gpu::{GpuContext, GpuError, read_staging};

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

/// The bytes of one row of a readback of `width` pixels, padded as copies need.
fn padded_row(width: u32) -> u32 {
    (4 * width).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// The bytes of the readback buffer of a `width` × `height` picture.
pub fn readback_bytes(width: u32, height: u32) -> u64 {
    u64::from(padded_row(width)) * u64::from(height)
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

    /// Copies the resolved texture to the CPU (after all submitted work) as an RGBA image.
    pub fn read(&self, context: &GpuContext) -> Result<RgbaImage, RenderError> {
        let device = &context.device;
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
        let readback = TextureReadback::record(&mut encoder, device, &self.resolved);
        context.queue.submit([encoder.finish()]);
        let pixels = readback.finish(context)?;
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| GpuError::Validation("the picture readback has the wrong size".to_string()).into())
    }
}

/// A copy of a 4-byte-per-texel texture into a mappable buffer, through rows padded to wgpu's
/// 256-byte alignment: pictures and window screenshots.
#[derive(Debug)]
pub struct TextureReadback {
    staging: wgpu::Buffer,
    width: u32,
    height: u32,
    padded_row: u32,
}

impl TextureReadback {
    /// Records the copy of `texture` into `encoder`.
    pub fn record(
        encoder: &mut wgpu::CommandEncoder,
        device: &wgpu::Device,
        texture: &wgpu::Texture,
    ) -> TextureReadback {
        let (width, height) = (texture.width(), texture.height());
        let padded_row = padded_row(width);
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd texture readback"),
            size: u64::from(padded_row) * u64::from(height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        );
        TextureReadback { staging, width, height, padded_row }
    }

    /// The texels row after row without padding, once the copy has been submitted (blocks
    /// until the GPU is done).
    pub fn finish(self, context: &GpuContext) -> Result<Vec<u8>, GpuError> {
        let padded_rows = read_staging(context, &self.staging)?;
        let row = 4 * self.width as usize;
        Ok(padded_rows
            .chunks_exact(self.padded_row as usize)
            .take(self.height as usize)
            .flat_map(|r| &r[..row])
            .copied()
            .collect())
    }
}
