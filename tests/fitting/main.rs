//! Fitting and autorig: sweeps fitted to parts (§3), skeletons, sections, autorig on stars and real
//! meshes, falloff bands.

#[path = "../common/mod.rs"]
mod common;

mod autorig_pipeline;
mod autorig_star;
mod falloff;
mod falloff_meshes;
mod falloff_rebind;
mod fit;
mod fit_sections;
mod fit_skeleton;
