//! The GPU engine through its public API: construction, the inputs it refuses, and the embed
//! example. The kernels against their twins are unit tests of `gpu` (`src/gpu/tests`).

#[path = "../common/mod.rs"]
mod common;

mod bend_limbs;
mod construction;
mod embed_example;
mod engine_inputs;
