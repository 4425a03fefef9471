//! A device whose storage bindings hold 160 KiB: a 20k-vertex tube's bindings, normal
//! coordinates and probe windows then split into several chunks, and its positions are read
//! through two windows. The Jacobian probe, the fused kernel and the staged stores give there
//! what they give on the adapter's own limits, bit for bit.

use crate::common;

use sweepffd::gpu::{BindingSource, DeformOrder, DeformerDescriptor, GpuContext, GpuDeformer, rest_positions};
use sweepffd::rig::BendTwistTaper;
use sweepffd::synthetic::{Tube, tube_rig};

/// Bytes of the small device's largest storage binding.
const SMALL_BINDING: u32 = 160 << 10;

/// A device on `context`'s adapter whose storage bindings hold [`SMALL_BINDING`] bytes.
fn small_device(context: &GpuContext) -> GpuContext {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()))
        .into_iter()
        .find(|adapter| adapter.get_info() == context.info)
        .expect("the context's adapter");
    let limits = wgpu::Limits { max_storage_buffer_binding_size: SMALL_BINDING as u64, ..adapter.limits() };
    let (device, queue) = pollster::block_on(
        adapter.request_device(&wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() }),
    )
    .unwrap();
    GpuContext::from_device(device, queue, adapter.get_info())
}

#[test]
fn chunked_probe_fused_normals_and_staged_stores_match_one_chunk() {
    let Some(context) = common::gpu() else { return };
    let small = small_device(context);
    assert_eq!(small.device.limits().max_storage_buffer_binding_size, SMALL_BINDING as u64);
    let tube = Tube::with_vertex_count(20_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    let posed = rig.pose(&BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 }.keys(&rig)).unwrap();
    let descriptor = DeformerDescriptor::new(rig.rest(), &positions, BindingSource::bind(&owners));
    let run = |context: &GpuContext, descriptor: &DeformerDescriptor| {
        let mut deformer = GpuDeformer::new(context, descriptor).unwrap();
        deformer.deform(&posed).unwrap();
        let normals = deformer.read_normals().unwrap();
        (deformer.read_positions().unwrap(), normals, deformer)
    };
    // The fused kernel and the probe, chunked: the same verdicts, positions and normals.
    let fused = descriptor.with_triangles(&triangles).with_jacobian_normals();
    let (positions_one, normals_one, one) = run(context, &fused);
    let (positions_many, normals_many, many) = run(&small, &fused);
    assert!(many.chunk_count() >= 2, "{} deform dispatches on the small device", many.chunk_count());
    assert_eq!(one.chunk_count(), 1);
    let verdicts = one.jacobian_normal_vertices().unwrap();
    assert!(verdicts.iter().filter(|&&v| v).count() > positions.len() / 2, "the tube keeps most Jacobian normals");
    assert_eq!(many.jacobian_normal_vertices().unwrap(), verdicts, "the chunked probe's verdicts");
    assert_eq!(positions_many, positions_one);
    assert_eq!(normals_many, normals_one);
    // The staged stores, chunked, against one vertex an invocation.
    let staged = descriptor.with_deform_order(DeformOrder::StagedVertices);
    let (staged_positions, _, staged_deformer) = run(&small, &staged);
    assert_eq!(staged_deformer.deform_order(), DeformOrder::StagedVertices);
    let (vertex_positions, _, _) = run(context, &descriptor.with_deform_order(DeformOrder::Vertices));
    assert_eq!(staged_positions, vertex_positions);
}
