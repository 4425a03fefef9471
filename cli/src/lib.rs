//! The `sweepffd` application over the sweepffd engine: the command line ([`run`]), the
//! interactive viewer ([`view`], feature `viewer`, on by default) and headless PNG pictures of
//! meshes and their control sweeps ([`render`]).

#[macro_use]
mod console;
mod commands;
pub mod render;
#[cfg(feature = "viewer")]
pub mod view;

pub use commands::run;
