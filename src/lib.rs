//! sweepffd: sweep-based freeform deformation of 3D meshes (Yoon & Kim, "Sweep-based Freeform
//! Deformations").
//!
//! Deformable parts of a mesh are approximated by control sweep surfaces built from key
//! cross-sections; every vertex is bound to a sweep by parameters (θ, t, d, h) and follows the
//! sweep through Eq. 2 when the sweep is edited. The data flows through the modules in order:
//!
//! rig → sweep → sweep coefficients → bind → deform → normals → output
//!
//! - [`rig`]: rig and pose files, validation, which sweep owns which vertex.
//! - [`sweep`]: the f64 sweep surface model, C(t), R(t), r(θ, t), and its volume (Eq. 1).
//! - [`fit`]: control sweeps fitted to mesh parts (§3).
//! - [`edit`]: posing by edits: key moves, point drags, hierarchies, volume rules (§4–5).
//! - [`bind`]: binding parameters of each vertex by root-finding (§3).
//! - [`deform`]: vertex positions of a posed rig through Eq. 2.
//! - [`mesh`]: mesh files in and out, enclosed volume.
//! - [`coeffs`]: sweeps as compact f32 coefficient arrays, the GPU buffer layouts.
//! - [`cpu`]: f32 twins of the WGSL kernels in `shaders/`.
//! - [`synthetic`]: procedural meshes, rigs and poses.
//! - [`limits`]: the largest inputs accepted, checked before allocating.
//! - [`render`]: headless pictures of meshes and their control sweeps (PNG).
//! - `view` (feature `viewer`, on by default): the interactive viewer, a winit window drawing
//!   the GPU deformer's buffers, with direct manipulation (§4–5), undo and scripted sessions.
//!
//! ```no_run
//! use glam::DVec3;
//! use sweepffd::{deform::deform_vertices, mesh::Mesh, rig::Rig};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let mesh = Mesh::load("bunny.obj".as_ref())?;
//! let rig = Rig::load("bunny-rig.json".as_ref())?;
//! let owners = rig.owners(&mesh, "bunny.obj")?;
//! let bindings = rig.bind_mesh(&mesh, &owners, &|_| {}); // with the falloff bands, if any
//! let posed = rig.load_pose("bunny-pose.json".as_ref())?;
//! let mut deformed = vec![DVec3::ZERO; mesh.positions.len()];
//! deform_vertices(rig.rest(), &posed, &bindings, &mesh.positions, &mut deformed);
//! mesh.save("bunny-posed.obj".as_ref(), &deformed)?;
//! # Ok(())
//! # }
//! ```

#[cfg(feature = "cli")]
pub mod bench;
pub mod bind;
pub mod coeffs;
pub mod cpu;
pub mod deform;
pub mod edit;
pub mod fit;
pub mod gpu;
pub mod limits;
pub mod mesh;
pub mod normals;
pub mod parallel;
#[cfg(feature = "render")]
pub mod render;
pub mod rig;
pub mod sweep;
pub mod synthetic;
#[cfg(feature = "viewer")]
pub mod view;

// What an embedder's frame loop names, and the two crates whose versions it must match.
pub use coeffs::UNOWNED;
pub use glam;
pub use gpu::{BindingSource, GpuContext, GpuDeformer, GpuError};
pub use mesh::{Faces, Mesh};
pub use rig::{Rig, RigError, RigSweep};
pub use sweep::{Key, Sweep};
pub use wgpu;
