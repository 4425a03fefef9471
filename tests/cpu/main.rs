//! The CPU paths and editing through the public API: hierarchies, edit controls, posing into
//! buffers. The twins and the fast path against the reference are unit tests of `cpu` and
//! `cpu_fast`.

#[path = "../common/mod.rs"]
mod common;

mod bunny_ears_scene;
mod edit_controls;
mod hierarchy;
mod keep_length;
mod pose_into;
mod pose_warnings;
