//! Instances: one bound mesh, many poses, one deform dispatch. Each instance's positions equal
//! the f32 twin's (`src/cpu/deform.rs`) for that instance's pose within the tolerance of
//! `tests/gpu_equivalence.rs`, and, bit for bit, a one-instance deformer's; several poses in one
//! command buffer each land; the previous positions are last frame's output, bit for bit.

use crate::common;

use common::app_buffer::{app_buffer, assert_untouched_around};
use sweepffd::coeffs::SweepCoefficients;
use sweepffd::cpu;
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, read_bytes};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Sweep;
use sweepffd::synthetic::{BendTwistTaper, Tube, attached_tube_rig, tube_rig};

/// As `tests/gpu_equivalence.rs`: positions within this share of the bounding-box diagonal.
const POSITION_TOLERANCE: f64 = 1e-5;

/// Pose `i` of `n`: bend, twist and taper each different.
fn pose(rig: &Rig, i: usize, n: usize) -> Vec<Sweep> {
    let f = i as f64 / n as f64;
    let keys = BendTwistTaper { bend: 2.0 * f - 1.0, twist: 3.0 * f, taper: 0.5 + f }.keys(rig);
    rig.pose(&keys).unwrap()
}

fn descriptor<'a>(rig: &'a Rig, positions: &'a [[f32; 3]], owners: &'a [u32]) -> DeformerDescriptor<'a> {
    DeformerDescriptor::new(rig.rest(), positions, BindingSource::Bind { owners, bands: &[] })
}

/// Every instance's latest positions, read back in one copy.
fn read_all(context: &GpuContext, deformer: &GpuDeformer, buffer: &wgpu::Buffer) -> Vec<Vec<f32>> {
    let n = deformer.instance_count();
    let size = deformer.instance_offset(n - 1) + deformer.vertex_count() as u64 * 12;
    let all: Vec<f32> = bytemuck::pod_collect_to_vec(&read_bytes(context, buffer, 0, size).unwrap());
    (0..n)
        .map(|i| {
            let at = (deformer.instance_offset(i) / 4) as usize;
            all[at..at + 3 * deformer.vertex_count() as usize].to_vec()
        })
        .collect()
}

fn encode_and_submit(context: &GpuContext, deformer: &mut GpuDeformer) {
    let mut encoder = context.device.create_command_encoder(&Default::default());
    deformer.encode(&mut encoder);
    context.queue.submit([encoder.finish()]);
}

#[test]
fn a_thousand_instances_of_a_10k_mesh_match_the_twin_pose_by_pose() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(10_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let n = 1000;
    let mut deformer = GpuDeformer::new(context, &descriptor(&rig, &positions, &owners).with_instances(n)).unwrap();
    let poses: Vec<Vec<Sweep>> = (0..n as usize).map(|i| pose(&rig, i, n as usize)).collect();
    for (i, posed) in poses.iter().enumerate() {
        deformer.set_pose(i as u32, posed).unwrap();
    }
    encode_and_submit(context, &mut deformer);
    let gpu = read_all(context, &deformer, deformer.positions());
    let bindings = deformer.read_bindings().unwrap();
    let diagonal = mesh.diagonal();
    let mut coefficients = SweepCoefficients::new(rig.rest());
    let (mut worst, mut worst_ulps, mut worst_at) = (0.0f32, 0, (0, 0));
    for (i, posed) in poses.iter().enumerate() {
        coefficients.update(posed).unwrap();
        let mut twin = cpu::packed(&mesh.positions);
        cpu::deform::deform(&coefficients.cells, &bindings, &mut twin);
        let (error, ulps, at) = common::worst_f32(&gpu[i], &twin);
        worst_ulps = worst_ulps.max(ulps);
        if error > worst {
            (worst, worst_at) = (error, (i, at / 3));
        }
    }
    println!(
        "1000 instances × 10k vertices: max |Δ| {worst:.3e} ({:.2e} × diagonal), max {worst_ulps} ULP, worst instance {} vertex {}",
        worst as f64 / diagonal,
        worst_at.0,
        worst_at.1
    );
    assert!(
        worst as f64 <= POSITION_TOLERANCE * diagonal,
        "max |Δposition| {worst:e} at instance {} vertex {}",
        worst_at.0,
        worst_at.1
    );
    // The instances really differ: the first and last poses move a vertex differently.
    assert_ne!(gpu[0], gpu[n as usize - 1]);
}

/// Each instance of an `n`-instance deformer equals, bit for bit, a one-instance deformer posed
/// the same, with falloff bands (the band kernel per instance) and normals.
fn instances_equal_single_deformers(n: u32, mesh: &Mesh, rig: &Rig) {
    let Some(context) = common::gpu() else { return };
    let owners = rig.owners(mesh, "tube").unwrap();
    let bands = rig.band_weights(mesh, &owners);
    assert!(!bands.is_empty(), "the rig has falloff bands");
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let base = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &bands })
        .with_triangles(&triangles);
    let mut many = GpuDeformer::new(context, &base.with_instances(n)).unwrap();
    let mut one = GpuDeformer::new(context, &base).unwrap();
    for i in 0..n {
        many.set_pose(i, &pose(rig, i as usize, n as usize)).unwrap();
    }
    encode_and_submit(context, &mut many);
    for i in 0..n {
        one.deform(&pose(rig, i as usize, n as usize)).unwrap();
        let positions = many.read_instance_positions(i).unwrap();
        assert!(positions == one.read_positions().unwrap(), "{n} instances: instance {i}'s positions");
        let normals = many.read_instance_normals(i).unwrap();
        assert!(normals == one.read_normals().unwrap(), "{n} instances: instance {i}'s normals");
    }
}

#[test]
fn few_instances_with_falloff_bands_in_the_uniform_variant_equal_single_deformers_bit_for_bit() {
    // 7 knot intervals × 8 samples × 5 instances = 280 cells: the uniform variant.
    let tube = Tube::with_vertex_count(3_000, 4.0, 0.5);
    instances_equal_single_deformers(5, &tube.mesh(), &attached_tube_rig(&tube, 8, 8, 0.6));
}

#[test]
fn many_instances_with_falloff_bands_in_the_storage_variant_equal_single_deformers_bit_for_bit() {
    // 7 × 16 × 40 = 4,480 cells: past the uniform variant's 409.
    let tube = Tube::with_vertex_count(3_000, 4.0, 0.5);
    instances_equal_single_deformers(40, &tube.mesh(), &attached_tube_rig(&tube, 8, 16, 0.6));
}

/// The instanced deform kernel numbers its invocations flat over instances × vertices, so one
/// workgroup of 128 spans several instances of a small mesh (here 18 vertices: up to 9) or
/// the end of one and the start of the next (here 130 vertices); every instance still equals,
/// bit for bit, a one-instance deformer posed the same.
#[test]
fn instances_numbered_flat_across_workgroups_equal_single_deformers_bit_for_bit() {
    let Some(context) = common::gpu() else { return };
    for (around, n) in [(8, 37), (64, 11)] {
        let tube = Tube { rings: 2, around, length: 1.0, radius: 0.3 };
        let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 4, 8));
        let owners = rig.owners(&mesh, "tube").unwrap();
        let positions = sweepffd::gpu::rest_positions(&mesh.positions);
        let base = descriptor(&rig, &positions, &owners);
        let mut many = GpuDeformer::new(context, &base.with_instances(n)).unwrap();
        let mut one = GpuDeformer::new(context, &base).unwrap();
        for i in 0..n {
            many.set_pose(i, &pose(&rig, i as usize, n as usize)).unwrap();
        }
        encode_and_submit(context, &mut many);
        let all = read_all(context, &many, many.positions());
        for i in 0..n {
            one.deform(&pose(&rig, i as usize, n as usize)).unwrap();
            let vertices = mesh.positions.len();
            assert!(all[i as usize] == one.read_positions().unwrap(), "{vertices} vertices × {n}: instance {i}");
        }
        assert_ne!(all[0], all[n as usize - 1], "the poses move the vertices differently");
    }
}

#[test]
fn a_pose_for_an_instance_that_does_not_exist_is_refused() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(1_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 4, 8));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let mut deformer = GpuDeformer::new(context, &descriptor(&rig, &positions, &owners).with_instances(3)).unwrap();
    assert!(deformer.set_pose(2, &pose(&rig, 1, 2)).is_ok());
    let error = deformer.set_pose(3, &pose(&rig, 1, 2)).unwrap_err();
    assert!(error.to_string().contains("instance 3"), "{error}");
    let error = GpuDeformer::new(context, &descriptor(&rig, &positions, &owners).with_instances(0)).unwrap_err();
    assert!(error.to_string().contains("at least one"), "{error}");
}

#[test]
fn every_pose_encoded_into_one_command_buffer_lands() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(2_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 6, 8));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    // Five poses, more than the two staging buffers a deformer starts with.
    let poses: Vec<Vec<Sweep>> = (0..5).map(|i| pose(&rig, i, 4)).collect();
    let mut reference = GpuDeformer::new(context, &descriptor(&rig, &positions, &owners)).unwrap();
    let expected: Vec<Vec<f32>> = poses
        .iter()
        .map(|posed| {
            reference.deform(posed).unwrap();
            reference.read_positions().unwrap()
        })
        .collect();
    assert!(expected.windows(2).all(|pair| pair[0] != pair[1]), "the poses differ");

    let mut deformer = GpuDeformer::new(context, &descriptor(&rig, &positions, &owners)).unwrap();
    assert_eq!(deformer.pose_uploads(), 2);
    let size = deformer.vertex_count() as u64 * 12;
    let copies: Vec<wgpu::Buffer> = (0..poses.len())
        .map(|_| {
            context.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("one pose's positions"),
                size,
                usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        })
        .collect();
    let read = |buffer| -> Vec<f32> { bytemuck::pod_collect_to_vec(&read_bytes(context, buffer, 0, size).unwrap()) };
    // Twice: the second command buffer reuses the staging buffers the first one made.
    for round in 0..2 {
        let mut encoder = context.device.create_command_encoder(&Default::default());
        for (posed, copy) in poses.iter().zip(&copies) {
            deformer.set_pose(0, posed).unwrap();
            deformer.encode(&mut encoder);
            encoder.copy_buffer_to_buffer(deformer.positions(), 0, copy, 0, size);
        }
        context.queue.submit([encoder.finish()]);
        for (i, (copy, expected)) in copies.iter().zip(&expected).enumerate() {
            assert!(read(copy) == *expected, "round {round}: encode {i} saw another pose than its own");
        }
        assert_eq!(deformer.pose_uploads(), poses.len(), "round {round}: one staging buffer per encode in flight");
    }
}

#[test]
fn previous_positions_are_last_frames_output_bit_for_bit() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(2_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), attached_tube_rig(&tube, 6, 8, 0.0));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let descriptor = descriptor(&rig, &positions, &owners).with_instances(3).with_previous_positions();
    let mut deformer = GpuDeformer::new(context, &descriptor).unwrap();
    let rest: Vec<f32> = positions.iter().flatten().copied().collect();
    for i in 0..3 {
        assert!(deformer.read_previous_positions(i).unwrap().unwrap() == rest, "before any frame");
    }
    let mut last: Vec<Vec<f32>> = (0..3).map(|_| rest.clone()).collect();
    for frame in 0..4 {
        for i in 0..3 {
            deformer.set_pose(i, &pose(&rig, frame + i as usize, 7)).unwrap();
        }
        encode_and_submit(context, &mut deformer);
        for i in 0..3 {
            let previous = deformer.read_previous_positions(i).unwrap().unwrap();
            assert!(previous == last[i as usize], "frame {frame}, instance {i}: previous is not last frame's");
            let current = deformer.read_instance_positions(i).unwrap();
            assert_ne!(current, previous, "frame {frame}, instance {i}: the pose moved nothing");
            // The unbound first ring keeps its rest position in both buffers.
            assert_eq!(current[..3 * tube.around as usize], rest[..3 * tube.around as usize]);
            last[i as usize] = current;
        }
    }
    assert!(deformer.previous_positions().is_some());
    assert!(GpuDeformer::new(context, &descriptor.with_instances(1)).unwrap().previous_positions().is_some());
}

#[test]
fn previous_positions_in_two_app_buffers_equal_the_deformers_own_bit_for_bit() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(2_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), attached_tube_rig(&tube, 6, 8, 0.0));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let base = descriptor(&rig, &positions, &owners).with_instances(2).with_triangles(&triangles);
    let mut own = GpuDeformer::new(context, &base.with_previous_positions()).unwrap();
    let offset = 256 * context.device.limits().min_storage_buffer_offset_alignment as u64;
    let bytes = own.instance_offset(1) + own.vertex_count() as u64 * 12;
    let (first, second) = (app_buffer(context, offset, bytes), app_buffer(context, offset, bytes));
    let mut supplied = GpuDeformer::new(context, &base.with_outputs(&first, &second, offset)).unwrap();
    assert_eq!(supplied.positions(), &first, "the first buffer holds the rest positions before any encode");
    assert_eq!(supplied.previous_positions(), Some(&second));
    for frame in 0..3 {
        for deformer in [&mut own, &mut supplied] {
            for i in 0..2 {
                deformer.set_pose(i, &pose(&rig, frame + i as usize, 5)).unwrap();
            }
            encode_and_submit(context, deformer);
        }
        let (latest, other) = if frame % 2 == 0 { (&second, &first) } else { (&first, &second) };
        assert_eq!(supplied.positions(), latest, "frame {frame}: the encodes alternate between the app's buffers");
        assert_eq!(supplied.previous_positions(), Some(other), "frame {frame}");
        for i in 0..2 {
            let (mine, theirs) =
                (supplied.read_instance_positions(i).unwrap(), own.read_instance_positions(i).unwrap());
            assert!(mine == theirs, "frame {frame}, instance {i}: positions");
            let previous = (supplied.read_previous_positions(i).unwrap(), own.read_previous_positions(i).unwrap());
            assert!(previous.0 == previous.1, "frame {frame}, instance {i}: previous positions");
            assert!(supplied.read_instance_normals(i).unwrap() == own.read_instance_normals(i).unwrap(), "normals {i}");
        }
    }
    for buffer in [&first, &second] {
        assert_untouched_around(context, buffer, offset, bytes);
    }
    let one_buffer = base.with_output(&first, offset).with_previous_positions();
    let error = GpuDeformer::new(context, &one_buffer).unwrap_err().to_string();
    assert!(error.contains("two buffers (with_outputs)"), "{error}");
    let same = base.with_outputs(&first, &first, offset);
    assert!(GpuDeformer::new(context, &same).unwrap_err().to_string().contains("must differ"));
    let small = app_buffer(context, offset, bytes - 128);
    let too_small = base.with_outputs(&first, &small, offset);
    assert!(GpuDeformer::new(context, &too_small).unwrap_err().to_string().contains("bytes"));
}
