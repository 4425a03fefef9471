//! What can go wrong on the GPU path.

use thiserror::Error;

use super::InputError;
use crate::coeffs::StructureMismatch;
use crate::rig::RigError;

/// An error of the GPU engine. wgpu validation errors are caught with error scopes and
/// returned here, never as panics.
#[derive(Debug, Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter is available (install a Vulkan, Metal or DX12 driver; on Linux without a GPU, Mesa's software Vulkan: apt-get install mesa-vulkan-drivers)"
    )]
    NoAdapter,
    #[error("the GPU adapter {adapter} does not run compute shaders")]
    NoCompute { adapter: String },
    #[error("the GPU adapter {adapter} could not create a device: {reason}")]
    Device { adapter: String, reason: String },
    #[error("{what} needs {needed} bytes in one buffer, more than this device allows ({limit} bytes)")]
    TooLarge { what: &'static str, needed: u64, limit: u64 },
    #[error("invalid input for the GPU deformer: {0}")]
    Input(#[from] InputError),
    #[error("invalid input for the GPU deformer: {0}")]
    Rig(#[from] RigError),
    #[error("wgpu reported a validation error: {0}")]
    Validation(String),
    #[error("the GPU ran out of memory: {0}")]
    OutOfMemory(String),
    #[error("the GPU device was lost: {0}")]
    DeviceLost(String),
    #[error(transparent)]
    Structure(#[from] StructureMismatch),
}

impl From<wgpu::Error> for GpuError {
    fn from(error: wgpu::Error) -> GpuError {
        match error {
            wgpu::Error::OutOfMemory { source } => GpuError::OutOfMemory(source.to_string()),
            wgpu::Error::Validation { description, .. } => GpuError::Validation(description),
            wgpu::Error::Internal { description, .. } => GpuError::Validation(description),
        }
    }
}
