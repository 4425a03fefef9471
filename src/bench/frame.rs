//! The host's share of a frame: what the documented frame loop costs the CPU — posing the rig
//! into storage made once ([`Rig::pose_into`]), turning the posed sweeps into coefficients and
//! queueing their upload ([`GpuDeformer::set_pose`]), and recording the deform and normals
//! passes ([`GpuDeformer::encode`]) into an encoder the application made. The GPU's own time
//! is not in it (see `frame_ms`); neither are the encoder's creation and submission, which the
//! application pays for its own passes too.

use std::time::Instant;

use super::{BenchScene, median};
use crate::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, GpuError, wait};
use crate::rig::{PoseBuffer, Rig};
use crate::sweep::Key;
use crate::synthetic::{Tube, split_tube_rig};

/// Frames timed for `frame_cpu_ms`, after [`FRAME_WARMUP`] untimed ones.
pub const FRAME_CPU_FRAMES: usize = 500;
/// Frames run before timing.
pub const FRAME_WARMUP: usize = 50;
/// The GPU is waited for every this many frames, so that queued work stays bounded.
const FRAMES_PER_WAIT: usize = 16;

/// Host seconds of one frame of posing `rig` by `keys` into `posed` and deforming by it with
/// `deformer`; the encoder is made before the clock starts and submitted after it stops.
pub fn host_frame_seconds(
    context: &GpuContext,
    deformer: &mut GpuDeformer,
    rig: &Rig,
    keys: &[Vec<Key>],
    posed: &mut PoseBuffer,
) -> Result<f64, GpuError> {
    let mut encoder =
        context.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd frame") });
    let start = Instant::now();
    rig.pose_into(keys, posed)?;
    deformer.set_pose(0, posed)?;
    deformer.encode(&mut encoder);
    let seconds = start.elapsed().as_secs_f64();
    context.queue.submit([encoder.finish()]);
    Ok(seconds)
}

/// The median of [`host_frame_seconds`] over `frames` frames after [`FRAME_WARMUP`], in
/// milliseconds.
pub fn median_host_frame_ms(
    context: &GpuContext,
    deformer: &mut GpuDeformer,
    rig: &Rig,
    keys: &[Vec<Key>],
    frames: usize,
) -> Result<f64, GpuError> {
    let mut posed = rig.pose_buffer();
    let mut samples = Vec::with_capacity(frames);
    for frame in 0..FRAME_WARMUP + frames {
        let seconds = host_frame_seconds(context, deformer, rig, keys, &mut posed)?;
        if frame >= FRAME_WARMUP {
            samples.push(seconds);
        }
        if frame % FRAMES_PER_WAIT == FRAMES_PER_WAIT - 1 {
            wait(context)?;
        }
    }
    wait(context)?;
    Ok(median(&mut samples) * 1e3)
}

/// A deformer of a scene, with normals, timed frame by frame on the host (the criterion
/// bench's `frame_cpu`).
pub struct FrameBench {
    context: GpuContext,
    scene: BenchScene,
    deformer: GpuDeformer,
    posed: PoseBuffer,
}

impl FrameBench {
    /// The engine-shaped scene of the target: a closed tube of about `vertices` vertices (36k
    /// for the target of 0.1 ms) bound to two 4-key sweeps of 16 radii meeting at its middle,
    /// no falloff.
    pub fn two_sweep_tube(vertices: usize) -> BenchScene {
        let tube = Tube::with_vertex_count(vertices.max(super::MIN_BENCH_VERTICES), 4.0, 0.5);
        BenchScene::new(tube.mesh(), split_tube_rig(&tube, 4, 16, 0.0), "tube").expect("the split rig owns the tube")
    }

    /// Uploads and binds `scene` (with its falloff bands, if any).
    pub fn new(context: &GpuContext, scene: BenchScene) -> Result<FrameBench, GpuError> {
        let bands = scene.rig.band_weights(&scene.mesh, &scene.owners);
        let source = BindingSource::Bind { owners: &scene.owners, bands: &bands };
        let positions = crate::gpu::rest_positions(&scene.mesh.positions);
        let triangles: Vec<u32> = scene.mesh.faces.triangles().flatten().collect();
        let descriptor = DeformerDescriptor::new(scene.rig.rest(), &positions, source).with_triangles(&triangles);
        let deformer = GpuDeformer::new(context, &descriptor)?;
        let posed = scene.rig.pose_buffer();
        Ok(FrameBench { context: context.clone(), scene, deformer, posed })
    }

    /// The deformer.
    pub fn deformer(&self) -> &GpuDeformer {
        &self.deformer
    }

    /// Host seconds of one frame ([`host_frame_seconds`]); waits for the GPU every few frames.
    pub fn time_frame(&mut self, frame: u64) -> Result<f64, GpuError> {
        let scene = &self.scene;
        let seconds = host_frame_seconds(&self.context, &mut self.deformer, &scene.rig, &scene.keys, &mut self.posed)?;
        if frame % FRAMES_PER_WAIT as u64 == FRAMES_PER_WAIT as u64 - 1 {
            wait(&self.context)?;
        }
        Ok(seconds)
    }

    /// The same frame with the posed sweeps made anew by [`Rig::pose`] instead of
    /// [`Rig::pose_into`]: the baseline of the saving.
    pub fn time_frame_posing_anew(&mut self, frame: u64) -> Result<f64, GpuError> {
        let mut encoder = self
            .context
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd frame") });
        let start = Instant::now();
        let posed = self.scene.rig.pose(&self.scene.keys)?;
        self.deformer.set_pose(0, &posed)?;
        self.deformer.encode(&mut encoder);
        let seconds = start.elapsed().as_secs_f64();
        self.context.queue.submit([encoder.finish()]);
        if frame % FRAMES_PER_WAIT as u64 == FRAMES_PER_WAIT as u64 - 1 {
            wait(&self.context)?;
        }
        Ok(seconds)
    }

    /// [`median_host_frame_ms`] of the scene.
    pub fn median_ms(&mut self, frames: usize) -> Result<f64, GpuError> {
        let scene = &self.scene;
        median_host_frame_ms(&self.context, &mut self.deformer, &scene.rig, &scene.keys, frames)
    }
}
