//! The tangents pass: the host's rest tangents turned with the normals of the deformed mesh
//! (`shaders/tangents.wgsl`; f64 reference [`crate::normals::tangents`]), recorded after the
//! normals pass.
//!
//! Like the normals, every tangent is computed once at creation (from the rest normals, so that
//! each output tangent is orthogonal to its normal) and per frame only those of the vertices the
//! normals pass recomputes. The stage serves the same `instances` copies of one mesh as its
//! [`NormalsStage`]: instance k's vertex v is at `k · vertex_count + v` in every buffer.

use wgpu::util::DeviceExt;

use std::sync::Arc;

use super::InputError;
use super::buffers::{POSITION_STRIDE, check_fits, params_buffer, window};
use super::chunks::{ChunkLimits, dispatch_grid};
use super::kernels::Kernel;
use super::normals_pass::{Dispatch, NormalsStage, list_chunks, record, storage_init};
use super::{GpuContext, GpuError};
use crate::coeffs::DispatchParams;
use crate::normals::instanced;

/// Bytes per vertex of the tangent buffers: f32 xyzw, tightly packed.
pub const TANGENT_STRIDE: u64 = 16;

/// The tangents pass: its kernel, the rest data it reads, its output buffer and per-frame
/// dispatches.
#[derive(Debug)]
pub(crate) struct TangentStage {
    kernel: Arc<Kernel>,
    /// The output: f32 xyzw per vertex, `VERTEX | STORAGE | COPY_SRC`.
    buffer: wgpu::Buffer,
    /// The per-frame dispatches, over the normals stage's dirty vertices.
    dispatches: Vec<Dispatch>,
    /// Device memory the stage keeps: the tangents, the rest normals and tangents it reads and
    /// the per-frame vertex lists.
    pub(crate) device_bytes: u64,
}

/// What the tangent dispatches of one stage share.
struct TangentPlan<'a> {
    kernel: &'a Kernel,
    rest_normals: &'a wgpu::Buffer,
    normals: &'a wgpu::Buffer,
    rest_tangents: &'a wgpu::Buffer,
    tangents: &'a wgpu::Buffer,
    limits: &'a ChunkLimits,
}

impl TangentStage {
    /// Plans the tangents of `instances` copies of a mesh of `vertex_count` vertices whose rest
    /// tangents are `rest_tangents` (xyzw per vertex of one instance, w = ±1 the handedness, as
    /// glTF stores them), turned with the normals of `normals` (built for the same instances).
    /// Records, into `encoder` after the normals' rest pass, the copy of the rest normals and
    /// the pass over every vertex; the stage's own dispatches then cover the normals' dirty
    /// vertices. Fails on a tangent count other than `vertex_count`, a non-finite tangent, or
    /// buffers beyond the device's limits.
    pub(crate) fn new(
        context: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        rest_tangents: &[[f32; 4]],
        normals: &NormalsStage,
        (vertex_count, stride): (u32, u32),
        instances: u32,
        limits: &ChunkLimits,
    ) -> Result<TangentStage, GpuError> {
        if rest_tangents.len() != vertex_count as usize {
            return Err(InputError::TangentCount { tangents: rest_tangents.len(), vertices: vertex_count }.into());
        }
        if let Some(i) = rest_tangents.iter().position(|t| !t.iter().all(|c| c.is_finite())) {
            return Err(InputError::TangentNotFinite { index: i }.into());
        }
        let device = &context.device;
        let total = (instances.max(1) as u64 - 1) * stride as u64 + vertex_count as u64;
        check_fits("the tangent buffer", total * TANGENT_STRIDE, limits.max_buffer)?;
        let rest_normals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd rest normals"),
            size: total * POSITION_STRIDE,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_buffer_to_buffer(&normals.buffer, 0, &rest_normals, 0, total * POSITION_STRIDE);
        let mut every_instance = vec![[0.0f32; 4]; total as usize];
        for k in 0..instances.max(1) as usize {
            let first = k * stride as usize;
            every_instance[first..first + vertex_count as usize].copy_from_slice(rest_tangents);
        }
        let rest_tangents = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sweepffd rest tangents"),
            contents: bytemuck::cast_slice(&every_instance),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd tangents"),
            size: total * TANGENT_STRIDE,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let kernel = context.kernels().tangents(device);
        let plan = TangentPlan {
            kernel: &kernel,
            rest_normals: &rest_normals,
            normals: &normals.buffer,
            rest_tangents: &rest_tangents,
            tangents: &buffer,
            limits,
        };
        let every = instanced(&(0..vertex_count).collect::<Vec<u32>>(), stride, instances.max(1));
        record(encoder, "sweepffd rest tangents", &kernel, &plan.dispatches(device, &every)?);
        let dispatches = plan.dispatches(device, &normals.dirty)?;
        let device_bytes = buffer.size() + rest_normals.size() + rest_tangents.size() + 4 * normals.dirty.len() as u64;
        Ok(TangentStage { kernel, buffer, dispatches, device_bytes })
    }

    /// The deformed tangents, f32 xyzw per vertex (16 bytes, tightly packed, instance after
    /// instance); usage `VERTEX | STORAGE | COPY_SRC`.
    pub(crate) fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Number of per-frame dispatches.
    pub(crate) fn dispatch_count(&self) -> usize {
        self.dispatches.len()
    }

    /// Records the per-frame dispatches into `pass`, which must come after the normals pass's
    /// (in the same pass or a later one).
    pub(crate) fn encode(&self, pass: &mut wgpu::ComputePass) {
        pass.set_pipeline(&self.kernel.pipeline);
        for (group, grid) in &self.dispatches {
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(grid.0, grid.1, 1);
        }
    }
}

impl TangentPlan<'_> {
    /// The dispatches computing the tangents of `vertices` (ascending, over all instances).
    fn dispatches(&self, device: &wgpu::Device, vertices: &[u32]) -> Result<Vec<Dispatch>, GpuError> {
        let chunks = list_chunks(vertices, TANGENT_STRIDE, |_| 0, self.limits).ok_or(InputError::TangentTooLarge)?;
        let dispatches = chunks
            .iter()
            .map(|chunk| {
                let list = &vertices[chunk.items.clone()];
                let params = params_buffer(
                    device,
                    DispatchParams {
                        vertex_count: list.len() as u32,
                        first_vertex: chunk.span.start,
                        ..Default::default()
                    },
                );
                let group = self.kernel.bind_group(
                    device,
                    "sweepffd tangents",
                    &[
                        params.as_entire_binding(),
                        storage_init(device, "sweepffd tangent vertices", list).as_entire_binding(),
                        window(self.rest_normals, &chunk.span, POSITION_STRIDE),
                        window(self.normals, &chunk.span, POSITION_STRIDE),
                        window(self.rest_tangents, &chunk.span, TANGENT_STRIDE),
                        window(self.tangents, &chunk.span, TANGENT_STRIDE),
                    ],
                );
                (group, dispatch_grid(list.len() as u32, self.limits))
            })
            .collect();
        Ok(dispatches)
    }
}

#[cfg(test)]
mod tests {
    //! Both stages on three instances of one tube, the second and third moved differently in
    //! the first sweep-owned half: each instance's normals and tangents match the twins'.
    //! Without a GPU adapter the test passes with a notice (unless `SWEEPFFD_REQUIRE_GPU=1`).

    use glam::{DVec3, Vec3};

    use super::*;
    use crate::gpu::{GpuContext, read_bytes};
    use crate::normals::{NormalAdjacency, dirty_vertices};
    use crate::synthetic::Tube;

    #[test]
    fn three_instances_each_get_their_own_normals_and_tangents() {
        let context = match GpuContext::new() {
            Ok(context) => context,
            Err(e) if std::env::var("SWEEPFFD_REQUIRE_GPU").is_ok_and(|v| v == "1") => panic!("no GPU: {e}"),
            Err(e) => return eprintln!("skipping GPU test: {e}"),
        };
        let device = &context.device;
        let mesh = Tube { rings: 12, around: 10, length: 2.0, radius: 0.5 }.mesh();
        let n = mesh.positions.len();
        let moves: Vec<bool> = mesh.positions.iter().map(|p| p.z > 1.0).collect();
        let instance = |k: usize| -> Vec<f32> {
            let bend = |p: DVec3| if p.z > 1.0 { p + DVec3::new(0.3 * k as f64 * (p.z - 1.0), 0.0, 0.0) } else { p };
            crate::cpu::packed(&mesh.positions.iter().map(|&p| bend(p)).collect::<Vec<_>>())
        };
        let rest_tangents: Vec<[f32; 4]> =
            mesh.positions.iter().map(|p| Vec3::new(-p.y as f32, p.x as f32, 0.1).extend(1.0).to_array()).collect();
        let positions = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: 3 * n as u64 * POSITION_STRIDE,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let rest: Vec<f32> = (0..3).flat_map(|_| instance(0)).collect();
        context.queue.write_buffer(&positions, 0, bytemuck::cast_slice(&rest));
        let limits = ChunkLimits::of(&device.limits());
        let mut encoder = device.create_command_encoder(&Default::default());
        let normals = NormalsStage::new(
            &context,
            &mut encoder,
            &NormalAdjacency::new(&mesh.faces, n),
            (&positions, 0),
            (n as u32, n as u32),
            3,
            (&moves, None),
            &limits,
        )
        .unwrap();
        let tangents =
            TangentStage::new(&context, &mut encoder, &rest_tangents, &normals, (n as u32, n as u32), 3, &limits)
                .unwrap();
        context.queue.submit([encoder.finish()]);
        // The frame: the instances' own positions, then the per-frame dispatches.
        let posed: Vec<f32> = (0..3).flat_map(instance).collect();
        context.queue.write_buffer(&positions, 0, bytemuck::cast_slice(&posed));
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&normals.kernel.pipeline);
            for (group, grid) in &normals.dispatches {
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(grid.0, grid.1, 1);
            }
            tangents.encode(&mut pass);
        }
        context.queue.submit([encoder.finish()]);
        let gpu_normals: Vec<f32> =
            bytemuck::pod_collect_to_vec(&read_bytes(&context, &normals.buffer, 0, 3 * n as u64 * 12).unwrap());
        let gpu_tangents: Vec<[f32; 4]> =
            bytemuck::pod_collect_to_vec(&read_bytes(&context, tangents.buffer(), 0, 3 * n as u64 * 16).unwrap());

        let adjacency = NormalAdjacency::new(&mesh.faces, n);
        assert_eq!(normals.dirty.len(), 3 * dirty_vertices(&adjacency, |v| moves[v]).len());
        let mut rest_normals = vec![0.0; 3 * n];
        crate::cpu::normals::normals(&instance(0), &adjacency, &mut rest_normals);
        for k in 0..3 {
            let mut twin_normals = vec![0.0; 3 * n];
            crate::cpu::normals::normals(&instance(k), &adjacency, &mut twin_normals);
            let mut twin_tangents = vec![[0.0; 4]; n];
            crate::cpu::tangents::tangents(&rest_normals, &twin_normals, &rest_tangents, &mut twin_tangents);
            for v in 0..n {
                let g = k * n + v;
                let normal = Vec3::from_slice(&gpu_normals[3 * g..3 * g + 3]);
                let error = (normal - Vec3::from_slice(&twin_normals[3 * v..3 * v + 3])).length();
                assert!(error < 1e-5, "instance {k}, vertex {v}: normal {normal} off by {error}");
                let error = (glam::Vec4::from(gpu_tangents[g]) - glam::Vec4::from(twin_tangents[v])).length();
                assert!(error < 1e-5, "instance {k}, vertex {v}: tangent {:?} off by {error}", gpu_tangents[g]);
            }
        }
        let moved = (0..n).filter(|&v| gpu_normals[3 * (2 * n + v)] != gpu_normals[3 * v]).count();
        assert!(moved > 0, "the instances' normals do not differ: the test would prove nothing");
    }
}
