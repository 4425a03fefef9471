//! The fast CPU path: the f32 kernels of `crate::cpu` (the twins of the WGSL shaders)
//! vectorized across vertices and run on every core, for machines without a GPU.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind → deform → (Jacobian) normals** → output.
//!
//! The inputs and outputs are the GPU's ([`crate::coeffs`]: cell records, [`GpuBinding`]s,
//! band records, tightly packed f32 positions), so a binding made here deforms on the GPU and
//! back. [`deform::deform`] evaluates Eq. 2 (+h) eight vertices to a register where the CPU has
//! AVX2 and FMA ([`Isa`], detected at run time), one by one elsewhere; [`bind::bind`] runs the
//! twin's root finding eight vertices to a register (with the twin's rounding), in parallel and
//! without allocating; [`deform::deform_with_normals`] fuses the deform with the vertex normals
//! carried through Eq. 2's parameter Jacobian, likewise; falloff band vertices, few, go through
//! the band twin ([`bands`]). Results equal the twins' to rounding, not bit for bit;
//! the f64 reference ([`crate::bind`], [`crate::deform`]) stays the oracle.
//!
//! [`GpuBinding`]: crate::coeffs::GpuBinding

pub mod bands;
pub mod bind;
#[cfg(target_arch = "x86_64")]
mod bind_avx2;
pub mod deform;
#[cfg(target_arch = "x86_64")]
mod deform_avx2;
mod deform_normals;
#[cfg(target_arch = "x86_64")]
mod deform_normals_avx2;
mod isa;
#[cfg(target_arch = "x86_64")]
mod lanes8;
pub mod mesh;

/// Positions as the fast path takes them: f32, tightly packed xyz.
pub use crate::cpu::packed;

/// Vertices per parallel task: big enough that scheduling is noise, small enough for two
/// threads to share the work evenly at 100k vertices.
pub const CHUNK: usize = 16 * 1024;
pub use isa::Isa;
pub use mesh::FastMesh;

#[cfg(test)]
mod tests;
