//! The device the engine runs on: the host application's, or one of its own.

use std::sync::{Arc, Mutex};

use super::GpuError;
use super::kernel_cache::KernelCache;

/// A wgpu device and queue, with a description of the adapter behind them.
///
/// Real-time applications pass their own device ([`GpuContext::from_device`]); tools and tests
/// let the engine create one ([`GpuContext::new`]). Clones share the device and its compiled
/// pipelines: build every deformer from one context (or its clones) to compile each kernel once.
#[derive(Clone, Debug)]
pub struct GpuContext {
    /// The device every buffer and pipeline is created on.
    pub device: wgpu::Device,
    /// The queue work is submitted to.
    pub queue: wgpu::Queue,
    /// The adapter's name, backend and driver.
    pub info: wgpu::AdapterInfo,
    lost: Arc<Mutex<Option<String>>>,
    /// The device's pipelines, compiled once and shared by every deformer on this context and
    /// its clones.
    kernels: Arc<KernelCache>,
}

impl GpuContext {
    /// Creates a device on the best adapter: the one named by the `WGPU_ADAPTER_NAME`
    /// environment variable if set, else the high-performance one, on the backends of
    /// `WGPU_BACKEND` (default: Vulkan, Metal, DX12). Requests the adapter's own limits (so large
    /// meshes fit) and timestamp queries where supported. Blocks (pollster).
    pub fn new() -> Result<GpuContext, GpuError> {
        pollster::block_on(GpuContext::new_async())
    }

    async fn new_async() -> Result<GpuContext, GpuError> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle();
        descriptor.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
        let instance = wgpu::Instance::new(descriptor);
        let adapter = pick_adapter(&instance).await.ok_or(GpuError::NoAdapter)?;
        let info = adapter.get_info();
        if !adapter.get_downlevel_capabilities().flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS) {
            return Err(GpuError::NoCompute { adapter: info.name });
        }
        let required_features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("sweepffd"),
                required_features,
                required_limits: adapter.limits(),
                experimental_features: wgpu::ExperimentalFeatures::disabled(),
                memory_hints: wgpu::MemoryHints::Performance,
                trace: wgpu::Trace::Off,
            })
            .await
            .map_err(|e| GpuError::Device { adapter: info.name.clone(), reason: e.to_string() })?;
        let lost = Arc::new(Mutex::new(None));
        let flag = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut lost) = flag.lock() {
                *lost = Some(format!("{reason:?}: {message}"));
            }
        });
        Ok(GpuContext { device, queue, info, lost, kernels: Arc::default() })
    }

    /// Wraps a host application's device and queue; `info` describes its adapter.
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue, info: wgpu::AdapterInfo) -> GpuContext {
        GpuContext { device, queue, info, lost: Arc::new(Mutex::new(None)), kernels: Arc::default() }
    }

    /// `Err(DeviceLost)` if the device created by [`GpuContext::new`] has been lost.
    pub fn check_alive(&self) -> Result<(), GpuError> {
        match self.lost.lock().ok().and_then(|lost| lost.clone()) {
            Some(reason) => Err(GpuError::DeviceLost(reason)),
            None => Ok(()),
        }
    }

    /// The device's pipelines, compiled on first use.
    pub(crate) fn kernels(&self) -> &KernelCache {
        &self.kernels
    }

    /// Number of compute pipelines the engine has compiled on this context (and its clones):
    /// each kernel and variant once, however many deformers are built.
    pub fn compiled_pipelines(&self) -> usize {
        self.kernels.compiled()
    }

    /// Whether timestamp queries are enabled on the device.
    pub fn has_timestamps(&self) -> bool {
        self.device.features().contains(wgpu::Features::TIMESTAMP_QUERY)
    }
}

async fn pick_adapter(instance: &wgpu::Instance) -> Option<wgpu::Adapter> {
    if let Ok(wanted) = std::env::var("WGPU_ADAPTER_NAME") {
        let wanted = wanted.to_lowercase();
        return instance
            .enumerate_adapters(wgpu::Backends::all())
            .await
            .into_iter()
            .find(|adapter| adapter.get_info().name.to_lowercase().contains(&wanted));
    }
    instance
        .request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        })
        .await
        .ok()
}
