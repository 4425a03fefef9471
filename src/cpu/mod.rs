//! CPU twins of the WGSL kernels: f32 code that mirrors `shaders/*.wgsl` statement by
//! statement, file for file (`shaders/bind.wgsl` ↔ [`bind`], `shaders/deform.wgsl` ↔
//! [`deform`], `shaders/band.wgsl` ↔ [`band`], `shaders/band_pack.wgsl` ↔ [`band_pack`],
//! `shaders/band_flags.wgsl` ↔ [`band_flags`], `shaders/cell_order.wgsl` ↔ [`cell_order`], `shaders/normals.wgsl` ↔ [`normals`],
//! `shaders/tangents.wgsl` ↔ [`tangents`], and the shared `shaders/sweep_eval.wgsl` ↔
//! [`sweep_eval`], `shaders/jacobian.wgsl` ↔ [`jacobian`], `shaders/angle.wgsl` ↔ [`angle`], `shaders/blend.wgsl` ↔ [`blend`]; the
//! benchmark baselines `shaders/copy.wgsl` ↔ [`copy`],
//! `shaders/skinning.wgsl` ↔ [`skinning`]).
//!
//! They are the executable specification of the GPU path: tests check them against the f64
//! reference ([`crate::bind`], [`crate::deform`]) tightly and against the GPU within named
//! tolerances, so a divergence can be bisected stage by stage. Each runs every invocation of
//! its kernel, in parallel over the vertices.

pub mod angle;
pub mod band;
pub mod band_flags;
pub mod band_pack;
pub mod bind;
pub mod blend;
pub mod bounds;
pub mod cell_order;
pub mod copy;
pub mod deform;
mod gpu_bindings;
pub mod jacobian;
pub mod normals;
pub mod skinning;
pub mod sweep_eval;
pub mod tangents;

use glam::{DVec3, Vec3};

/// Positions as the kernels take them: f32, tightly packed xyz.
pub fn packed(positions: &[DVec3]) -> Vec<f32> {
    positions.iter().flat_map(|p| p.as_vec3().to_array()).collect()
}

/// The vertex at index `i` of a tightly packed xyz array.
pub(crate) fn position(positions: &[f32], i: usize) -> Vec3 {
    Vec3::new(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2])
}

#[cfg(test)]
mod tests;
