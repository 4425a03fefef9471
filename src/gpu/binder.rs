//! The bind kernel (`shaders/bind.wgsl`) with the rest rig's tables: binds chunks of vertices
//! whose rest positions are on the GPU.

use std::ops::Range;

use wgpu::util::DeviceExt;

use super::GpuContext;
use super::buffers::{POSITION_STRIDE, params_buffer, window};
use super::chunks::{ChunkLimits, dispatch_grid};
use super::kernels::Kernel;
use crate::coeffs::{DispatchParams, SweepCoefficients, bind_segments};
use crate::sweep::Sweep;

/// The bind kernel with the rest rig's tables: used while the deformer is built, and kept to
/// bind the second influences of new falloff bands. `cells` must hold the rest rig's records.
#[derive(Debug)]
pub(crate) struct Binder {
    kernel: std::sync::Arc<Kernel>,
    device: wgpu::Device,
    cells: wgpu::Buffer,
    bind_segments: wgpu::Buffer,
    sweeps: wgpu::Buffer,
}

impl Binder {
    pub(crate) fn new(
        context: &GpuContext,
        rest: &[Sweep],
        coefficients: &SweepCoefficients,
        cells: &wgpu::Buffer,
    ) -> Binder {
        let device = &context.device;
        let table = |label, bytes: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytes,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let segments = bind_segments(rest);
        let cubic = segments.iter().any(|segment| segment.degree != 5);
        Binder {
            kernel: context.kernels().bind(device, cubic),
            device: device.clone(),
            cells: cells.clone(),
            bind_segments: table("sweepffd bind segments", bytemuck::cast_slice(&segments)),
            sweeps: table("sweepffd sweeps", bytemuck::cast_slice(&coefficients.sweeps)),
        }
    }

    /// Records the binding of the vertices in `range` into `bindings`.
    #[expect(clippy::too_many_arguments, reason = "one per resource of the dispatch")]
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        range: &Range<u32>,
        owners: &[u32],
        positions: &wgpu::Buffer,
        bindings: &wgpu::Buffer,
        limits: &ChunkLimits,
        timestamps: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let device = &self.device;
        let owners = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd owners"),
            contents: bytemuck::cast_slice(owners),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let params = params_buffer(device, DispatchParams { vertex_count: range.len() as u32, ..Default::default() });
        let group = self.kernel.bind_group(
            device,
            "sweepffd bind",
            &[
                params.as_entire_binding(),
                self.cells.as_entire_binding(),
                self.bind_segments.as_entire_binding(),
                self.sweeps.as_entire_binding(),
                owners.as_entire_binding(),
                window(positions, range, POSITION_STRIDE),
                bindings.as_entire_binding(),
            ],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sweepffd bind"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.kernel.pipeline);
        pass.set_bind_group(0, &group, &[]);
        let (x, y) = dispatch_grid(range.len() as u32, limits);
        pass.dispatch_workgroups(x, y, 1);
    }
}
