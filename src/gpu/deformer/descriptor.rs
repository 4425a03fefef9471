//! [`DeformerDescriptor`]: what a [`GpuDeformer`](super::GpuDeformer) is built from, in the
//! engine's own types (f32 rest positions, a `u32` triangle list), and the checks made on it
//! before anything reaches the GPU.

use super::super::kernels::CellRecords;
use super::super::{GpuError, InputError};
use super::BindingSource;
use super::cell_groups::DeformOrder;
use crate::coeffs::{BAND_FLAG, BandRecord, MAX_PACKED_CELLS, UNOWNED};
use crate::mesh::Faces;
use crate::sweep::Sweep;

/// Everything a [`GpuDeformer`](super::GpuDeformer) is built from.
///
/// ```no_run
/// # fn make(rest: &[sweepffd::sweep::Sweep], positions: &[[f32; 3]], owners: &[u32], triangles: &[u32]) {
/// use sweepffd::gpu::{BindingSource, DeformerDescriptor};
/// let descriptor = DeformerDescriptor::new(rest, positions, BindingSource::Bind { owners, bands: &[] })
///     .with_triangles(triangles);
/// # }
/// ```
#[derive(Clone, Copy, Debug)]
pub struct DeformerDescriptor<'a> {
    /// The rest rig's sweeps (the f64 reference geometry, turned into f32 cell records).
    pub rest: &'a [Sweep],
    /// The rest positions, f32 xyz, one per vertex ([`rest_positions`](crate::gpu::rest_positions)
    /// converts f64 ones): finite, fewer than [`UNOWNED`] of them.
    pub positions: &'a [[f32; 3]],
    /// How the vertices are bound to the rig.
    pub bindings: BindingSource<'a>,
    /// A triangle list (three vertex indices a triangle, each below the vertex count): with it
    /// the deformer also keeps area-weighted vertex normals of the deformed mesh.
    pub triangles: Option<&'a [u32]>,
    /// Instances of the mesh (at least 1), each with its own pose, deformed in one dispatch.
    pub instances: u32,
    /// Staging buffers for the poses' uploads made at creation (at least 1; each holds every
    /// instance's cell records). Each encode uploads through a free one and makes another if
    /// none is free, so this is a starting size, not a limit: as many encodes as wanted may
    /// share a command buffer, each with its own poses.
    pub pose_uploads: u32,
    /// Whether to keep the previous frame's positions (two position buffers, alternating).
    pub previous_positions: bool,
    /// Whether to compute every instance's bounds on the GPU each frame.
    pub bounds: bool,
    /// The host's rest tangents (f32 xyzw per vertex, w = ±1 the handedness, as glTF stores
    /// them), with triangles: the deformer then keeps deformed tangents, each turned with its
    /// vertex's normal ([`crate::normals::tangents`]).
    pub rest_tangents: Option<&'a [[f32; 4]]>,
    /// Whether the normals (with triangles) come through the deformation's Jacobian, fused into
    /// the deform kernel (see [`with_jacobian_normals`](Self::with_jacobian_normals)), rather
    /// than from the deformed triangles.
    pub jacobian_normals: bool,
    /// The application's own buffer to write the positions into, instead of one of the
    /// deformer's.
    pub output: Option<OutputBuffer<'a>>,
    /// Whether the deform dispatches cover every vertex rather than only the ranges holding
    /// bound ones (the default): the same positions, bit for bit, more work. For tests and
    /// benches.
    pub full_dispatch: bool,
    /// Which vertices one invocation of the deform kernel (or the fused deform + Jacobian normals
    /// kernel) deforms: the same positions and normals, bit for bit.
    pub deform_order: DeformOrder,
    /// Where the kernels read the cell records from: the same positions and normals, bit for
    /// bit.
    pub cell_records: CellRecords,
}

/// An application buffer the deformer writes its positions into (an engine's own vertex buffer):
/// instance i's positions, tightly packed f32 xyz, at `offset + instance_offset(i) − offset`
/// bytes, i.e. laid out from `offset` exactly as the deformer's own buffer. The buffer needs
/// `STORAGE | COPY_DST` usage (`COPY_SRC` to read it back), `offset` a multiple of the device's
/// `min_storage_buffer_offset_alignment`, and room for every instance. The deformer writes the
/// rest positions into it at creation (unbound vertices are never written again) and the
/// deformed ones each frame; the application must not write that range. With `previous`, the
/// deformer keeps previous positions in the two buffers, alternating, laid out alike from the
/// same offset ([`DeformerDescriptor::with_outputs`]).
#[derive(Clone, Copy, Debug)]
pub struct OutputBuffer<'a> {
    /// The buffer.
    pub buffer: &'a wgpu::Buffer,
    /// Byte offset of instance 0's first position.
    pub offset: u64,
    /// The second buffer of the previous positions' ping-pong, if any.
    pub previous: Option<&'a wgpu::Buffer>,
}

impl<'a> OutputBuffer<'a> {
    /// The buffer, then the previous positions' second one if any.
    pub fn buffers(&self) -> impl Iterator<Item = &'a wgpu::Buffer> + use<'a> {
        std::iter::once(self.buffer).chain(self.previous)
    }
}

impl<'a> DeformerDescriptor<'a> {
    /// A deformer of `positions` bound to the rig `rest` by `bindings`, without normals.
    pub fn new(rest: &'a [Sweep], positions: &'a [[f32; 3]], bindings: BindingSource<'a>) -> DeformerDescriptor<'a> {
        DeformerDescriptor {
            rest,
            positions,
            bindings,
            triangles: None,
            instances: 1,
            pose_uploads: 2,
            previous_positions: false,
            bounds: false,
            rest_tangents: None,
            jacobian_normals: false,
            output: None,
            full_dispatch: false,
            deform_order: DeformOrder::Auto,
            cell_records: CellRecords::Auto,
        }
    }

    /// The same, keeping the vertex normals of the triangles `triangles` (three indices each).
    pub fn with_triangles(self, triangles: &'a [u32]) -> DeformerDescriptor<'a> {
        DeformerDescriptor { triangles: Some(triangles), ..self }
    }

    /// The same with `instances` instances of the mesh.
    pub fn with_instances(self, instances: u32) -> DeformerDescriptor<'a> {
        DeformerDescriptor { instances, ..self }
    }

    /// The same with `pose_uploads` staging buffers made at creation (default 2, enough for a
    /// frame loop with a frame in flight; more are made when needed).
    pub fn with_pose_uploads(self, pose_uploads: u32) -> DeformerDescriptor<'a> {
        DeformerDescriptor { pose_uploads, ..self }
    }

    /// The same, keeping the previous frame's positions in two position buffers of the
    /// deformer's own (with the application's output, [`with_outputs`](Self::with_outputs)
    /// takes the two buffers).
    pub fn with_previous_positions(self) -> DeformerDescriptor<'a> {
        DeformerDescriptor { previous_positions: true, ..self }
    }

    /// The same, computing every instance's bounds each frame.
    pub fn with_bounds(self) -> DeformerDescriptor<'a> {
        DeformerDescriptor { bounds: true, ..self }
    }

    /// The same, turning the host's rest tangents (xyzw per vertex) with the normals each
    /// frame; needs triangles.
    pub fn with_tangents(self, rest_tangents: &'a [[f32; 4]]) -> DeformerDescriptor<'a> {
        DeformerDescriptor { rest_tangents: Some(rest_tangents), ..self }
    }

    /// The same, computing the normals of the vertices a sweep moves through the Jacobian of
    /// the deformation (Nanson's formula, [`crate::deform::jacobian`]) in the deform kernel
    /// itself: each such vertex's binding is read once and its position and normal written
    /// once, with no gather over its triangles. It covers the vertices whose whole one-ring one
    /// sweep moves ([`crate::normals::jacobian_reach`]) and whose Jacobian normals match their
    /// facets under a probe pose (checked once here, on the GPU, which creation then waits for;
    /// [`crate::deform::jacobian_normal_vertices`] is the f64 twin); the others (falloff bands,
    /// hard seams between sweeps, unbound vertices beside moving ones, rings too coarse for the
    /// deformation) keep the triangle normals. Needs triangles; the falloff bands are then fixed
    /// ([`set_bands`](crate::gpu::GpuDeformer::set_bands) refuses).
    pub fn with_jacobian_normals(self) -> DeformerDescriptor<'a> {
        DeformerDescriptor { jacobian_normals: true, ..self }
    }

    /// The same, writing the positions into the application's `buffer` from byte `offset` on.
    pub fn with_output(self, buffer: &'a wgpu::Buffer, offset: u64) -> DeformerDescriptor<'a> {
        DeformerDescriptor { output: Some(OutputBuffer { buffer, offset, previous: None }), ..self }
    }

    /// The same, keeping the previous frame's positions in two of the application's buffers:
    /// each encode writes the one the encode before did not, so that
    /// [`positions`](crate::gpu::GpuDeformer::positions) is the latest and
    /// [`previous_positions`](crate::gpu::GpuDeformer::previous_positions) the other (`first`
    /// before the first encode), both laid out from `offset` as [`with_output`](Self::with_output)
    /// says. Two different buffers, each meeting `with_output`'s conditions.
    pub fn with_outputs(
        self,
        first: &'a wgpu::Buffer,
        second: &'a wgpu::Buffer,
        offset: u64,
    ) -> DeformerDescriptor<'a> {
        let output = OutputBuffer { buffer: first, offset, previous: Some(second) };
        DeformerDescriptor { output: Some(output), previous_positions: true, ..self }
    }

    /// The same, dispatching over every vertex (see [`full_dispatch`](Self::full_dispatch)).
    pub fn with_full_dispatch(self) -> DeformerDescriptor<'a> {
        DeformerDescriptor { full_dispatch: true, ..self }
    }

    /// The same, deforming in `order` (see [`DeformOrder`]; default [`DeformOrder::Auto`]).
    pub fn with_deform_order(self, deform_order: DeformOrder) -> DeformerDescriptor<'a> {
        DeformerDescriptor { deform_order, ..self }
    }

    /// The same, reading the cell records from `cell_records` (see [`CellRecords`]; default
    /// [`CellRecords::Auto`]).
    pub fn with_cell_records(self, cell_records: CellRecords) -> DeformerDescriptor<'a> {
        DeformerDescriptor { cell_records, ..self }
    }

    /// `Err(Input)` naming the first problem: no vertices, too many, a non-finite position, owners
    /// or bindings of another length or out of the rig's range, falloff bands not sorted, bound and
    /// in range, a triangle list not a multiple of three or indexing past the vertices.
    pub(super) fn check(&self) -> Result<(), GpuError> {
        check_input(self.rest, self.positions, &self.bindings)?;
        if self.instances == 0 || self.pose_uploads == 0 {
            return Err(InputError::NoInstances { instances: self.instances, pose_uploads: self.pose_uploads }.into());
        }
        if self.jacobian_normals && self.triangles.is_none() {
            return Err(InputError::JacobianNormalsWithoutTriangles.into());
        }
        if self.rest_tangents.is_some() && self.triangles.is_none() {
            return Err(InputError::TangentsWithoutTriangles.into());
        }
        if let Some(output) = self.output {
            match output.previous {
                None if self.previous_positions => {
                    return Err(InputError::PreviousPositionsNeedTwoOutputs.into());
                }
                Some(previous) if previous == output.buffer => {
                    return Err(InputError::PreviousOutputIsTheOutput.into());
                }
                _ => {}
            }
            let needed = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
            for buffer in output.buffers() {
                if !buffer.usage().contains(needed) {
                    return Err(InputError::OutputUsage { usage: buffer.usage() }.into());
                }
            }
        }
        if let Some(triangles) = self.triangles {
            if triangles.len() % 3 != 0 {
                return Err(InputError::TriangleIndexCount { indices: triangles.len() }.into());
            }
            let n = self.positions.len();
            if let Some(i) = triangles.iter().position(|&v| v as usize >= n) {
                return Err(InputError::TriangleVertexOutOfRange {
                    triangle: i / 3,
                    vertex: triangles[i],
                    vertices: n,
                }
                .into());
            }
        }
        Ok(())
    }
}

/// A triangle list as [`Faces`] (one face of three vertices per triangle), for the normals.
pub(super) fn triangle_faces(triangles: &[u32]) -> Faces {
    let offsets = (0..=triangles.len() as u32 / 3).map(|t| 3 * t).collect();
    Faces { offsets, indices: triangles.to_vec() }
}

fn check_input(rest: &[Sweep], positions: &[[f32; 3]], bindings: &BindingSource) -> Result<(), GpuError> {
    if positions.is_empty() {
        return Err(InputError::NoVertices.into());
    }
    let cells: usize = rest.iter().map(|s| s.segments().len() * s.radius_samples()).sum();
    if cells > MAX_PACKED_CELLS as usize {
        return Err(InputError::TooManyCells { cells, max: MAX_PACKED_CELLS }.into());
    }
    if positions.len() >= UNOWNED as usize {
        return Err(InputError::TooManyVertices { vertices: positions.len() }.into());
    }
    if let Some(i) = positions.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(InputError::PositionNotFinite { vertex: i }.into());
    }
    match bindings {
        BindingSource::Bind { owners, bands } => {
            if owners.len() != positions.len() {
                return Err(InputError::OwnerCount { owners: owners.len(), vertices: positions.len() }.into());
            }
            if let Some(i) = owners.iter().position(|&o| o != UNOWNED && o as usize >= rest.len()) {
                return Err(InputError::OwnerOutOfRange { vertex: i, sweep: owners[i], sweeps: rest.len() }.into());
            }
            super::check_weights(bands, rest.len(), |v| owners.get(v).is_some_and(|&o| o != UNOWNED))?;
        }
        BindingSource::Precomputed { bindings, bands } => {
            if bindings.len() != positions.len() {
                return Err(InputError::BindingCount { bindings: bindings.len(), vertices: positions.len() }.into());
            }
            if let Some(i) = bindings.iter().position(|b| b.cell != UNOWNED && (b.cell & !BAND_FLAG) as usize >= cells)
            {
                return Err(InputError::BindingCellOutOfRange { binding: i, cell: bindings[i].cell, cells }.into());
            }
            let band = |b: &BandRecord| (b.vertex, b.weight as f64, b.cell);
            let bound = |v: usize| bindings.get(v).is_some_and(|b| b.cell != UNOWNED);
            super::check_bands(bands, band, cells, bound).map_err(|()| InputError::BandRecordsOutOfOrder)?;
        }
    }
    Ok(())
}
