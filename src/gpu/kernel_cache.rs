//! The compute pipelines of one device, compiled the first time a deformer needs each and then
//! shared by every deformer (and binder) built on the same [`GpuContext`](super::GpuContext)
//! or its clones: building a deformer compiles nothing after the first.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

use super::kernels::{self, DeformVariant, Kernel};

/// One lazily compiled kernel.
type Slot = OnceLock<Arc<Kernel>>;

/// The kernels of one device, each compiled on first use.
#[derive(Debug, Default)]
pub(crate) struct KernelCache {
    bind: [Slot; 2],
    deform: [Slot; 2],
    deform_instances: [Slot; 2],
    deform_staged: [Slot; 2],
    /// Over cell groups, one workgroup layer per instance, then numbered flat.
    deform_groups: [[Slot; 2]; 2],
    cell_order: OnceLock<Arc<[Kernel; 7]>>,
    deform_normals: [Slot; 2],
    deform_normals_groups: [Slot; 2],
    normal_coords: [Slot; 2],
    band: [Slot; 2],
    band_pack: Slot,
    band_flags: Slot,
    normals: [Slot; 2],
    bounds: Slot,
    bounds_finalize: Slot,
    tangents: Slot,
    jacobian_probe: Slot,
    /// Number of pipelines compiled so far.
    compiled: AtomicUsize,
}

fn variant_index(variant: DeformVariant) -> usize {
    match variant {
        DeformVariant::Uniform => 0,
        DeformVariant::Storage => 1,
    }
}

impl KernelCache {
    fn get(&self, slot: &Slot, compile: impl FnOnce() -> Kernel) -> Arc<Kernel> {
        Arc::clone(slot.get_or_init(|| {
            self.compiled.fetch_add(1, Ordering::Relaxed);
            Arc::new(compile())
        }))
    }

    /// `shaders/bind.wgsl`, for rigs with sweeps whose rotations are cubic or not
    /// ([`kernels::bind`]).
    pub(crate) fn bind(&self, device: &wgpu::Device, cubic: bool) -> Arc<Kernel> {
        self.get(&self.bind[usize::from(cubic)], || kernels::bind(device, cubic))
    }

    /// `shaders/deform.wgsl` for cell records of `variant`.
    pub(crate) fn deform(&self, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        self.get(&self.deform[variant_index(variant)], || kernels::deform(device, variant))
    }

    /// `shaders/deform.wgsl`'s flat-numbered instances kernel for cell records of `variant`.
    pub(crate) fn deform_instances(&self, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        self.get(&self.deform_instances[variant_index(variant)], || kernels::deform_instances(device, variant))
    }

    /// `shaders/deform_groups.wgsl` for cell records of `variant`, its instances numbered flat
    /// with `flat`.
    pub(crate) fn deform_groups(&self, device: &wgpu::Device, variant: DeformVariant, flat: bool) -> Arc<Kernel> {
        let slot = &self.deform_groups[flat as usize][variant_index(variant)];
        self.get(slot, || kernels::deform_groups(device, variant, flat))
    }

    /// `shaders/cell_order.wgsl`'s seven passes.
    pub(crate) fn cell_order(&self, device: &wgpu::Device) -> Arc<[Kernel; 7]> {
        Arc::clone(self.cell_order.get_or_init(|| {
            self.compiled.fetch_add(7, Ordering::Relaxed);
            Arc::new(kernels::cell_order(device))
        }))
    }

    /// `shaders/deform_normals_groups.wgsl` for cell records of `variant`.
    pub(crate) fn deform_normals_groups(&self, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        let slot = &self.deform_normals_groups[variant_index(variant)];
        self.get(slot, || kernels::deform_normals_groups(device, variant))
    }

    /// `shaders/deform_normals.wgsl` for cell records of `variant`.
    pub(crate) fn deform_normals(&self, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        self.get(&self.deform_normals[variant_index(variant)], || kernels::deform_normals(device, variant))
    }

    /// `shaders/normal_coords.wgsl` for rest cell records of `variant`.
    pub(crate) fn normal_coords(&self, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        self.get(&self.normal_coords[variant_index(variant)], || kernels::normal_coords(device, variant))
    }

    /// `shaders/band.wgsl` for cell records of `variant`.
    pub(crate) fn band(&self, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        self.get(&self.band[variant_index(variant)], || kernels::band(device, variant))
    }

    /// `shaders/band_pack.wgsl`.
    pub(crate) fn band_pack(&self, device: &wgpu::Device) -> Arc<Kernel> {
        self.get(&self.band_pack, || kernels::band_pack(device))
    }

    /// `shaders/band_flags.wgsl`.
    pub(crate) fn band_flags(&self, device: &wgpu::Device) -> Arc<Kernel> {
        self.get(&self.band_flags, || kernels::band_flags(device))
    }

    /// `shaders/normals.wgsl`, reading the positions through one or two windows.
    pub(crate) fn normals(&self, device: &wgpu::Device, two_windows: bool) -> Arc<Kernel> {
        self.get(&self.normals[two_windows as usize], || kernels::normals(device, two_windows))
    }

    /// `shaders/bounds.wgsl`.
    pub(crate) fn bounds(&self, device: &wgpu::Device) -> Arc<Kernel> {
        self.get(&self.bounds, || kernels::bounds(device))
    }

    /// `shaders/bounds_finalize.wgsl`.
    pub(crate) fn bounds_finalize(&self, device: &wgpu::Device) -> Arc<Kernel> {
        self.get(&self.bounds_finalize, || kernels::bounds_finalize(device))
    }

    /// `shaders/deform.wgsl`'s staged entry point for cell records of `variant`.
    pub(crate) fn deform_staged(&self, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        self.get(&self.deform_staged[variant_index(variant)], || kernels::deform_staged(device, variant))
    }

    /// `shaders/tangents.wgsl`.
    pub(crate) fn tangents(&self, device: &wgpu::Device) -> Arc<Kernel> {
        self.get(&self.tangents, || kernels::tangents(device))
    }

    /// `shaders/jacobian_probe.wgsl`.
    pub(crate) fn jacobian_probe(&self, device: &wgpu::Device) -> Arc<Kernel> {
        self.get(&self.jacobian_probe, || kernels::jacobian_probe(device))
    }

    /// Number of pipelines compiled on this cache so far.
    pub(crate) fn compiled(&self) -> usize {
        self.compiled.load(Ordering::Relaxed)
    }
}
