//! `--backend cpu|gpu|auto`: where binding and deformation run.

use clap::ValueEnum;
use sweepffd::gpu::{GpuContext, GpuError};

/// Where the per-vertex work runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// The f64 reference path on all CPU cores.
    Cpu,
    /// The WGSL kernels; an error if no GPU adapter is available.
    Gpu,
    /// The GPU if an adapter is available, else the CPU with a one-line notice.
    #[default]
    Auto,
}

/// The GPU device to use, or `None` for the CPU path.
pub fn resolve(backend: Backend, quiet: bool) -> Result<Option<GpuContext>, GpuError> {
    match backend {
        Backend::Cpu => Ok(None),
        Backend::Gpu => GpuContext::new().map(Some),
        Backend::Auto => match GpuContext::new() {
            Ok(context) => Ok(Some(context)),
            Err(error) => {
                if !quiet {
                    eprintln!("note: using the CPU, the GPU is not available: {error}");
                }
                Ok(None)
            }
        },
    }
}
