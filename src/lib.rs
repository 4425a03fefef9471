//! sweepffd: sweep-based freeform deformation of 3D meshes (Yoon & Kim, "Sweep-based Freeform
//! Deformations"), on the GPU in an application's own frame loop.
//!
//! Deformable parts of a mesh are approximated by control sweep surfaces built from key
//! cross-sections; every vertex is bound to a sweep by parameters (θ, t, d, h) and follows the
//! sweep through Eq. 2 when the sweep is edited. An application hands over its wgpu device,
//! builds a [`GpuDeformer`] once from a [`DeformerDescriptor`] (a [`Rig`] of [`RigSweep`]s through
//! [`Key`] cross-sections, f32 positions, a [`BindingSource`]), and each frame poses its rigs and
//! records the deformation into its own command encoder, then draws our buffers.
//! `examples/embed.rs` is that frame loop, complete and compile-checked, with every instance
//! checked against the f64 reference ([`Rig::deform_reference`]).
//!
//! The data flows rig → sweep coefficients → bind → deform → normals → output. The modules,
//! each importing only those listed before it:
//!
//! - [`layout`]: the GPU buffer layouts shared with the WGSL, and [`UNOWNED`].
//! - [`limits`]: the largest inputs accepted, checked before allocating.
//! - [`atomic_file`]: files written whole or not at all.
//! - [`names`]: names in error messages, a few listed and the rest counted.
//! - [`sweep`]: the f64 sweep surface model, C(t), R(t), r(θ, t), and its volume (Eq. 1).
//! - [`mesh`]: meshes in code: positions, faces, groups, and their measures.
//! - `formats` (feature `formats`): mesh files in and out, OBJ, PLY, OFF and glTF, written back
//!   faithfully.
//! - [`coeffs`]: sweeps as compact f32 coefficient arrays (the sweep coefficients).
//! - [`bind`]: binding parameters of each vertex by root-finding (§3).
//! - [`frame`]: a frame local to a part, where the f32 paths keep their accuracy wherever the
//!   part sits and whatever its size.
//! - [`normals`]: vertex normals and tangents, and which vertices a deformation can reach,
//!   f64 reference.
//! - [`rig`]: rigs built in code or read from files (feature `json`), which sweep owns which
//!   vertex, the hierarchy (§5), posing.
//! - [`deform`]: vertex positions of a posed rig through Eq. 2, and their Jacobian normals, f64
//!   reference.
//! - `bindings_file` (feature `json`): bindings saved for a rig and mesh.
//! - [`fit`]: control sweeps fitted to mesh parts (§3), and autorig.
//! - [`synthetic`]: procedural meshes and rigs.
//! - [`edit`]: posing by edits: key moves, point drags, hierarchies, volume rules (§4–5).
//! - [`cpu_fast`]: the fast CPU path, the kernels vectorized across vertices (AVX2 + FMA where
//!   the CPU has them) on every core.
//! - [`gpu`]: the engine: binding, Eq. 2, normals, tangents and bounds in WGSL compute.
//! - `bench` (feature `bench`): the throughput measurements of `sweepffd bench` and the
//!   criterion benches.
//!
//! The f32 twins of the WGSL kernels (`cpu`), the kernels themselves and the spline and fitting
//! machinery are internals, public only with the feature `internals` (for the benches `cpu` and
//! `fit`); the equivalence tests are unit tests of the modules that own them.
//!
//! The command line, the interactive viewer and the PNG renderer are the workspace member
//! `sweepffd-cli` (`cli/`), so that this crate's default build pulls no app crates.
//!
//! On the CPU, with files (features `formats` and `parallel`):
//!
//! ```no_run
//! # #[cfg(feature = "formats")]
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use sweepffd::glam::DVec3;
//! use sweepffd::{deform::deform_vertices, formats::LoadedMesh, rig::Rig};
//!
//! let file = LoadedMesh::load("bunny.obj".as_ref())?;
//! let mesh = &file.mesh;
//! let rig = Rig::load("bunny-rig.json".as_ref())?;
//! let owners = rig.owners(&mesh, "bunny.obj")?;
//! let bindings = rig.bind_mesh(&mesh, &owners, &|_| {}); // with the falloff bands, if any
//! let posed = rig.load_pose("bunny-pose.json".as_ref())?;
//! let mut deformed = vec![DVec3::ZERO; mesh.positions.len()];
//! deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut deformed);
//! file.save("bunny-posed.obj".as_ref(), &deformed)?;
//! # Ok(())
//! # }
//! # #[cfg(not(feature = "formats"))]
//! # fn main() {}
//! ```

/// Declares modules that are the engine's internals: the CPU twins of the kernels, the kernels
/// and shaders themselves, the spline and fitting machinery. They are public with the feature
/// `internals`, which the benches `cpu` and `fit` use (no stable API), and
/// crate-private otherwise, so that an embedder's documentation shows what it builds on.
macro_rules! internal_mod {
    ($($(#[$attr:meta])* $name:ident;)*) => {$(
        #[cfg(feature = "internals")]
        $(#[$attr])*
        pub mod $name;
        #[cfg(not(feature = "internals"))]
        #[allow(dead_code, unused_imports, reason = "some of its items serve only the benches and tests (feature internals)")]
        $(#[$attr])*
        pub(crate) mod $name;
    )*};
}

/// Declares methods that are the engine's internals: public with the feature `internals` (the
/// benches and tests inspect a deformer's dispatches and GPU-side records with them),
/// crate-private otherwise.
macro_rules! internal_fn {
    ($(#[$attr:meta])* fn $name:ident $($rest:tt)*) => {
        #[cfg(feature = "internals")]
        $(#[$attr])*
        pub fn $name $($rest)*
        #[cfg(not(feature = "internals"))]
        #[allow(dead_code, reason = "the benches and tests use it, with the feature internals")]
        $(#[$attr])*
        pub(crate) fn $name $($rest)*
    };
}

#[cfg(feature = "bench")]
pub mod bench;
pub mod bind;
#[cfg(feature = "json")]
pub mod bindings_file;
pub mod coeffs;
internal_mod! {
    cpu;
    parallel;
}
pub mod atomic_file;
pub mod cpu_fast;
pub mod deform;
pub mod edit;
pub mod fit;
#[cfg(feature = "formats")]
pub mod formats;
pub mod frame;
pub mod gpu;
pub mod layout;
pub mod limits;
pub mod mesh;
pub mod names;
pub mod normals;
pub mod rig;
pub mod sweep;
pub mod synthetic;

// The unit tests name the crate as the integration tests do, and share their helpers.
#[cfg(test)]
extern crate self as sweepffd;
#[cfg(test)]
#[path = "../tests/common/mod.rs"]
mod common;

// What an embedder's frame loop names, and the two crates whose versions it must match.
pub use glam;
pub use gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, GpuError};
pub use layout::UNOWNED;
pub use mesh::{Faces, Mesh};
pub use rig::{Rig, RigError, RigSweep, VertexSelection};
pub use sweep::{Key, Sweep};
pub use wgpu;
