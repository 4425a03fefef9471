//! The GPU engine: binding (§3) and Eq. 2 in WGSL compute shaders on wgpu, with the output
//! buffers ready for the host application to draw.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind → deform → normals** (on the GPU) →
//! output buffers.
//!
//! The kernels in `shaders/` have CPU twins in [`crate::cpu`]; tests prove the GPU agrees with
//! them (and with the f64 reference) on lavapipe.

pub(crate) mod binder;
mod chunks;
mod context;
pub(crate) mod deformer;
mod error;
pub mod kernels;
mod readback;
pub mod shaders;

pub use chunks::{ChunkLimits, dispatch_grid, normal_chunks, uniform_chunks};
pub use context::GpuContext;
pub use deformer::{BINDING_STRIDE, BindingSource, DeformVariant, GpuDeformer, POSITION_STRIDE};
pub use error::GpuError;
pub use readback::{read_bytes, wait};
