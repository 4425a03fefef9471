//! The window's GPU: a device created for the window's surface (and handed to the deformer, as
//! a host application hands its own), the surface configuration, the 4× multisampled colour
//! and depth targets, and screenshots read back from the presented texture.

use std::sync::Arc;

use image::RgbaImage;
use winit::window::Window;

use super::ViewError;
use crate::render::{DEPTH_FORMAT, SAMPLES, TextureReadback};
use sweepffd::gpu::GpuContext;

/// The surface and the targets drawn into before it.
pub struct WindowGpu {
    /// The device, shared with the deformer.
    pub context: GpuContext,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The format pipelines render in: the surface's without sRGB encoding (the shaders encode).
    pub format: wgpu::TextureFormat,
    /// Multisampled colour target, resolved into the surface texture.
    pub colour: wgpu::TextureView,
    /// Multisampled depth target.
    pub depth: wgpu::TextureView,
    /// Whether the surface texture can be copied out (screenshots).
    pub readable: bool,
    /// The last configuration failed (the window system can refuse one for a moment, e.g.
    /// while a window moves); retried before the next frame.
    unconfigured: bool,
}

impl WindowGpu {
    /// Creates the device for `window` on `instance`; `vsync` off presents as fast as possible
    /// (scripted sessions measure frame times that way).
    pub fn new(instance: &wgpu::Instance, window: Arc<Window>, vsync: bool) -> Result<WindowGpu, ViewError> {
        let size = window.inner_size();
        let surface = instance.create_surface(window).map_err(|e| ViewError::Gpu(format!("no window surface: {e}")))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            compatible_surface: Some(&surface),
            force_fallback_adapter: false,
            apply_limit_buckets: false,
        }))
        .map_err(|e| ViewError::Gpu(format!("no GPU adapter can draw into the window: {e}")))?;
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("sweepffd viewer"),
            required_features: wgpu::Features::empty(),
            required_limits: adapter.limits(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| ViewError::Gpu(format!("{}: cannot create a device: {e}", info.name)))?;
        let capabilities = surface.get_capabilities(&adapter);
        let surface_format = capabilities
            .formats
            .iter()
            .copied()
            .find(|f| matches!(f, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm))
            .or_else(|| capabilities.formats.first().copied())
            .ok_or_else(|| ViewError::Gpu(format!("{}: the window surface offers no format", info.name)))?;
        let format = surface_format.remove_srgb_suffix();
        let readable = capabilities.usages.contains(wgpu::TextureUsages::COPY_SRC);
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        if readable {
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        let present_mode = if vsync { wgpu::PresentMode::AutoVsync } else { wgpu::PresentMode::AutoNoVsync };
        let config = wgpu::SurfaceConfiguration {
            usage,
            format: surface_format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
            desired_maximum_frame_latency: 2,
            alpha_mode: capabilities.alpha_modes.first().copied().unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: if format == surface_format { vec![] } else { vec![format] },
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&device, &config);
        let (colour, depth) = targets(&device, format, config.width, config.height);
        let context = GpuContext::from_device(device, queue, info);
        Ok(WindowGpu { context, surface, config, format, colour, depth, readable, unconfigured: false })
    }

    /// The surface size in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Reconfigures for a new window size (ignored while minimised).
    pub fn resize(&mut self, width: u32, height: u32) {
        if width == 0 || height == 0 || (width, height) == self.size() {
            return;
        }
        self.config.width = width;
        self.config.height = height;
        self.configure();
        (self.colour, self.depth) = targets(&self.context.device, self.format, width, height);
    }

    /// Applies the configuration; a refusal is remembered (not a panic) and retried.
    fn configure(&mut self) {
        let scope = self.context.device.push_error_scope(wgpu::ErrorFilter::Validation);
        self.surface.configure(&self.context.device, &self.config);
        self.unconfigured = pollster::block_on(scope.pop()).is_some();
    }

    /// The next surface texture, or `None` when this frame cannot be drawn (the surface is
    /// reconfigured where that helps).
    pub fn acquire(&mut self) -> Option<wgpu::SurfaceTexture> {
        if self.unconfigured {
            self.configure();
            if self.unconfigured {
                return None;
            }
        }
        let scope = self.context.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let acquired = self.surface.get_current_texture();
        let refused = pollster::block_on(scope.pop()).is_some();
        match acquired {
            wgpu::CurrentSurfaceTexture::Success(texture) if !refused => Some(texture),
            // Drawn now, reconfigured for the next frame.
            wgpu::CurrentSurfaceTexture::Suboptimal(texture) if !refused => {
                self.unconfigured = true;
                Some(texture)
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.configure();
                None
            }
            _ => None,
        }
    }

    /// The view pipelines draw into on `texture`.
    pub fn view_of(&self, texture: &wgpu::SurfaceTexture) -> wgpu::TextureView {
        texture.texture.create_view(&wgpu::TextureViewDescriptor { format: Some(self.format), ..Default::default() })
    }
}

/// The multisampled colour and depth targets of a `width` × `height` window.
fn targets(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
    width: u32,
    height: u32,
) -> (wgpu::TextureView, wgpu::TextureView) {
    let target = |label: &str, format| {
        device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: SAMPLES,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                view_formats: &[],
            })
            .create_view(&wgpu::TextureViewDescriptor::default())
    };
    (target("sweepffd window colour", format), target("sweepffd window depth", DEPTH_FORMAT))
}

/// A screenshot being copied out of a surface texture.
pub struct Capture {
    readback: TextureReadback,
    width: u32,
    height: u32,
    bgra: bool,
}

impl Capture {
    /// Records the copy of `texture` (before it is presented) into `encoder`.
    pub fn record(encoder: &mut wgpu::CommandEncoder, device: &wgpu::Device, texture: &wgpu::Texture) -> Capture {
        let bgra = matches!(texture.format().remove_srgb_suffix(), wgpu::TextureFormat::Bgra8Unorm);
        let readback = TextureReadback::record(encoder, device, texture);
        Capture { readback, width: texture.width(), height: texture.height(), bgra }
    }

    /// The picture, once the copy has been submitted (blocks until the GPU is done).
    pub fn finish(self, context: &GpuContext) -> Result<RgbaImage, ViewError> {
        let mut pixels = self.readback.finish(context).map_err(|e| ViewError::Gpu(e.to_string()))?;
        for pixel in pixels.chunks_exact_mut(4) {
            if self.bgra {
                pixel.swap(0, 2);
            }
            pixel[3] = 255;
        }
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| ViewError::Gpu("the screenshot has the wrong size".into()))
    }
}
