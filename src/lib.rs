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
//! - [`bind`]: binding parameters of each vertex by root-finding (§3).
//! - [`deform`]: vertex positions of a posed rig through Eq. 2.
//! - [`mesh`]: mesh files in and out, enclosed volume.

pub mod bind;
pub mod coeffs;
pub mod cpu;
pub mod deform;
pub mod mesh;
pub mod rig;
pub mod sweep;
pub mod synthetic;
