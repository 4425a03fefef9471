//! Hostile and broken input through the command line and the readers: clear errors, no panics,
//! bounded memory, and the fuzz regression corpus.

#[path = "../common/mod.rs"]
mod common;

mod allocation_bombs;
mod bad_input;
mod fuzz_regressions;
mod hostile_cli;
mod hostile_fit;
mod hostile_gltf;
mod hostile_groups;
mod hostile_mesh;
mod hostile_rig;
mod mesh_formats;
