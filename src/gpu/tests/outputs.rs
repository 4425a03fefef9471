//! What the deformer hands the application besides positions: per-instance bounds computed on
//! the GPU, equal to the CPU min and max of the read-back positions exactly.

use crate::common;

use common::app_buffer::{app_buffer, assert_untouched_around};
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuDeformer};
use sweepffd::synthetic::{BendTwistTaper, Tube, attached_tube_rig};

#[test]
fn per_instance_bounds_equal_the_cpu_extremes_of_the_read_back_positions_exactly() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(5_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), attached_tube_rig(&tube, 8, 16, 0.6));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bands = rig.band_weights(&mesh, &owners);
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let n = 30;
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &bands })
            .with_instances(n)
            .with_bounds()
            .with_previous_positions();
    let mut deformer = GpuDeformer::new(context, &descriptor).unwrap();
    for frame in 0..2 {
        for i in 0..n {
            let f = (i + frame * n) as f64 / (2 * n) as f64;
            let keys = BendTwistTaper { bend: 3.0 * f - 1.5, twist: 2.0 * f, taper: 0.4 + 1.2 * f }.keys(&rig);
            deformer.set_pose(i, &rig.pose(&keys).unwrap()).unwrap();
        }
        let mut encoder = context.device.create_command_encoder(&Default::default());
        deformer.encode(&mut encoder);
        context.queue.submit([encoder.finish()]);
        let bounds = deformer.read_bounds().unwrap().expect("asked for bounds");
        assert_eq!(bounds.len(), n as usize);
        for i in 0..n {
            let p = deformer.read_instance_positions(i).unwrap();
            let mut expected = [
                f32::INFINITY,
                f32::INFINITY,
                f32::INFINITY,
                0.0,
                f32::NEG_INFINITY,
                f32::NEG_INFINITY,
                f32::NEG_INFINITY,
                0.0,
            ];
            for v in p.chunks_exact(3) {
                for c in 0..3 {
                    expected[c] = expected[c].min(v[c]);
                    expected[4 + c] = expected[4 + c].max(v[c]);
                }
            }
            assert_eq!(bounds[i as usize], expected, "frame {frame}, instance {i}");
        }
        assert_ne!(bounds[0], bounds[n as usize - 1], "frame {frame}: the instances' bounds differ");
    }
}

fn tube_deformer_inputs() -> (Tube, sweepffd::mesh::Mesh, sweepffd::rig::Rig) {
    let tube = Tube::with_vertex_count(3_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), attached_tube_rig(&tube, 6, 8, 0.5));
    (tube, mesh, rig)
}

fn posed(rig: &sweepffd::rig::Rig, i: u32) -> Vec<sweepffd::sweep::Sweep> {
    let keys = BendTwistTaper { bend: 0.4 * i as f64, twist: 0.3, taper: 0.8 }.keys(rig);
    rig.pose(&keys).unwrap()
}

#[test]
fn positions_written_into_an_app_buffer_at_an_offset_equal_the_deformers_own_bit_for_bit() {
    let Some(context) = common::gpu() else { return };
    let (_, mesh, rig) = tube_deformer_inputs();
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bands = rig.band_weights(&mesh, &owners);
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let n = 3;
    let base = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &bands })
        .with_triangles(&triangles)
        .with_instances(n)
        .with_bounds();
    let mut own = GpuDeformer::new(context, &base).unwrap();
    let offset = 3 * context.device.limits().min_storage_buffer_offset_alignment as u64;
    let bytes = own.instance_offset(n - 1) + own.vertex_count() as u64 * 12;
    let app = app_buffer(context, offset, bytes);
    let mut supplied = GpuDeformer::new(context, &base.with_output(&app, offset)).unwrap();
    assert_eq!(supplied.positions(), &app);
    for deformer in [&mut own, &mut supplied] {
        for i in 0..n {
            deformer.set_pose(i, &posed(&rig, i)).unwrap();
        }
        let mut encoder = context.device.create_command_encoder(&Default::default());
        deformer.encode(&mut encoder);
        context.queue.submit([encoder.finish()]);
    }
    for i in 0..n {
        assert!(
            supplied.read_instance_positions(i).unwrap() == own.read_instance_positions(i).unwrap(),
            "instance {i}"
        );
        assert!(supplied.read_instance_normals(i).unwrap() == own.read_instance_normals(i).unwrap(), "normals {i}");
    }
    assert_eq!(supplied.read_bounds().unwrap(), own.read_bounds().unwrap());
    assert_untouched_around(context, &app, offset, bytes);
    let misaligned = base.with_output(&app, offset + 4);
    assert!(GpuDeformer::new(context, &misaligned).unwrap_err().to_string().contains("alignment"));
    let too_small = base.with_instances(n + 1).with_output(&app, offset);
    assert!(GpuDeformer::new(context, &too_small).unwrap_err().to_string().contains("bytes"));
}

#[test]
fn a_device_with_only_the_required_limits_runs_the_deformer() {
    let Some(context) = common::gpu() else { return };
    let limits = GpuDeformer::required_limits();
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default())).unwrap();
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("required limits"),
        required_features: wgpu::Features::empty(),
        required_limits: limits.clone(),
        experimental_features: wgpu::ExperimentalFeatures::disabled(),
        memory_hints: wgpu::MemoryHints::Performance,
        trace: wgpu::Trace::Off,
    }))
    .unwrap();
    let small = sweepffd::gpu::GpuContext::from_device(device, queue, adapter.get_info());
    let (_, mesh, rig) = tube_deformer_inputs();
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bands = rig.band_weights(&mesh, &owners);
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &bands })
            .with_instances(4)
            .with_bounds();
    let mut on_small = GpuDeformer::new(&small, &descriptor).unwrap();
    let mut on_full = GpuDeformer::new(context, &descriptor).unwrap();
    for deformer in [&mut on_small, &mut on_full] {
        for i in 0..4 {
            deformer.set_pose(i, &posed(&rig, i)).unwrap();
        }
        let context = deformer.context().clone();
        let mut encoder = context.device.create_command_encoder(&Default::default());
        deformer.encode(&mut encoder);
        context.queue.submit([encoder.finish()]);
    }
    let diagonal = mesh.diagonal() as f32;
    for i in 0..4 {
        let (a, b) = (on_small.read_instance_positions(i).unwrap(), on_full.read_instance_positions(i).unwrap());
        let (error, ulps, at) = common::worst_f32(&a, &b);
        assert!(error <= 1e-5 * diagonal, "instance {i}: {error:e} ({ulps} ULP) at vertex {}", at / 3);
    }
}

/// A rig of one sweep owning only the rings `rings` of `tube` (circular keys over them), with
/// falloff `falloff` into the rest of the mesh.
fn partial_tube_rig(tube: &Tube, rings: std::ops::Range<u32>, falloff: f64) -> sweepffd::rig::Rig {
    let step = tube.length / (tube.rings - 1) as f64;
    let owned: Vec<u32> = (rings.start * tube.around..rings.end * tube.around).collect();
    let z = (rings.start as f64 * step, (rings.end - 1) as f64 * step);
    sweepffd::rig::Rig::new(vec![sweepffd::synthetic::straight_sweep(tube, owned, z, 5, 8, falloff)]).unwrap()
}

#[test]
fn dispatching_only_the_bound_ranges_gives_the_full_dispatchs_positions_normals_and_bounds_bit_for_bit() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(40_000, 4.0, 0.5);
    let mesh = tube.mesh();
    let middle = tube.rings / 2;
    let rig = partial_tube_rig(&tube, middle..middle + tube.rings * 3 / 100, 0.02);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let bands = rig.band_weights(&mesh, &owners);
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let n = 3;
    let base = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &bands })
        .with_triangles(&triangles)
        .with_instances(n)
        .with_bounds();
    let mut partial = GpuDeformer::new(context, &base).unwrap();
    let mut full = GpuDeformer::new(context, &base.with_full_dispatch()).unwrap();
    let covered = partial.dispatched_vertex_count();
    println!("bound ranges cover {covered} of {} vertices ({} bands)", mesh.positions.len(), bands.len());
    assert!((covered as usize) < mesh.positions.len() / 10, "{covered} vertices dispatched");
    assert_eq!(full.dispatched_vertex_count() as usize, mesh.positions.len());
    assert_eq!(partial.read_bindings().unwrap(), full.read_bindings().unwrap());
    for frame in 0..2 {
        for deformer in [&mut partial, &mut full] {
            for i in 0..n {
                deformer.set_pose(i, &posed(&rig, i + frame)).unwrap();
            }
            let mut encoder = context.device.create_command_encoder(&Default::default());
            deformer.encode(&mut encoder);
            context.queue.submit([encoder.finish()]);
        }
        for i in 0..n {
            let p = partial.read_instance_positions(i).unwrap();
            assert!(p == full.read_instance_positions(i).unwrap(), "frame {frame} instance {i}: positions");
            assert_ne!(p, positions.iter().flatten().copied().collect::<Vec<f32>>(), "the pose moved nothing");
            let normals = partial.read_instance_normals(i).unwrap();
            assert!(normals == full.read_instance_normals(i).unwrap(), "frame {frame} instance {i}: normals");
        }
        assert_eq!(partial.read_bounds().unwrap(), full.read_bounds().unwrap(), "frame {frame}: bounds");
    }
}
