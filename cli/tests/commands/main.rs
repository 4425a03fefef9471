//! The `sweepffd` commands end to end: bind, deform, pose, fit, autorig, volume, render, the viewer
//! and the picture examples.

#[path = "../common/mod.rs"]
mod common;

mod autorig;
mod batch;
mod cli;
mod edit_time;
mod examples;
mod export;
mod falloff_cli;
mod far_meshes;
mod fit_cli;
mod pose_cli;
mod render;
mod rotation_cli;
mod viewer;
