//! The GPU engine: WGSL kernels against their f32 twins and the f64 reference, instances, normals,
//! tangents, bounds, the naga layout checks, the zero-allocation frame and the embed example.

#[path = "../common/mod.rs"]
mod common;

mod cell_groups;
mod construction;
mod embed_example;
mod engine_inputs;
mod equivalence;
mod frame_allocations;
mod instances;
mod jacobian_normals;
mod normal_fans;
mod outputs;
mod partial_normals;
mod shader_layout;
mod tangents;
