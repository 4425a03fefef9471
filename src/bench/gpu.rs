//! The GPU bench: bind, deform, copy and skinning kernels on one device, timed per pass.

use std::ops::Range;
use std::time::Instant;

use wgpu::util::DeviceExt;

use super::alternatives::Alternatives;
use super::creation::{CreationReport, compile_kernels, timed_deformer};
use super::engine::EngineComparisons;
use super::fused::{FusedComparison, RECORD_STRIDE};
use super::passes::{Dispatches, Stamps, chunk_params, encode, time};
use super::skinning::{skinning_influences, skinning_joints};
use super::traffic::{BufferCopy, MemoryReport, PassTimes};
use super::{BenchReport, BenchScene, FalloffKind, FalloffReport, GpuTimer, Round, best_of, median, median_of};
use crate::coeffs::{BAND_FLAG, SweepCoefficients};
use crate::gpu::binder::Binder;
use crate::gpu::buffers::window;
use crate::gpu::{
    BAND_STRIDE, BINDING_STRIDE, BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, GpuError, POSITION_STRIDE,
    dispatch_grid, kernels, uniform_chunks, wait,
};

/// Runs before the timed ones.
const WARMUP: usize = 3;
/// Each round keeps the best of this many back-to-back timings of a kernel, so that a burst of
/// load from elsewhere on a shared machine does not land in one kernel's figure only.
const BEST_OF: usize = 3;

/// Every kernel of the bench, set up on one device for one scene.
pub struct GpuBench {
    context: GpuContext,
    scene: BenchScene,
    deformer: GpuDeformer,
    /// The owners as the bind kernel takes them, with BAND_FLAG on band vertices.
    flagged_owners: Vec<u32>,
    /// The falloff comparisons' deformers, posed once.
    falloff: Vec<(FalloffKind, GpuDeformer)>,
    binder: Binder,
    copy: Dispatches,
    skinning: Dispatches,
    timer: Option<GpuTimer>,
    /// Instances against one mesh, a partial rig against a full one.
    engine: EngineComparisons,
    /// The fused deform + Jacobian normals kernel.
    fused: FusedComparison,
    /// The whole-buffer copy, the memory ceiling of the copy engine.
    buffer_copy: BufferCopy,
    /// The deform pass as the adapter did not choose it.
    alternatives: Alternatives,
    creation: CreationReport,
}

impl GpuBench {
    /// Uploads the scene, binds it once, and prepares the baselines.
    pub fn new(context: &GpuContext, scene: BenchScene) -> Result<GpuBench, GpuError> {
        let device = &context.device;
        let rest = scene.rig.rest();
        let bands = scene.rig.band_weights(&scene.mesh, &scene.owners);
        let source = BindingSource::Bind { owners: &scene.owners, bands: &bands };
        let positions = crate::gpu::rest_positions(&scene.mesh.positions);
        let triangles: Vec<u32> = scene.mesh.faces.triangles().flatten().collect();
        let descriptor = DeformerDescriptor::new(rest, &positions, source).with_triangles(&triangles);
        compile_kernels(context, &descriptor)?;
        let (mut deformer, creation_ms, creation_host_ms) = timed_deformer(context, &descriptor)?;
        let fused = FusedComparison::new(context, descriptor, &mut deformer, &scene.posed)?;
        let mut flagged_owners = scene.owners.clone();
        for band in &bands {
            flagged_owners[band.vertex as usize] |= BAND_FLAG;
        }
        let falloff = falloff_deformers(context, &scene)?;
        let binder = Binder::new(context, rest, &SweepCoefficients::new(rest), deformer.rest_cells());
        let n = deformer.vertex_count();
        let scratch = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd bench output"),
            size: n as u64 * POSITION_STRIDE,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let copy = copy_baseline(device, &deformer, &scratch);
        let buffer_copy = BufferCopy::new(context, n as u64 * BINDING_STRIDE);
        let alternatives = Alternatives::new(context, &scene, &deformer)?;
        let creation = CreationReport {
            ms: creation_ms,
            host_ms: creation_host_ms,
            jacobian_normals_ms: fused.creation.0,
            jacobian_normals_host_ms: fused.creation.1,
        };
        let skinning = skinning_baseline(device, &scene, deformer.limits(), &scratch);
        Ok(GpuBench {
            context: context.clone(),
            scene,
            deformer,
            flagged_owners,
            falloff,
            binder,
            copy,
            skinning,
            timer: GpuTimer::new(context),
            engine: EngineComparisons::new(context, n as usize)?,
            fused,
            buffer_copy,
            alternatives,
            creation,
        })
    }

    /// The deformer under test.
    pub fn deformer(&self) -> &GpuDeformer {
        &self.deformer
    }

    /// Seconds to bind every vertex (the bind kernel alone). Call before the deform timings:
    /// binding reads the rest positions, which deforming overwrites.
    pub fn time_bind(&self) -> Result<f64, GpuError> {
        let limits = *self.deformer.limits();
        let chunks: Vec<(Range<u32>, wgpu::Buffer)> =
            self.deformer.binding_chunks().map(|(range, buffer)| (range.clone(), buffer.clone())).collect();
        self.time(|encoder, stamps| {
            let last = chunks.len() - 1;
            for (c, (range, bindings)) in chunks.iter().enumerate() {
                let owners = &self.flagged_owners[range.start as usize..range.end as usize];
                let writes = match (c == 0, c == last) {
                    (true, true) => stamps.pass(),
                    (true, false) => stamps.opening(),
                    (false, true) => stamps.closing(),
                    (false, false) => None,
                };
                self.binder.encode(encoder, range, owners, self.deformer.positions(), bindings, &limits, writes);
            }
        })
    }

    /// Seconds of the deform kernel alone, after the pose has been set.
    pub fn time_deform(&mut self) -> Result<f64, GpuError> {
        self.deformer.set_pose(0, &self.scene.posed)?;
        time(&self.context, self.timer.as_ref(), |encoder, stamps| {
            self.deformer.encode_deform_pass(encoder, stamps.pass())
        })
    }

    /// Seconds of the deform pass of falloff comparison `i`.
    pub fn time_falloff_deform(&mut self, i: usize) -> Result<f64, GpuError> {
        let deformer = &mut self.falloff[i].1;
        time(&self.context, self.timer.as_ref(), |encoder, stamps| deformer.encode_deform_pass(encoder, stamps.pass()))
    }

    /// Seconds of the deform pass of [`INSTANCES`](super::INSTANCES) instances of a small tube
    /// and of one tube of as many vertices in all, back to back.
    pub fn time_instances(&mut self) -> Result<(f64, f64), GpuError> {
        self.engine.time_instances(&self.context, self.timer.as_ref())
    }

    /// Seconds of the deform and normals passes of a rig owning
    /// [`PARTIAL_SHARE`](super::PARTIAL_SHARE) of a tube and of one owning all, back to back.
    pub fn time_partial(&mut self) -> Result<(f64, f64), GpuError> {
        self.engine.time_partial(&self.context, self.timer.as_ref())
    }

    /// Seconds of the fused deform + Jacobian normals pass.
    pub fn time_fused(&mut self) -> Result<f64, GpuError> {
        self.fused.time_fused(&self.context, self.timer.as_ref())
    }

    /// Seconds of the copy kernel moving the fused kernel's bytes.
    pub fn time_wide_copy(&self) -> Result<f64, GpuError> {
        self.fused.time_wide_copy(&self.context, self.timer.as_ref())
    }

    /// Seconds of the copy baseline.
    pub fn time_copy(&self) -> Result<f64, GpuError> {
        self.time(|encoder, stamps| encode(encoder, &self.copy, stamps))
    }

    /// Seconds of the skinning baseline.
    pub fn time_skinning(&self) -> Result<f64, GpuError> {
        self.time(|encoder, stamps| encode(encoder, &self.skinning, stamps))
    }

    /// Wall-clock seconds of one frame: posing the rig's sweeps from keys, turning them into
    /// coefficients, uploading those and the deform dispatch, waited for (no normals, no
    /// readback).
    pub fn time_frame(&mut self) -> Result<f64, GpuError> {
        let start = Instant::now();
        let posed = self.scene.rig.pose(&self.scene.keys)?;
        self.deformer.set_pose(0, &posed)?;
        let device = &self.context.device;
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd frame") });
        self.deformer.encode_deform_pass(&mut encoder, None);
        self.context.queue.submit([encoder.finish()]);
        wait(&self.context)?;
        Ok(start.elapsed().as_secs_f64())
    }

    /// Seconds of the normals pass alone (zero without faces).
    pub fn time_normals(&self) -> Result<f64, GpuError> {
        self.time(|encoder, stamps| self.deformer.encode_normals_pass(encoder, stamps.pass()))
    }

    /// Wall-clock seconds to read the positions back.
    pub fn time_readback(&self) -> Result<f64, GpuError> {
        let start = Instant::now();
        self.deformer.read_positions()?;
        Ok(start.elapsed().as_secs_f64())
    }

    /// Every figure of the report. Binding is timed first (it needs the rest positions); then
    /// each round times deform, copy, skinning and a frame back to back, so that the ratios
    /// compare kernels under the same machine load; figures and ratios are medians over rounds.
    pub fn report(&mut self, runs: usize) -> Result<BenchReport, GpuError> {
        let n = self.deformer.vertex_count() as f64;
        let bind = median_of(WARMUP, runs, || self.time_bind())?;
        let mut rounds = Vec::with_capacity(runs);
        for round in 0..WARMUP + runs {
            let times = Round {
                deform: best_of(BEST_OF, || self.time_deform())?,
                falloff: (0..self.falloff.len())
                    .map(|i| best_of(BEST_OF, || self.time_falloff_deform(i)))
                    .collect::<Result<_, _>>()?,
                copy: best_of(BEST_OF, || self.time_copy())?,
                lbs: best_of(BEST_OF, || self.time_skinning())?,
                frame: best_of(BEST_OF, || self.time_frame())?,
                normals: best_of(BEST_OF, || self.time_normals())?,
                instances: self.engine.time_instances(&self.context, self.timer.as_ref())?,
                partial: self.engine.time_partial(&self.context, self.timer.as_ref())?,
                fused: best_of(BEST_OF, || self.time_fused())?,
                wide_copy: best_of(BEST_OF, || self.time_wide_copy())?,
                buffer_copy: best_of(BEST_OF, || self.buffer_copy.seconds(&self.context, self.timer.as_ref()))?,
                alternatives: self.alternatives.time(&self.context, self.timer.as_ref())?,
            };
            if round >= WARMUP {
                rounds.push(times);
            }
        }
        let (rig, keys) = (&self.scene.rig, &self.scene.keys);
        let frame_cpu =
            super::median_host_frame_ms(&self.context, &mut self.deformer, rig, keys, super::FRAME_CPU_FRAMES)?;
        let readback = median_of(1, runs, || self.time_readback())?;
        let device_bytes = self.deformer.device_bytes();
        let column = |f: fn(&Round) -> f64| median(&mut rounds.iter().map(f).collect::<Vec<_>>());
        let falloff = self
            .falloff
            .iter()
            .enumerate()
            .map(|(i, (kind, deformer))| {
                let mut over: Vec<f64> = rounds.iter().map(|r| r.falloff[i] / r.deform).collect();
                let mut times: Vec<f64> = rounds.iter().map(|r| r.falloff[i]).collect();
                FalloffReport {
                    kind: *kind,
                    band_fraction: deformer.band_vertex_count() as f64 / deformer.vertex_count() as f64,
                    deform_verts_per_s: n / median(&mut times),
                    over_plain: median(&mut over),
                    device_bytes_per_vertex: Some(deformer.device_bytes() as f64 / deformer.vertex_count() as f64),
                }
            })
            .collect();
        Ok(BenchReport {
            backend: "gpu",
            adapter: format!("{} ({:?})", self.context.info.name, self.context.info.backend),
            n: n as usize,
            cell_records: Some(self.deformer.cell_records().name()),
            deform_order: Some(self.deformer.deform_order().name()),
            bind_verts_per_s: n / bind,
            deform_verts_per_s: n / column(|r| r.deform),
            copy_verts_per_s: n / column(|r| r.copy),
            lbs_verts_per_s: n / column(|r| r.lbs),
            deform_over_copy: column(|r| r.deform / r.copy),
            deform_over_lbs: column(|r| r.deform / r.lbs),
            cpu: None,
            frame_ms: column(|r| r.frame) * 1e3,
            frame_cpu_ms: Some(frame_cpu),
            normals_ms: column(|r| r.normals) * 1e3,
            readback_ms: Some(readback * 1e3),
            device_bytes_per_vertex: Some(device_bytes as f64 / n),
            falloff,
            instances_over_single: Some(column(|r| r.instances.0 / r.instances.1)),
            partial_over_full: Some(column(|r| r.partial.0 / r.partial.1)),
            fused_over_copy: Some(column(|r| r.fused / r.wide_copy)),
            fused_over_separate: Some(column(|r| r.fused / (r.deform + r.normals))),
            normals_angle_p99_deg: Some(self.fused.angle_p99_deg),
            alternatives: self
                .alternatives
                .reports(n, &rounds.iter().map(|r| (r.alternatives.clone(), r.deform)).collect::<Vec<_>>()),
            creation: Some(self.creation),
            memory: Some(self.memory_report(&rounds, bind)),
            runs,
            repeats: super::repeats(&self.context),
            timestamps: self.timer.is_some(),
        })
    }

    /// The traffic of every pass over `rounds`, binding (timed apart) at its median `bind`
    /// seconds in each.
    fn memory_report(&self, rounds: &[Round], bind: f64) -> MemoryReport {
        let n = self.deformer.vertex_count() as f64;
        let column = |f: &dyn Fn(&Round) -> f64| rounds.iter().map(f).collect::<Vec<f64>>();
        let plain = (self.deformer.dispatched_vertex_count() as u64 * (BINDING_STRIDE + POSITION_STRIDE)) as f64 / n;
        let times = |pass, bytes_per_vertex, seconds| PassTimes { pass, bytes_per_vertex, seconds };
        let copy = times("copy kernel", plain, column(&|r| r.copy));
        let mut passes = vec![
            times("deform", plain, column(&|r| r.deform)),
            copy.clone(),
            times("lbs", (2 * POSITION_STRIDE + 8) as f64, column(&|r| r.lbs)),
        ];
        for (i, (kind, deformer)) in self.falloff.iter().enumerate() {
            let band_share = deformer.band_vertex_count() as f64 / deformer.vertex_count() as f64;
            let bytes = (BINDING_STRIDE + POSITION_STRIDE) as f64 + band_share * (BAND_STRIDE + BINDING_STRIDE) as f64;
            let pass = match kind {
                FalloffKind::Rest => "bands (rest)",
                FalloffKind::Sweep => "bands (sweep)",
            };
            passes.push(times(pass, bytes, column(&|r| r.falloff[i])));
        }
        passes.push(times("normals", self.deformer.normals_frame_bytes() as f64 / n, column(&|r| r.normals)));
        let fused = (BINDING_STRIDE + RECORD_STRIDE + 2 * POSITION_STRIDE) as f64;
        passes.push(times("fused", fused, column(&|r| r.fused)));
        passes.push(times("bind", (4 + POSITION_STRIDE + BINDING_STRIDE) as f64, vec![bind; rounds.len()]));
        let copy_rates = column(&|r| self.buffer_copy.bytes() / r.buffer_copy);
        MemoryReport::new(n, &copy, &copy_rates, &passes)
    }

    /// Records with `record`, submits, waits, and returns the timestamped seconds (wall-clock
    /// without timestamp queries).
    fn time(&self, record: impl FnMut(&mut wgpu::CommandEncoder, Stamps)) -> Result<f64, GpuError> {
        time(&self.context, self.timer.as_ref(), record)
    }
}

/// The falloff comparisons' deformers, each posed once.
fn falloff_deformers(context: &GpuContext, scene: &BenchScene) -> Result<Vec<(FalloffKind, GpuDeformer)>, GpuError> {
    let mut falloff = Vec::with_capacity(scene.with_falloff.len());
    for (kind, variant) in &scene.with_falloff {
        let bands = variant.rig.band_weights(&variant.mesh, &variant.owners);
        let source = BindingSource::Bind { owners: &variant.owners, bands: &bands };
        let positions = crate::gpu::rest_positions(&variant.mesh.positions);
        let mut deformer = GpuDeformer::new(context, &DeformerDescriptor::new(variant.rig.rest(), &positions, source))?;
        deformer.set_pose(0, &variant.posed)?;
        falloff.push((*kind, deformer));
    }
    Ok(falloff)
}

/// The copy baseline over the deformer's chunks: each bound vertex's binding read, its
/// position written into `scratch`, as the deform kernel reads and writes.
fn copy_baseline(device: &wgpu::Device, deformer: &GpuDeformer, scratch: &wgpu::Buffer) -> Dispatches {
    let limits = *deformer.limits();
    let kernel = kernels::copy(device);
    let dispatches = deformer
        .binding_chunks()
        .map(|(range, bindings)| {
            let params = chunk_params(device, range);
            let group = kernel.bind_group(
                device,
                "sweepffd copy baseline",
                &[params.as_entire_binding(), bindings.as_entire_binding(), window(scratch, range, POSITION_STRIDE)],
            );
            (group, dispatch_grid(range.len() as u32, &limits))
        })
        .collect();
    (kernel, dispatches)
}

/// The four-bone linear blend skinning baseline over every vertex of `scene`, writing into
/// `scratch`.
fn skinning_baseline(
    device: &wgpu::Device,
    scene: &BenchScene,
    limits: &crate::gpu::ChunkLimits,
    scratch: &wgpu::Buffer,
) -> Dispatches {
    let n = scene.vertex_count() as u32;
    let kernel = kernels::skinning(device);
    let storage = |label, bytes: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage: wgpu::BufferUsages::STORAGE,
        })
    };
    let joints = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("sweepffd bench joints"),
        contents: bytemuck::cast_slice(&skinning_joints()),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let rest_f32 = crate::cpu::packed(&scene.mesh.positions);
    let rest_buffer = storage("sweepffd bench rest", bytemuck::cast_slice(&rest_f32));
    let influences = storage("sweepffd bench influences", bytemuck::cast_slice(&skinning_influences(n as usize)));
    let dispatches = uniform_chunks(n, POSITION_STRIDE, limits)
        .iter()
        .map(|range| {
            let params = chunk_params(device, range);
            let group = kernel.bind_group(
                device,
                "sweepffd skinning baseline",
                &[
                    params.as_entire_binding(),
                    joints.as_entire_binding(),
                    window(&rest_buffer, range, POSITION_STRIDE),
                    window(&influences, range, 8),
                    window(scratch, range, POSITION_STRIDE),
                ],
            );
            (group, dispatch_grid(range.len() as u32, limits))
        })
        .collect();
    (kernel, dispatches)
}
