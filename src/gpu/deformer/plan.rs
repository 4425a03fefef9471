//! [`DeformerPlan`]: everything a [`GpuDeformer`](super::GpuDeformer) decides from its
//! descriptor and the device before any GPU work, once: which vertices are bound and which are
//! banded, the deform chunks, the position buffers' layout, the Jacobian normals' reach and the
//! kernel. Pure: it needs the device's limits and type, not the device.

use std::ops::Range;
use std::sync::Arc;

use super::super::chunks::{ChunkLimits, bound_chunks, uniform_chunks};
use super::super::kernel_cache::KernelCache;
use super::super::kernels::{DeformVariant, Kernel};
use super::super::{GpuError, InputError};
use super::cell_groups::DeformOrder;
use super::descriptor::triangle_faces;
use super::instances::{Numbering, PositionTargets};
use super::{BindingSource, DeformerDescriptor, STORAGE_BUFFERS_NEEDED};
use crate::coeffs::{SweepCoefficients, UNOWNED};
use crate::gpu::buffers::{BINDING_STRIDE, check_fits};
use crate::normals::{NormalAdjacency, jacobian_reach};

/// The deform kernel a deformer runs, and how its invocations are numbered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct KernelChoice {
    /// The fused deform + Jacobian normals kernel rather than the plain one.
    pub jacobian_normals: bool,
    /// One invocation a cell group of vertices rather than one a vertex.
    pub cell_groups: bool,
    /// A workgroup's positions staged and stored whole (the single-instance deform kernel).
    pub staged: bool,
    pub numbering: Numbering,
}

impl KernelChoice {
    /// The kernel for `jacobian_normals`, the deform `order` (not [`DeformOrder::Auto`]) and
    /// `instances`. Several instances of the plain kernel are numbered flat: with one workgroup
    /// layer per instance, a small mesh's last workgroup of every instance runs nearly empty.
    pub fn new(jacobian_normals: bool, order: DeformOrder, instances: u32) -> KernelChoice {
        let flat = !jacobian_normals && instances > 1;
        let numbering = if flat { Numbering::Flat } else { Numbering::Layered };
        let cell_groups = order == DeformOrder::CellGroups;
        let staged = order == DeformOrder::StagedVertices && !jacobian_normals && !flat;
        KernelChoice { jacobian_normals, cell_groups, staged, numbering }
    }

    /// The order the kernel runs in.
    pub fn order(&self) -> DeformOrder {
        match (self.cell_groups, self.staged) {
            (true, _) => DeformOrder::CellGroups,
            (false, true) => DeformOrder::StagedVertices,
            (false, false) => DeformOrder::Vertices,
        }
    }

    /// The compiled kernel, from the context's cache.
    pub fn kernel(&self, kernels: &KernelCache, device: &wgpu::Device, variant: DeformVariant) -> Arc<Kernel> {
        let flat = self.numbering == Numbering::Flat;
        match (self.jacobian_normals, self.cell_groups) {
            (true, false) => kernels.deform_normals(device, variant),
            (true, true) => kernels.deform_normals_groups(device, variant),
            (false, false) if flat => kernels.deform_instances(device, variant),
            (false, false) if self.staged => kernels.deform_staged(device, variant),
            (false, false) => kernels.deform(device, variant),
            (false, true) => kernels.deform_groups(device, variant, flat),
        }
    }
}

/// What a deformer is built from, decided once.
#[derive(Debug)]
pub(super) struct DeformerPlan {
    pub limits: ChunkLimits,
    pub vertex_count: u32,
    /// Whether each vertex is bound to a sweep.
    pub bound: Vec<bool>,
    /// The vertices of each deform chunk: only ranges holding bound vertices are bound and
    /// deformed (all, with `full_dispatch`); the others keep their rest positions.
    pub ranges: Vec<Range<u32>>,
    /// The position buffers' layout (their buffers are made by the build).
    pub targets: PositionTargets,
    /// The rest rig as cell records.
    pub coefficients: SweepCoefficients,
    /// Where the deform kernel reads the cell records from.
    pub variant: DeformVariant,
    pub kernel: KernelChoice,
    /// The vertices in a falloff band, increasing.
    pub band_vertices: Vec<u32>,
    /// The triangles' fans, if there are triangles.
    pub adjacency: Option<NormalAdjacency>,
    /// With Jacobian normals, the vertices whose one-ring one sweep moves whole
    /// ([`crate::normals::jacobian_reach`]): the deform kernel writes the normals of those
    /// whose Jacobian predicts their facets under a probe pose (decided on the GPU,
    /// [`super::jacobian_probe`]); the normals pass computes the others, after it.
    pub reach: Option<Vec<bool>>,
    /// With Jacobian normals, the sweep moving each vertex whole, or [`UNOWNED`].
    pub influence: Option<Vec<u32>>,
}

impl DeformerPlan {
    /// The plan of `descriptor` on a device with `device_limits`, of `device_type` (which
    /// chooses the deform order and the cell records); input errors are found here, before the GPU.
    pub fn new(
        descriptor: &DeformerDescriptor,
        device_limits: &wgpu::Limits,
        device_type: wgpu::DeviceType,
    ) -> Result<DeformerPlan, GpuError> {
        descriptor.check()?;
        if device_limits.max_storage_buffers_per_shader_stage < STORAGE_BUFFERS_NEEDED {
            let allowed = device_limits.max_storage_buffers_per_shader_stage;
            return Err(InputError::TooFewStorageBuffers { allowed, needed: STORAGE_BUFFERS_NEEDED }.into());
        }
        let limits = ChunkLimits::of(device_limits);
        let vertex_count = descriptor.positions.len() as u32;
        let bound: Vec<bool> = match descriptor.bindings {
            BindingSource::Bind { owners, .. } => owners.iter().map(|&o| o != UNOWNED).collect(),
            BindingSource::Precomputed { bindings, .. } => bindings.iter().map(|b| b.cell != UNOWNED).collect(),
        };
        let ranges = match descriptor.full_dispatch {
            true => uniform_chunks(vertex_count, BINDING_STRIDE, &limits),
            false => bound_chunks(&bound, BINDING_STRIDE, &limits),
        };
        let max_chunk = ranges.iter().map(|r| r.len() as u32).max().unwrap_or(0);
        let targets = PositionTargets::plan(vertex_count, descriptor.instances, max_chunk, &limits);
        check_fits("the position buffer", targets.bytes(), limits.max_buffer)?;
        check_output(descriptor, &targets, &limits)?;
        let coefficients = SweepCoefficients::new(descriptor.rest);
        let total_cells = coefficients.cells.len() * descriptor.instances as usize;
        let variant = descriptor.cell_records.variant(total_cells, device_limits, device_type);
        let order = descriptor.deform_order.on_type(device_type);
        let kernel = KernelChoice::new(descriptor.jacobian_normals, order, descriptor.instances);
        let band_vertices: Vec<u32> = match descriptor.bindings {
            BindingSource::Bind { bands, .. } => bands.iter().map(|b| b.vertex).collect(),
            BindingSource::Precomputed { bands, .. } => bands.iter().map(|b| b.vertex).collect(),
        };
        let adjacency = descriptor.triangles.map(|t| NormalAdjacency::new(&triangle_faces(t), vertex_count as usize));
        let influence = jacobian_influence(descriptor, &coefficients, &band_vertices);
        let reach = influence.as_ref().zip(descriptor.triangles).map(|(influence, t)| jacobian_reach(t, influence));
        let plan = DeformerPlan {
            limits,
            vertex_count,
            bound,
            ranges,
            targets,
            coefficients,
            variant,
            kernel,
            band_vertices,
            adjacency,
            reach,
            influence,
        };
        Ok(plan)
    }

    /// The band vertices among the vertices `range`.
    pub fn bands_in(&self, range: &Range<u32>) -> &[u32] {
        let first = self.band_vertices.partition_point(|&v| v < range.start);
        let last = self.band_vertices.partition_point(|&v| v < range.end);
        &self.band_vertices[first..last]
    }
}

/// Fails if the application's output buffer is misaligned or too small for `targets`.
fn check_output(
    descriptor: &DeformerDescriptor,
    targets: &PositionTargets,
    limits: &ChunkLimits,
) -> Result<(), GpuError> {
    let Some(output) = descriptor.output else { return Ok(()) };
    if output.offset % limits.offset_alignment != 0 {
        return Err(
            InputError::OutputOffsetMisaligned { offset: output.offset, alignment: limits.offset_alignment }.into()
        );
    }
    if let Some(buffer) = output.buffers().find(|b| output.offset + targets.bytes() > b.size()) {
        let (size, needed, offset) = (buffer.size(), targets.bytes(), output.offset);
        return Err(InputError::OutputTooSmall { size, needed, offset }.into());
    }
    Ok(())
}

/// With Jacobian normals (and triangles), the sweep moving each vertex whole: its own, or
/// [`UNOWNED`] for unbound vertices and band vertices, which blend two influences.
fn jacobian_influence(
    descriptor: &DeformerDescriptor,
    coefficients: &SweepCoefficients,
    band_vertices: &[u32],
) -> Option<Vec<u32>> {
    if !descriptor.jacobian_normals || descriptor.triangles.is_none() {
        return None;
    }
    let mut influence: Vec<u32> = match descriptor.bindings {
        BindingSource::Bind { owners, .. } => owners.to_vec(),
        BindingSource::Precomputed { bindings, .. } => {
            bindings.iter().map(|b| coefficients.sweep_of_cell(b.cell)).collect()
        }
    };
    for &v in band_vertices {
        influence[v as usize] = UNOWNED;
    }
    Some(influence)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::{DeformOrder, rest_positions};
    use crate::rig::Rig;
    use crate::synthetic::{Tube, attached_tube_rig, straight_sweep};

    #[test]
    fn the_plan_binds_only_the_chunks_holding_bound_vertices_and_picks_the_kernel_by_adapter() {
        // A long tube whose sweep owns its top sixth only: the chunks skip the rest.
        let tube = Tube { rings: 600, around: 16, length: 12.0, radius: 0.3 };
        let owned: Vec<u32> = (8000..tube.vertex_count() as u32).collect();
        let rig = Rig::new(vec![straight_sweep(&tube, owned, (10.0, 12.0), 4, 16, 0.0)]).unwrap();
        let positions = rest_positions(&tube.mesh().positions);
        let owners = rig.vertex_owners(positions.len()).unwrap();
        let descriptor = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::bind(&owners));
        let limits = crate::gpu::GpuDeformer::required_limits();
        let plan = DeformerPlan::new(&descriptor, &limits, wgpu::DeviceType::DiscreteGpu).unwrap();
        assert_eq!(plan.vertex_count as usize, positions.len());
        assert_eq!(plan.bound.iter().filter(|&&b| b).count(), positions.len() - 8000);
        let covered = |v: u32| plan.ranges.iter().any(|r| r.contains(&v));
        assert!((8000..plan.vertex_count).all(covered), "{:?}", plan.ranges);
        let dispatched: u32 = plan.ranges.iter().map(|r| r.len() as u32).sum();
        assert!(dispatched < plan.vertex_count - 2000, "{dispatched} of {} vertices dispatched", plan.vertex_count);
        assert_eq!(plan.kernel, KernelChoice::new(false, DeformOrder::StagedVertices, 1));
        assert!(plan.kernel.staged, "GPUs store a workgroup's positions whole");
        assert!(plan.reach.is_none() && plan.adjacency.is_none() && plan.band_vertices.is_empty());
        let cpu = DeformerPlan::new(&descriptor, &limits, wgpu::DeviceType::Cpu).unwrap();
        assert!(cpu.kernel.cell_groups, "CPU adapters deform over cell groups");
        let vertices = descriptor.with_deform_order(DeformOrder::Vertices);
        assert!(!DeformerPlan::new(&vertices, &limits, wgpu::DeviceType::Cpu).unwrap().kernel.cell_groups);
    }

    #[test]
    fn instances_are_numbered_flat_unless_the_kernel_writes_normals() {
        use DeformOrder::{CellGroups, StagedVertices, Vertices};
        assert_eq!(KernelChoice::new(false, Vertices, 4).numbering, Numbering::Flat);
        assert_eq!(KernelChoice::new(false, CellGroups, 4).numbering, Numbering::Flat);
        assert_eq!(KernelChoice::new(true, Vertices, 4).numbering, Numbering::Layered);
        assert_eq!(KernelChoice::new(false, Vertices, 1).numbering, Numbering::Layered);
        // Staging serves the single-instance plain kernel only.
        assert_eq!(KernelChoice::new(false, StagedVertices, 1).order(), StagedVertices);
        assert_eq!(KernelChoice::new(false, StagedVertices, 4).order(), Vertices);
        assert_eq!(KernelChoice::new(true, StagedVertices, 1).order(), Vertices);
    }

    #[test]
    fn input_faults_are_found_before_the_gpu() {
        let tube = Tube { rings: 4, around: 8, length: 1.0, radius: 0.3 };
        let rig = attached_tube_rig(&tube, 3, 8, 0.0);
        let positions = rest_positions(&tube.mesh().positions);
        let owners = vec![7; positions.len()];
        let descriptor = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::bind(&owners));
        let limits = crate::gpu::GpuDeformer::required_limits();
        let error = DeformerPlan::new(&descriptor, &limits, wgpu::DeviceType::Cpu).unwrap_err();
        assert!(matches!(error, GpuError::Input(InputError::OwnerOutOfRange { vertex: 0, sweep: 7, sweeps: 1 })));
        let owners = vec![0; positions.len()];
        let descriptor = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::bind(&owners));
        let few = wgpu::Limits { max_storage_buffers_per_shader_stage: 4, ..limits };
        let error = DeformerPlan::new(&descriptor, &few, wgpu::DeviceType::Cpu).unwrap_err();
        assert!(matches!(error, GpuError::Input(InputError::TooFewStorageBuffers { allowed: 4, needed: 6 })));
    }
}
