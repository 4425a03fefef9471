//! Mesh files in and out: OBJ, PLY, OFF and glTF read and written faithfully, and whole scenes
//! through them.

#[path = "../common/mod.rs"]
mod common;

mod io_scene;
mod mesh_io;
