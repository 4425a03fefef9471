//! What can go wrong while drawing a picture.

use std::path::PathBuf;

use thiserror::Error;

use sweepffd::gpu::GpuError;

/// An error of the renderer. wgpu validation errors are caught with error scopes and returned
/// here, never as panics.
#[derive(Debug, Error)]
pub enum RenderError {
    /// No GPU device could be created.
    #[error("render needs a GPU adapter (none found: {0})")]
    NoAdapter(GpuError),
    /// The GPU failed while drawing or reading back.
    #[error("rendering failed on the GPU: {0}")]
    Gpu(#[from] GpuError),
    /// The picture size is zero or larger than the device's textures allow.
    #[error("the picture size {width}x{height} is out of range (each side from 1 to {limit} pixels)")]
    Size { width: u32, height: u32, limit: u32 },
    /// The picture's readback buffer is larger than the device's largest buffer.
    #[error(
        "the picture size {width}x{height} needs a readback buffer of {bytes} bytes, over the device's limit of {limit}"
    )]
    Readback { width: u32, height: u32, bytes: u64, limit: u64 },
    /// The view angles are not finite, or the elevation is outside [−90°, 90°].
    #[error("the view azimuth {azimuth}°, elevation {elevation}° is out of range (elevation from -90 to 90)")]
    View { azimuth: f32, elevation: f32 },
    /// The scene has no triangle to draw, or a non-finite position.
    #[error("nothing to draw: {0}")]
    EmptyScene(String),
    /// The PNG file could not be written.
    #[error("cannot write {path}: {reason}")]
    Write { path: PathBuf, reason: String },
}
