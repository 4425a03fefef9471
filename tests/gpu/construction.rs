//! Deformer construction on one context: the pipelines are compiled once per context and shared
//! by every deformer built on it (or its clones), which makes building a small mesh's deformer
//! cheap after the first.

use crate::common;

use std::time::Instant;

use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer};
use sweepffd::synthetic::{Tube, tube_rig};

/// Milliseconds to build a 2,000-vertex tube's deformer (with normals) on `context`.
fn build_ms(context: &GpuContext) -> f64 {
    let tube = Tube::with_vertex_count(2_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let start = Instant::now();
    let source = BindingSource::Bind { owners: &owners, bands: &[] };
    let deformer = common::deformer(context, rig.rest(), &mesh.positions, source, Some(&mesh.faces)).unwrap();
    let ms = start.elapsed().as_secs_f64() * 1e3;
    drop(deformer);
    ms
}

#[test]
fn two_deformers_on_one_context_compile_each_pipeline_once() {
    let Some(context) = common::gpu() else { return };
    // A context of its own (same device, empty pipeline cache), so that other tests in this
    // binary do not fill its cache first.
    let own = GpuContext::from_device(context.device.clone(), context.queue.clone(), context.info.clone());
    build_ms(&own);
    let after_first = own.compiled_pipelines();
    assert!(after_first >= 3, "bind, deform and normals compiled: {after_first}");
    build_ms(&own.clone());
    assert_eq!(own.compiled_pipelines(), after_first, "the second deformer compiled pipelines of its own");
}

#[test]
fn construction_time_with_and_without_shared_pipelines() {
    let Some(context) = common::gpu() else { return };
    build_ms(context);
    // Before: every deformer compiled its own pipelines (a fresh cache each time).
    let fresh: Vec<f64> = (0..5)
        .map(|_| {
            build_ms(&GpuContext::from_device(context.device.clone(), context.queue.clone(), context.info.clone()))
        })
        .collect();
    let shared: Vec<f64> = (0..5).map(|_| build_ms(context)).collect();
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (fresh, shared) = (median(fresh), median(shared));
    println!("2k-vertex deformer construction: {fresh:.1} ms compiling its pipelines, {shared:.1} ms sharing them");
    assert!(shared < fresh, "sharing the pipelines made construction slower: {shared} ms vs {fresh} ms");
}

#[test]
fn the_async_constructor_builds_the_same_bindings_without_waiting() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(2_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &[] });
    let blocking = GpuDeformer::new(context, &descriptor).unwrap();
    let deformer = pollster::block_on(GpuDeformer::new_async(context, &descriptor)).unwrap();
    assert_eq!(deformer.read_bindings().unwrap(), blocking.read_bindings().unwrap());
}

#[test]
fn a_triangle_list_past_the_vertices_or_not_in_threes_is_refused() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(2_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, BindingSource::Bind { owners: &owners, bands: &[] });
    let past = [0, 1, positions.len() as u32];
    let error = GpuDeformer::new(context, &descriptor.with_triangles(&past)).unwrap_err();
    assert!(error.to_string().contains("refers to vertex"), "{error}");
    let error = GpuDeformer::new(context, &descriptor.with_triangles(&[0, 1])).unwrap_err();
    assert!(error.to_string().contains("multiple of 3"), "{error}");
    let mut nan = positions.clone();
    nan[7][1] = f32::NAN;
    let error = GpuDeformer::new(context, &DeformerDescriptor { positions: &nan, ..descriptor }).unwrap_err();
    assert!(error.to_string().contains("vertex 7"), "{error}");
}
