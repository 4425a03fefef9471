//! The GPU engine: binding (§3) and Eq. 2 in WGSL compute shaders on wgpu, with the output
//! buffers ready for the host application to draw.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind → deform → normals → tangents** (on the GPU) →
//! output buffers.
//!
//! The kernels in `shaders/` have CPU twins in `crate::cpu`; tests prove the GPU agrees with
//! them (and with the f64 reference) on lavapipe.

mod bands;
pub(crate) mod binder;
pub(crate) mod buffers;
mod chunks;
mod context;
pub(crate) mod deformer;
mod error;
mod input_error;
mod kernel_cache;
mod normals_pass;
mod readback;
mod tangents_pass;

internal_mod! {
    kernels;
    shaders;
}

pub use bands::BAND_STRIDE;
pub use buffers::{BINDING_STRIDE, POSITION_STRIDE};
pub use chunks::{ChunkLimits, dispatch_grid, normal_chunks, uniform_chunks};
pub use context::GpuContext;
pub use deformer::{
    BOUNDS_STRIDE, BindingSource, ChunkGroups, DeformOrder, DeformerDescriptor, GpuDeformer, INSTANCE_ALIGNMENT,
    OutputBuffer,
};
pub use error::GpuError;
pub use input_error::InputError;
pub use kernels::{CellRecords, DeformVariant};
pub use readback::{read_bytes, read_staging, wait};
pub use tangents_pass::TANGENT_STRIDE;

/// f64 positions as the engine takes them: f32 xyz (rounded to nearest).
pub fn rest_positions(positions: &[glam::DVec3]) -> Vec<[f32; 3]> {
    positions.iter().map(|p| p.as_vec3().to_array()).collect()
}

/// An app's `Vec3` positions (or normals) as the engine takes them, without a copy: glam's
/// `Vec3` is three f32 in order, 12 bytes, as `[f32; 3]` (`Vec3A`, 16 bytes, is not).
///
/// ```
/// let positions = [sweepffd::glam::Vec3::new(1.0, 2.0, 3.0)];
/// assert_eq!(sweepffd::gpu::vec3_positions(&positions), &[[1.0, 2.0, 3.0]]);
/// ```
pub fn vec3_positions(positions: &[glam::Vec3]) -> &[[f32; 3]] {
    bytemuck::cast_slice(positions)
}

#[cfg(test)]
mod tests;
