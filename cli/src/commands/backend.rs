//! `--backend cpu|reference|gpu|auto`: where binding and deformation run.

use clap::ValueEnum;
use sweepffd::gpu::{GpuContext, GpuError};

/// Where the per-vertex work runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// The fast f32 path on all CPU cores: the GPU kernels' arithmetic, eight vertices to a
    /// register where the CPU has AVX2 and FMA.
    Cpu,
    /// The f64 reference path on all CPU cores, the oracle the others are checked against.
    Reference,
    /// The WGSL kernels; an error if no GPU adapter is available.
    Gpu,
    /// The GPU if an adapter is available, else the fast CPU path with a one-line notice.
    #[default]
    Auto,
}

/// Where a command runs, once the backend is resolved.
pub enum Device {
    /// The WGSL kernels on this device.
    Gpu(Box<GpuContext>),
    /// The fast f32 CPU path ([`sweepffd::cpu_fast`]).
    Cpu,
    /// The f64 reference path ([`sweepffd::bind`], [`sweepffd::deform`]).
    Reference,
}

impl Device {
    /// How the command's summary line names it.
    pub fn name(&self) -> &'static str {
        match self {
            Device::Gpu(_) => "GPU",
            Device::Cpu => "CPU",
            Device::Reference => "f64 reference",
        }
    }
}

/// The device a command runs on.
pub fn resolve(backend: Backend, quiet: bool) -> Result<Device, GpuError> {
    match backend {
        Backend::Cpu => Ok(Device::Cpu),
        Backend::Reference => Ok(Device::Reference),
        Backend::Gpu => GpuContext::new().map(|context| Device::Gpu(Box::new(context))),
        Backend::Auto => match GpuContext::new() {
            Ok(context) => Ok(Device::Gpu(Box::new(context))),
            Err(error) => {
                if !quiet {
                    note!("note: using the CPU, the GPU is not available: {error}");
                }
                Ok(Device::Cpu)
            }
        },
    }
}
