//! The `bend` edit on the GPU: the bunny's ears and the armadillo's first limb (`autorig`, with
//! their falloff bands), each bent 60° over a fifth of it, deformed by the GPU engine and by the
//! f64 reference: the positions agree within 1e-5 of the diagonal, and so the largest edge
//! stretch, which `tests/fitting/bend_limbs.rs` bounds on the CPU, is the GPU's too.

use crate::common;

use glam::DVec3;
use sweepffd::deform::deform_vertices;
use sweepffd::edit::{Edit, Posing};
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuDeformer};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;

use common::bends::{stretch_range, thinnest_axis};

fn bend_on_the_gpu(file: &str, limbs: &[&str]) {
    let Some(path) = common::shared_mesh(file) else { return };
    let Some(context) = common::gpu() else { return };
    let mesh = Mesh::load(&path).unwrap();
    let rig = Rig::from_document(&autorig(&mesh, &AutorigOptions::default()).unwrap().document(), None).unwrap();
    let owners = rig.owners(&mesh, file).unwrap();
    let bands = rig.band_weights(&mesh, &owners);
    let reference_bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let positions = sweepffd::gpu::rest_positions(&mesh.positions);
    let source = BindingSource::Bind { owners: &owners, bands: &bands };
    let mut deformer = GpuDeformer::new(context, &DeformerDescriptor::new(rig.rest(), &positions, source)).unwrap();
    let diagonal = mesh.diagonal();
    for &limb in limbs {
        let sweep = rig.sweep_index(limb).unwrap();
        let (axis, _) = thinnest_axis(&rig, sweep, 0.5, 0.2);
        let mut posing = Posing::new(&rig);
        posing
            .apply(&Edit::Bend { sweep: limb.into(), t: 0.5, span: 0.2, axis: axis.to_array(), angle_deg: 60.0 })
            .unwrap();
        let posed = posing.sweeps().unwrap();
        deformer.deform(&posed).unwrap();
        let gpu: Vec<DVec3> = deformer
            .read_positions()
            .unwrap()
            .chunks_exact(3)
            .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
            .collect();
        let mut reference = vec![DVec3::ZERO; mesh.positions.len()];
        deform_vertices(rig.rest(), &posed, &reference_bindings, &mesh.positions, &mut reference);
        let (worst, at) = gpu
            .iter()
            .zip(&reference)
            .enumerate()
            .map(|(i, (g, r))| (g.distance(*r), i))
            .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a });
        let (gpu_range, cpu_range) = (stretch_range(&mesh, &gpu), stretch_range(&mesh, &reference));
        println!(
            "{file} {limb} bent 60° over a fifth: GPU vs f64 reference max |Δ| {:.2e} × diagonal at vertex {at}; \
             edges {:.4}–{:.4} of rest on the GPU, {:.4}–{:.4} on the CPU",
            worst / diagonal,
            gpu_range.1,
            gpu_range.0,
            cpu_range.1,
            cpu_range.0
        );
        assert!(worst <= 1e-5 * diagonal, "{file} {limb}: GPU off the reference by {worst} at vertex {at}");
        assert!((gpu_range.0 - cpu_range.0).abs() <= 1e-3 * cpu_range.0, "{file} {limb}: largest stretch");
    }
}

#[test]
fn bent_ears_on_the_gpu_match_the_reference() {
    bend_on_the_gpu("bunny_stanford_zipper.obj", &["limb0", "limb1"]);
}

#[test]
fn a_bent_armadillo_limb_on_the_gpu_matches_the_reference() {
    bend_on_the_gpu("armadillo_50k.obj", &["limb0"]);
}
