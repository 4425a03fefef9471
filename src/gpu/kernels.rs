//! Compute pipelines and their bind group layouts. The engine compiles each once per context
//! (`kernel_cache.rs`); the functions here compile a fresh one.

use std::borrow::Cow;

use super::shaders;
use crate::coeffs::{CellCoeffs, UNIFORM_CELL_CAPACITY};

/// How a kernel sees one of its bindings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// `var<uniform>`.
    Uniform,
    /// `var<storage, read>`.
    Read,
    /// `var<storage, read_write>`.
    ReadWrite,
}

/// A compute pipeline with the layout of its bind group 0.
#[derive(Debug)]
pub struct Kernel {
    /// The pipeline.
    pub pipeline: wgpu::ComputePipeline,
    /// The layout of group 0, binding i described by slot i.
    pub layout: wgpu::BindGroupLayout,
}

impl Kernel {
    /// Compiles `source` and builds the pipeline of `entry` with group 0 laid out as `slots`.
    pub fn new(device: &wgpu::Device, label: &str, source: &str, entry: &str, slots: &[Slot]) -> Kernel {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(source)),
        });
        let entries: Vec<wgpu::BindGroupLayoutEntry> = slots
            .iter()
            .enumerate()
            .map(|(binding, slot)| wgpu::BindGroupLayoutEntry {
                binding: binding as u32,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: match slot {
                        Slot::Uniform => wgpu::BufferBindingType::Uniform,
                        Slot::Read => wgpu::BufferBindingType::Storage { read_only: true },
                        Slot::ReadWrite => wgpu::BufferBindingType::Storage { read_only: false },
                    },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            })
            .collect();
        let layout =
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: &entries });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        Kernel { pipeline, layout }
    }

    /// A bind group for this kernel with `resources[i]` at binding i.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        label: &str,
        resources: &[wgpu::BindingResource],
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = resources
            .iter()
            .enumerate()
            .map(|(binding, resource)| wgpu::BindGroupEntry { binding: binding as u32, resource: resource.clone() })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout: &self.layout,
            entries: &entries,
        })
    }
}

use Slot::{Read, ReadWrite, Uniform};

/// Where the deform, band and normal-coordinate kernels read a deformer's cell records from,
/// as chosen: by adapter, or forced ([`DeformerDescriptor::with_cell_records`]).
///
/// [`DeformerDescriptor::with_cell_records`]: crate::gpu::DeformerDescriptor::with_cell_records
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CellRecords {
    /// [`Uniform`](CellRecords::Uniform) on a CPU adapter (lavapipe, llvmpipe, SwiftShader),
    /// [`Storage`](CellRecords::Storage) on any other. On lavapipe the storage records take 2.4×
    /// the uniform ones' deform time; on an NVIDIA H200 the uniform records took 1.5× the storage
    /// ones' at 10M vertices (2.5× at 1M), and the falloff bands over the plain pass 3.87 rather
    /// than 1.55: lanes of a warp reading records at different indices from a uniform buffer
    /// serialize there (docs/performance.md).
    #[default]
    Auto,
    /// A uniform buffer, where the rig fits one ([`DeformVariant::Uniform`]); storage otherwise.
    Uniform,
    /// A storage buffer.
    Storage,
}

impl CellRecords {
    /// The variant for a rig of `cells` cells (every instance's) on an adapter of `device_type`
    /// with `limits`.
    pub fn variant(self, cells: usize, limits: &wgpu::Limits, device_type: wgpu::DeviceType) -> DeformVariant {
        let fits = DeformVariant::uniform_fits(cells, limits);
        match self {
            CellRecords::Auto if fits && device_type == wgpu::DeviceType::Cpu => DeformVariant::Uniform,
            CellRecords::Uniform if fits => DeformVariant::Uniform,
            _ => DeformVariant::Storage,
        }
    }
}

impl From<DeformVariant> for CellRecords {
    /// The choice that forces `variant` (where the rig fits it).
    fn from(variant: DeformVariant) -> CellRecords {
        match variant {
            DeformVariant::Uniform => CellRecords::Uniform,
            DeformVariant::Storage => CellRecords::Storage,
        }
    }
}

/// Where the deform kernel reads the cell records from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeformVariant {
    /// A uniform buffer of [`UNIFORM_CELL_CAPACITY`] records: rigs and instances of up to that
    /// many cells on devices that allow 64 KiB uniform buffers; the faster choice on CPU
    /// adapters.
    Uniform,
    /// A storage buffer: rigs of any size; the faster choice on GPUs.
    Storage,
}

impl DeformVariant {
    /// Whether a rig of `cells` cells (every instance's) fits a uniform buffer on a device with
    /// `limits`.
    pub fn uniform_fits(cells: usize, limits: &wgpu::Limits) -> bool {
        let bytes = UNIFORM_CELL_CAPACITY as u64 * size_of::<CellCoeffs>() as u64;
        cells <= UNIFORM_CELL_CAPACITY as usize && limits.max_uniform_buffer_binding_size >= bytes
    }

    /// The other variant.
    pub fn other(self) -> DeformVariant {
        match self {
            DeformVariant::Uniform => DeformVariant::Storage,
            DeformVariant::Storage => DeformVariant::Uniform,
        }
    }

    /// `"uniform"` or `"storage"`, as `sweepffd info` and the bench name it.
    pub fn name(self) -> &'static str {
        match self {
            DeformVariant::Uniform => "uniform",
            DeformVariant::Storage => "storage",
        }
    }
}

/// `shaders/bind.wgsl`: params, cells, bind segments, sweeps, owners, positions (read);
/// bindings (written). With `cubic`, the entry point that also solves the nonics of sweeps
/// whose rotations are cubic (`bind_cubic_main`); without, the faster one for rigs whose
/// rotations are all linear.
pub fn bind(device: &wgpu::Device, cubic: bool) -> Kernel {
    let slots = [Uniform, Read, Read, Read, Read, Read, ReadWrite];
    let entry = if cubic { "bind_cubic_main" } else { "bind_main" };
    Kernel::new(device, "sweepffd bind", shaders::BIND, entry, &slots)
}

/// `shaders/deform.wgsl`: params, cells (uniform or storage), bindings (read); positions
/// (written).
pub fn deform(device: &wgpu::Device, variant: DeformVariant) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::DEFORM_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::DEFORM_STORAGE, Read),
    };
    Kernel::new(device, "sweepffd deform", source, "deform_main", &[Uniform, cells, Read, ReadWrite])
}

/// `shaders/deform.wgsl`'s `deform_instances_main`, the deform kernel of several instances
/// numbered flat (one invocation per vertex of each instance, no workgroup layers): the same
/// bindings and arithmetic as [`deform`].
pub fn deform_instances(device: &wgpu::Device, variant: DeformVariant) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::DEFORM_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::DEFORM_STORAGE, Read),
    };
    Kernel::new(
        device,
        "sweepffd deform instances",
        source,
        "deform_instances_main",
        &[Uniform, cells, Read, ReadWrite],
    )
}

/// `shaders/deform.wgsl`'s `deform_staged_main`: [`deform`] with a workgroup's positions
/// staged in workgroup memory and stored as whole words, the same bindings.
pub fn deform_staged(device: &wgpu::Device, variant: DeformVariant) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::DEFORM_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::DEFORM_STORAGE, Read),
    };
    Kernel::new(device, "sweepffd deform staged", source, "deform_staged_main", &[Uniform, cells, Read, ReadWrite])
}

/// `shaders/deform_groups.wgsl`'s `deform_groups_main` (one workgroup layer per instance) or, with
/// `flat`, `deform_groups_instances_main` (instances numbered flat): the deform kernel over the
/// cell groups of `cell_groups.rs`, with [`deform`]'s bindings and the groups after them.
pub fn deform_groups(device: &wgpu::Device, variant: DeformVariant, flat: bool) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::DEFORM_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::DEFORM_STORAGE, Read),
    };
    let entry = if flat { "deform_groups_instances_main" } else { "deform_groups_main" };
    Kernel::new(device, "sweepffd deform groups", source, entry, &[Uniform, cells, Read, ReadWrite, Read])
}

/// `shaders/cell_order.wgsl`'s seven passes, in order, each with params, bindings (read),
/// cursors, groups and the deform dispatches' arguments (written), the dispatches' shapes (read)
/// and the runs' starts (written).
pub fn cell_order(device: &wgpu::Device) -> [Kernel; 7] {
    let slots = [Uniform, Read, ReadWrite, ReadWrite, ReadWrite, Read, ReadWrite];
    [
        "cell_order_clear_main",
        "cell_order_count_main",
        "cell_order_sums_main",
        "cell_order_scan_main",
        "cell_order_offsets_main",
        "cell_order_scatter_main",
        "cell_order_fill_main",
    ]
    .map(|entry| Kernel::new(device, "sweepffd cell order", shaders::CELL_ORDER, entry, &slots))
}

/// `shaders/deform_normals.wgsl`: params, cells (uniform or storage), bindings (read),
/// positions (written), normal coordinates (read), normals (written).
pub fn deform_normals(device: &wgpu::Device, variant: DeformVariant) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::DEFORM_NORMALS_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::DEFORM_NORMALS_STORAGE, Read),
    };
    let slots = [Uniform, cells, Read, ReadWrite, Read, ReadWrite];
    Kernel::new(device, "sweepffd deform normals", source, "deform_normals_main", &slots)
}

/// `shaders/deform_normals_groups.wgsl`: [`deform_normals`] over the cell groups of
/// `cell_groups.rs`, with its bindings and the groups after them.
pub fn deform_normals_groups(device: &wgpu::Device, variant: DeformVariant) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::DEFORM_NORMALS_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::DEFORM_NORMALS_STORAGE, Read),
    };
    let slots = [Uniform, cells, Read, ReadWrite, Read, ReadWrite, Read];
    Kernel::new(device, "sweepffd deform normals groups", source, "deform_normals_groups_main", &slots)
}

/// `shaders/normal_coords.wgsl`: params, rest cells (uniform or storage), bindings, rest normals
/// (read); normal coordinates (written).
pub fn normal_coords(device: &wgpu::Device, variant: DeformVariant) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::NORMAL_COORDS_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::NORMAL_COORDS_STORAGE, Read),
    };
    let slots = [Uniform, cells, Read, Read, ReadWrite];
    Kernel::new(device, "sweepffd normal coordinates", source, "normal_coords_main", &slots)
}

/// `shaders/band.wgsl`: params, cells (uniform or storage), bindings (read), positions
/// (written), rest cells (uniform or storage), band records (read).
pub fn band(device: &wgpu::Device, variant: DeformVariant) -> Kernel {
    let (source, cells) = match variant {
        DeformVariant::Uniform => (shaders::BAND_UNIFORM, Uniform),
        DeformVariant::Storage => (shaders::BAND_STORAGE, Read),
    };
    Kernel::new(device, "sweepffd band", source, "band_main", &[Uniform, cells, Read, ReadWrite, cells, Read])
}

/// `shaders/band_pack.wgsl`: params, second bindings (read); band records (written).
pub fn band_pack(device: &wgpu::Device) -> Kernel {
    Kernel::new(device, "sweepffd band pack", shaders::BAND_PACK, "band_pack_main", &[Uniform, Read, ReadWrite])
}

/// `shaders/band_flags.wgsl`: params, band flag changes (read); bindings, positions (written).
pub fn band_flags(device: &wgpu::Device) -> Kernel {
    Kernel::new(
        device,
        "sweepffd band flags",
        shaders::BAND_FLAGS,
        "band_flags_main",
        &[Uniform, Read, ReadWrite, ReadWrite],
    )
}

/// `shaders/normals.wgsl`: params, positions (two windows), vertices, offsets, fans (read);
/// normals (written). `two_windows` when the positions do not fit one storage binding.
pub fn normals(device: &wgpu::Device, two_windows: bool) -> Kernel {
    let source = if two_windows { shaders::NORMALS_TWO_WINDOWS } else { shaders::NORMALS_ONE_WINDOW };
    let slots = [Uniform, Read, Read, Read, Read, Read, ReadWrite];
    Kernel::new(device, "sweepffd normals", source, "normals_main", &slots)
}

/// `shaders/bounds.wgsl`: params, positions (read); extremes (atomic, written).
pub fn bounds(device: &wgpu::Device) -> Kernel {
    Kernel::new(device, "sweepffd bounds", shaders::BOUNDS, "bounds_main", &[Uniform, Read, ReadWrite])
}

/// `shaders/bounds_finalize.wgsl`: params, extremes (read); bounds (written).
pub fn bounds_finalize(device: &wgpu::Device) -> Kernel {
    let entry = "bounds_finalize_main";
    Kernel::new(device, "sweepffd bounds finalize", shaders::BOUNDS_FINALIZE, entry, &[Uniform, Read, ReadWrite])
}

/// `shaders/copy.wgsl`: params, bindings (read); positions (written).
pub fn copy(device: &wgpu::Device) -> Kernel {
    Kernel::new(device, "sweepffd copy baseline", shaders::COPY, "copy_main", &[Uniform, Read, ReadWrite])
}

/// `shaders/copy_wide.wgsl`: params, bindings, records (read); positions, normals (written).
pub fn copy_wide(device: &wgpu::Device) -> Kernel {
    let slots = [Uniform, Read, Read, ReadWrite, ReadWrite];
    Kernel::new(device, "sweepffd wide copy baseline", shaders::COPY_WIDE, "copy_wide_main", &slots)
}

/// `shaders/skinning.wgsl`: params, joints (uniform), rest positions, influences (read); positions
/// (written).
pub fn skinning(device: &wgpu::Device) -> Kernel {
    let slots = [Uniform, Uniform, Read, Read, ReadWrite];
    Kernel::new(device, "sweepffd skinning baseline", shaders::SKINNING, "skinning_main", &slots)
}

/// `shaders/jacobian_probe.wgsl`: params, probed vertices, Jacobian normals, facet normals,
/// rest normals (read); verdicts (written).
pub fn jacobian_probe(device: &wgpu::Device) -> Kernel {
    let slots = [Uniform, Read, Read, Read, Read, ReadWrite];
    Kernel::new(device, "sweepffd jacobian probe", shaders::JACOBIAN_PROBE, "jacobian_probe_main", &slots)
}

/// `shaders/tangents.wgsl`: params, vertices, rest normals, normals, rest tangents (read);
/// tangents (written).
pub fn tangents(device: &wgpu::Device) -> Kernel {
    let slots = [Uniform, Read, Read, Read, Read, ReadWrite];
    Kernel::new(device, "sweepffd tangents", shaders::TANGENTS, "tangents_main", &slots)
}
