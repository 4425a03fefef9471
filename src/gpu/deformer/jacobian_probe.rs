//! The Jacobian probe on the GPU: which vertices of the Jacobian reach keep the normals the
//! fused deform kernel writes (`crate::deform::jacobian_normal_vertices` says why and is the f64
//! twin). Once at creation, after the binding, the rest normals and the normal coordinates are
//! recorded: the fused kernel deforms the mesh by the probe pose ([`PROBE`]) into scratch
//! positions and Jacobian normals, the normals kernel computes the normals of the probed
//! triangles, and `shaders/jacobian_probe.wgsl` compares the two for each probed vertex. The
//! verdicts, one word a probed vertex, are the one readback of a deformer's creation.
//!
//! Data flow: bind → normal coordinates → **probe (fused deform, normals, verdicts)** → the
//! normals pass's per-frame vertex lists.

use std::ops::Range;

use super::super::buffers::{POSITION_STRIDE, cells_buffer, params_buffer, window};
use super::super::chunks::{ChunkLimits, dispatch_grid};
use super::super::kernels::DeformVariant;
use super::super::normals_pass::{NormalsShape, list_chunks, record, storage_init};
use super::super::readback::read_bytes;
use super::super::{GpuContext, GpuError};
use crate::coeffs::{DispatchParams, InstanceParams, SweepCoefficients, UNOWNED};
use crate::deform::probe_sweep;
use crate::normals::NormalAdjacency;
use crate::sweep::Sweep;
use wgpu::util::DeviceExt;

/// What the probe reads of the deformer: each deform chunk's vertices, bindings and normal
/// coordinates, the rest positions and normals.
pub(super) struct ProbeInputs<'a> {
    pub rest: &'a [Sweep],
    pub coefficients: &'a SweepCoefficients,
    pub chunks: Vec<(Range<u32>, &'a wgpu::Buffer, &'a wgpu::Buffer)>,
    /// The rest positions, vertex 0 at byte 0.
    pub rest_positions: &'a wgpu::Buffer,
    /// The rest normals, vertex 0 at byte 0.
    pub rest_normals: &'a wgpu::Buffer,
    pub vertex_count: u32,
    pub limits: &'a ChunkLimits,
}

/// A probe recorded and not yet read: the verdicts' buffer and what they decide.
pub(super) struct JacobianProbe {
    verdicts: wgpu::Buffer,
    /// The probed vertices, ascending.
    probed: Vec<u32>,
    /// Every vertex's verdict, those of the probed vertices to be read: true in the reach of a
    /// sweep the probe cannot pose or without triangles (it keeps the Jacobian), false out of
    /// the reach.
    by_deform: Vec<bool>,
}

impl JacobianProbe {
    /// Records the probe of the vertices in `reach` (each moved whole by the sweep `influence`
    /// names) into `encoder`.
    pub(super) fn encode(
        context: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &ProbeInputs,
        (adjacency, reach, influence): (&NormalAdjacency, &[bool], &[u32]),
    ) -> Result<JacobianProbe, GpuError> {
        let device = &context.device;
        // A sweep the probe cannot pose keeps its reach; it stays at rest in the probe.
        let probes: Vec<Option<Sweep>> = inputs.rest.iter().map(probe_sweep).collect();
        let posed: Vec<Sweep> =
            probes.iter().zip(inputs.rest).map(|(probe, rest)| probe.clone().unwrap_or_else(|| rest.clone())).collect();
        let mut coefficients = inputs.coefficients.clone();
        coefficients.update(&posed)?;
        // A vertex without triangles has a zero rest normal and keeps the Jacobian unprobed.
        let unprobed = |v: usize| {
            influence[v] != UNOWNED && probes[influence[v] as usize].is_none() || adjacency.fans_of(v).is_empty()
        };
        let by_deform: Vec<bool> = (0..reach.len()).map(|v| reach[v] && unprobed(v)).collect();
        let probed: Vec<u32> =
            (0..reach.len() as u32).filter(|&v| reach[v as usize] && !unprobed(v as usize)).collect();
        let n = inputs.vertex_count as u64;
        let scratch = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: n.max(1) * POSITION_STRIDE,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let (positions, jacobian, facets) =
            (scratch("sweepffd probe positions"), scratch("sweepffd probe normals"), scratch("sweepffd probe facets"));
        encoder.copy_buffer_to_buffer(inputs.rest_positions, 0, &positions, 0, n * POSITION_STRIDE);
        let cells = cells_buffer(device, &coefficients, DeformVariant::Storage);
        let kernel = context.kernels().deform_normals(device, DeformVariant::Storage);
        let deform: Vec<_> = inputs
            .chunks
            .iter()
            .map(|(range, bindings, coordinates)| {
                let params = InstanceParams {
                    vertex_count: range.len() as u32,
                    cells_per_instance: coefficients.cells.len() as u32,
                    instance_count: 1,
                    ..Default::default()
                };
                let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sweepffd probe params"),
                    contents: bytemuck::bytes_of(&params),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let group = kernel.bind_group(
                    device,
                    "sweepffd probe deform",
                    &[
                        params.as_entire_binding(),
                        cells.as_entire_binding(),
                        bindings.as_entire_binding(),
                        window(&positions, range, POSITION_STRIDE),
                        coordinates.as_entire_binding(),
                        window(&jacobian, range, POSITION_STRIDE),
                    ],
                );
                (group, dispatch_grid(range.len() as u32, inputs.limits))
            })
            .collect();
        record(encoder, "sweepffd probe deform", &kernel, &deform);
        let shape = NormalsShape {
            positions: positions.clone(),
            positions_base: 0,
            stride: inputs.vertex_count,
            total: inputs.vertex_count,
            limits: *inputs.limits,
        };
        shape.record(context, encoder, adjacency, &facets, &probed)?;
        // One word a vertex, written for the probed ones only.
        let verdicts = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd probe verdicts"),
            size: n.max(1) * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let kernel = context.kernels().jacobian_probe(device);
        let chunks = list_chunks(&probed, POSITION_STRIDE, |_| 0, inputs.limits).unwrap_or_default();
        let compare: Vec<_> = chunks
            .iter()
            .map(|chunk| {
                let list: Vec<u32> = probed[chunk.items.clone()].iter().map(|v| v - chunk.span.start).collect();
                let count = list.len() as u32;
                let params =
                    DispatchParams { vertex_count: count, first_vertex: chunk.span.start, ..Default::default() };
                let group = kernel.bind_group(
                    device,
                    "sweepffd probe verdicts",
                    &[
                        params_buffer(device, params).as_entire_binding(),
                        storage_init(device, "sweepffd probed vertices", &list).as_entire_binding(),
                        window(&jacobian, &chunk.span, POSITION_STRIDE),
                        window(&facets, &chunk.span, POSITION_STRIDE),
                        window(inputs.rest_normals, &chunk.span, POSITION_STRIDE),
                        window(&verdicts, &chunk.span, 4),
                    ],
                );
                (group, dispatch_grid(count, inputs.limits))
            })
            .collect();
        record(encoder, "sweepffd probe verdicts", &kernel, &compare);
        Ok(JacobianProbe { verdicts, probed, by_deform })
    }

    /// The vertices whose normals the deform kernel writes, once the recorded probe has been
    /// submitted: reads the verdicts back (blocking until the GPU has run the probe).
    pub(super) fn by_deform(self, context: &GpuContext) -> Result<Vec<bool>, GpuError> {
        let JacobianProbe { verdicts, probed, mut by_deform } = self;
        if probed.is_empty() {
            return Ok(by_deform);
        }
        let bytes = read_bytes(context, &verdicts, 0, by_deform.len() as u64 * 4)?;
        let verdicts: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
        for &v in &probed {
            by_deform[v as usize] = verdicts[v as usize] != 0;
        }
        Ok(by_deform)
    }
}
