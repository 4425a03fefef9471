//! The documented frame loop allocates nothing in sweepffd's code: `rig.pose_into(..)`, then
//! `deformer.set_pose(..)`, then `deformer.encode(..)`, counted by a global allocator that
//! counts the allocations (and reallocations) of the test's own thread while a flag is set.
//!
//! What is counted, honestly:
//!
//! - [`Rig::pose_into`] and [`SweepCoefficients::update`] alone: must be 0.
//! - `set_pose` is `update` plus a copy into the deformer's host image of every instance's
//!   cell records: must be 0.
//! - `encode` uploads that image through a mapped staging buffer (a copy into its mapped range,
//!   `unmap`, `copy_buffer_to_buffer` and `map_buffer_on_submit`) and records compute passes,
//!   and wgpu allocates for all of these (mapping state, the callback, command lists,
//!   trackers); it is compared against a baseline making, on a fresh encoder of the same
//!   device, the same upload calls for as many bytes and the same number of compute passes
//!   with the same number of `set_bind_group` and dispatch calls (the deformer's deform and
//!   normals dispatches; no falloff bands), binding as many buffers as the deform kernel: no
//!   more than that. A plain `write_buffer` of the bytes is counted too, for the printout.
//!
//! Encoders are created, finished and submitted outside the counted regions, and each frame
//! waits for the last, outside them too (so that the staging buffers are mapped again, as in a
//! frame loop with a frame in flight, where the deformer's two staging buffers take turns);
//! ours and the baseline take turns going first. The frame count is even. Allocations on
//! wgpu's or the driver's own threads are not counted (the counter is per thread).

use crate::common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use sweepffd::coeffs::SweepCoefficients;
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, rest_positions};
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;
use sweepffd::synthetic::{BendTwistTaper, Tube, split_tube_rig};

struct Counting;

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<u64> = const { Cell::new(0) };
}

fn note() {
    // `try_with`: the thread-locals may be gone while a thread shuts down.
    let _ = COUNTING.try_with(|on| {
        if on.get() {
            let _ = COUNT.try_with(|count| count.set(count.get() + 1));
        }
    });
}

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The allocations `work` makes on this thread, and its result.
fn allocations<T>(work: impl FnOnce() -> T) -> (u64, T) {
    COUNT.with(|count| count.set(0));
    COUNTING.with(|on| on.set(true));
    let result = work();
    COUNTING.with(|on| on.set(false));
    (COUNT.with(Cell::get), result)
}

/// The two-sweep tube of the bench, small, and the keys of a few frames of posing it.
fn scene() -> (sweepffd::mesh::Mesh, Rig, Vec<Vec<Vec<Key>>>) {
    let tube = Tube::with_vertex_count(4_000, 4.0, 0.5);
    let rig = split_tube_rig(&tube, 4, 16, 0.0);
    let frames = (0..6)
        .map(|f| {
            BendTwistTaper { bend: 0.2 * f as f64, twist: 0.1 * f as f64, taper: 1.0 - 0.05 * f as f64 }.keys(&rig)
        })
        .collect();
    (tube.mesh(), rig, frames)
}

#[test]
fn posing_and_coefficients_allocate_nothing() {
    let (_, rig, frames) = scene();
    let mut posed = rig.pose_buffer();
    let mut coefficients = SweepCoefficients::new(rig.rest());
    for keys in &frames {
        let (count, result) = allocations(|| rig.pose_into(keys, &mut posed));
        result.unwrap();
        assert_eq!(count, 0, "pose_into allocated");
        let (count, result) = allocations(|| coefficients.update(&posed));
        result.unwrap();
        assert_eq!(count, 0, "SweepCoefficients::update allocated");
    }
    let (count, posed) = allocations(|| rig.pose(&frames[1]).unwrap());
    println!("for comparison, Rig::pose allocates {count} times a frame ({} sweeps)", posed.len());
}

/// The baseline of `encode`: `passes` compute passes of one bound group and one dispatch each,
/// recorded with plain wgpu calls.
struct Baseline {
    pipeline: wgpu::ComputePipeline,
    group: wgpu::BindGroup,
    scratch: wgpu::Buffer,
    staging: wgpu::Buffer,
    mapped: Arc<AtomicBool>,
}

impl Baseline {
    /// A trivial kernel reading as many storage buffers as the deform kernel binds; the last,
    /// `scratch_bytes` long, stands in for the cell records in the `write_buffer` baseline.
    fn new(device: &wgpu::Device, scratch_bytes: u64) -> Baseline {
        let source = "@group(0) @binding(0) var<uniform> n: vec4<u32>;
            @group(0) @binding(1) var<storage, read> a: array<u32>;
            @group(0) @binding(2) var<storage, read> b: array<u32>;
            @group(0) @binding(3) var<storage, read_write> c: array<u32>;
            @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {
                if (id.x >= n.x) { return; }
                c[id.x] = a[id.x] + b[id.x];
            }";
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("baseline"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("baseline"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let buffer = |size, usage| {
            device.create_buffer(&wgpu::BufferDescriptor { label: None, size, usage, mapped_at_creation: false })
        };
        let uniform = buffer(256, wgpu::BufferUsages::UNIFORM);
        let storage = [256, 256, scratch_bytes]
            .map(|size| buffer(size, wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST));
        let entries: Vec<wgpu::BindGroupEntry> = std::iter::once(&uniform)
            .chain(&storage)
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
            .collect();
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let [_, _, scratch] = storage;
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: scratch_bytes,
            usage: wgpu::BufferUsages::MAP_WRITE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: true,
        });
        Baseline { pipeline, group, scratch, staging, mapped: Arc::new(AtomicBool::new(true)) }
    }

    /// The deformer's upload: through the mapped staging buffer, mapped again on submit.
    fn upload(&self, encoder: &mut wgpu::CommandEncoder, bytes: &[u8]) {
        self.staging.slice(..).get_mapped_range_mut().unwrap().copy_from_slice(bytes);
        self.staging.unmap();
        encoder.copy_buffer_to_buffer(&self.staging, 0, &self.scratch, 0, bytes.len() as u64);
        self.mapped.store(false, Ordering::Release);
        let mapped = Arc::clone(&self.mapped);
        encoder.map_buffer_on_submit(&self.staging, wgpu::MapMode::Write, .., move |result| {
            mapped.store(result.is_ok(), Ordering::Release);
        });
    }

    /// One pass per `(label, dispatches)`, each dispatch after its own `set_bind_group`.
    fn encode(&self, encoder: &mut wgpu::CommandEncoder, passes: &[(&str, usize)]) {
        for &(label, dispatches) in passes {
            let mut pass =
                encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes: None });
            pass.set_pipeline(&self.pipeline);
            for _ in 0..dispatches {
                pass.set_bind_group(0, &self.group, &[]);
                pass.dispatch_workgroups(1, 1, 1);
            }
        }
    }
}

fn frames_on(context: &GpuContext) {
    let (mesh, rig, frames) = scene();
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bindings = BindingSource::Bind { owners: &owners, bands: &[] };
    let (positions, triangles) =
        (rest_positions(&mesh.positions), mesh.faces.triangles().flatten().collect::<Vec<u32>>());
    let descriptor = DeformerDescriptor::new(rig.rest(), &positions, bindings).with_triangles(&triangles);
    let mut deformer = GpuDeformer::new(context, &descriptor).unwrap();
    assert_eq!(deformer.band_vertex_count(), 0, "the baseline records no band dispatch");
    let passes = [("sweepffd deform", deformer.chunk_count()), ("sweepffd normals", deformer.normals_dispatch_count())];
    let cell_bytes =
        vec![0u8; SweepCoefficients::new(rig.rest()).cells.len() * size_of::<sweepffd::coeffs::CellCoeffs>()];
    let baseline = Baseline::new(&context.device, cell_bytes.len() as u64);
    let mut posed = rig.pose_buffer();
    let new_encoder = || context.device.create_command_encoder(&Default::default());
    let (mut ours, mut theirs) = ([0u64; 3], [0u64; 2]);
    // Two rounds: the first warms wgpu's caches up and is not compared.
    for round in 0..2 {
        let (mut set_pose, mut write, mut encode, mut plain_passes) = (0, 0, 0, 0);
        for (frame, keys) in frames.iter().enumerate() {
            let (count, result) = allocations(|| rig.pose_into(keys, &mut posed));
            result.unwrap();
            ours[0] += count;
            // The first write after a submit pays for wgpu's new pending-writes list: take turns.
            for turn in [frame % 2, 1 - frame % 2] {
                if turn == 0 {
                    let (count, result) = allocations(|| deformer.set_pose(0, &posed));
                    result.unwrap();
                    set_pose += count;
                } else {
                    let (count, ()) = allocations(|| context.queue.write_buffer(&baseline.scratch, 0, &cell_bytes));
                    write += count;
                }
            }
            let mut encoder = new_encoder();
            let mut plain = new_encoder();
            for turn in [frame % 2, 1 - frame % 2] {
                if turn == 0 {
                    let (count, ()) = allocations(|| deformer.encode(&mut encoder));
                    encode += count;
                } else {
                    // encode uploads the cell records through a staging buffer, then records.
                    let (count, ()) = allocations(|| {
                        baseline.upload(&mut plain, &cell_bytes);
                        baseline.encode(&mut plain, &passes)
                    });
                    plain_passes += count;
                }
            }
            context.queue.submit([encoder.finish(), plain.finish()]);
            context.device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
        }
        if round == 1 {
            ours[1..].copy_from_slice(&[set_pose, encode]);
            theirs = [write, plain_passes];
        }
    }
    let n = frames.len() as u64;
    println!(
        "allocations in {n} frames: pose_into {}, set_pose {} (plain write_buffer {}), encode {} (plain upload and passes {})",
        ours[0], ours[1], theirs[0], ours[2], theirs[1]
    );
    assert_eq!(ours[0], 0, "pose_into allocated");
    assert_eq!(ours[1], 0, "set_pose (a copy into the host image of the poses) allocated");
    assert!(ours[2] <= theirs[1], "encode allocated {} times, the plain passes {}", ours[2], theirs[1]);
}

#[test]
fn a_frame_allocates_no_more_than_the_wgpu_calls_it_makes() {
    let Some(context) = common::gpu() else { return };
    frames_on(context);
}
