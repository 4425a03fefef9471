//! Fitting and autorig through the public API: fits of real parts and autorig end to end. The
//! fitting machinery's own tests are unit tests of `fit` (`src/fit/tests`).

#[path = "../common/mod.rs"]
mod common;

mod autorig_pipeline;
mod bend_limbs;
mod fit;
