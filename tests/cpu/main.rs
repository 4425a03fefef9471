//! The CPU paths and editing: the fast f32 path against the reference, binding, round trips and
//! properties, hierarchies, edit controls and posing into buffers.

#[path = "../common/mod.rs"]
mod common;

mod binding;
mod bunny_ears_scene;
mod cpu_fast;
mod cpu_fast_normals;
mod edit_controls;
mod hierarchy;
mod pose_into;
mod properties;
mod round_trip;
