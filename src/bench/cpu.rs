//! The CPU bench: the f64 reference path on all cores, with the f32 twins of the copy and
//! skinning baselines.

use glam::DVec3;

use super::skinning::{skinning_influences, skinning_joints};
use std::time::Instant;

use super::{BenchReport, BenchScene, FalloffReport, Round, median, median_seconds};
use crate::bind::MeshBindings;
use crate::coeffs::GpuBinding;
use crate::cpu;
use crate::deform::deform_vertices;

const WARMUP: usize = 1;

/// The CPU path on one scene.
pub struct CpuBench {
    scene: BenchScene,
    bindings: MeshBindings,
    falloff_bindings: Vec<MeshBindings>,
    twin_bindings: Vec<GpuBinding>,
    rest_f32: Vec<f32>,
}

impl CpuBench {
    /// Binds the scene once (for the deform and copy timings).
    pub fn new(scene: BenchScene) -> CpuBench {
        let bindings = scene.rig.bind_mesh(&scene.mesh, &scene.owners, &|_| {});
        let rest = scene.rig.rest();
        let rest_f32 = cpu::packed(&scene.mesh.positions);
        let twin_bindings = cpu::bind::bind_to(rest, &scene.owners, &rest_f32);
        let falloff_bindings =
            scene.with_falloff.iter().map(|(_, s)| s.rig.bind_mesh(&s.mesh, &s.owners, &|_| {})).collect();
        CpuBench { scene, bindings, falloff_bindings, twin_bindings, rest_f32 }
    }

    /// Every figure of the report, each the median of `runs` runs after warm-up.
    pub fn report(&self, runs: usize) -> BenchReport {
        let scene = &self.scene;
        let n = scene.vertex_count();
        let mut out = vec![DVec3::ZERO; n];
        let mut out_f32 = vec![0.0f32; 3 * n];
        let bind = median_seconds(WARMUP, runs, || {
            scene.rig.bind_mesh(&scene.mesh, &scene.owners, &|_| {});
        });
        let (joints, influences) = (skinning_joints(), skinning_influences(n));
        let time = |work: &mut dyn FnMut()| {
            let start = Instant::now();
            work();
            start.elapsed().as_secs_f64()
        };
        let mut rounds = Vec::with_capacity(runs);
        for round in 0..WARMUP + runs {
            let times = Round {
                instances: (0.0, 1.0),
                partial: (0.0, 1.0),
                fused: 0.0,
                wide_copy: 1.0,
                deform: time(&mut || {
                    deform_vertices(scene.rig.rest(), &scene.posed, &self.bindings, &scene.mesh.positions, &mut out)
                }),
                falloff: scene
                    .with_falloff
                    .iter()
                    .zip(&self.falloff_bindings)
                    .map(|((_, variant), bindings)| {
                        let (rest, positions) = (variant.rig.rest(), &variant.mesh.positions);
                        time(&mut || deform_vertices(rest, &variant.posed, bindings, positions, &mut out))
                    })
                    .collect(),
                copy: time(&mut || cpu::copy::copy(&self.twin_bindings, &mut out_f32)),
                lbs: time(&mut || cpu::skinning::skinning(&joints, &self.rest_f32, &influences, &mut out_f32)),
                frame: time(&mut || {
                    let posed = scene.rig.pose(&scene.keys).expect("the bench pose fits its rig");
                    deform_vertices(scene.rig.rest(), &posed, &self.bindings, &scene.mesh.positions, &mut out);
                }),
                normals: 0.0,
            };
            if round >= WARMUP {
                rounds.push(times);
            }
        }
        let column = |f: fn(&Round) -> f64| median(&mut rounds.iter().map(f).collect::<Vec<_>>());
        let (deform, copy, lbs, frame) =
            (column(|r| r.deform), column(|r| r.copy), column(|r| r.lbs), column(|r| r.frame));
        let n_f = n as f64;
        BenchReport {
            backend: "cpu",
            adapter: format!("{} threads", crate::parallel::thread_count()),
            n,
            bind_verts_per_s: n_f / bind,
            deform_verts_per_s: n_f / deform,
            copy_verts_per_s: n_f / copy,
            lbs_verts_per_s: n_f / lbs,
            deform_over_copy: column(|r| r.deform / r.copy),
            deform_over_lbs: column(|r| r.deform / r.lbs),
            frame_ms: frame * 1e3,
            frame_cpu_ms: None,
            normals_ms: 0.0,
            readback_ms: None,
            device_bytes_per_vertex: None,
            instances_over_single: None,
            partial_over_full: None,
            fused_over_copy: None,
            fused_over_separate: None,
            normals_angle_p99_deg: None,
            falloff: scene
                .with_falloff
                .iter()
                .zip(&self.falloff_bindings)
                .enumerate()
                .map(|(i, ((kind, _), bindings))| FalloffReport {
                    kind: *kind,
                    band_fraction: bindings.bands.len() as f64 / n_f,
                    deform_verts_per_s: n_f / median(&mut rounds.iter().map(|r| r.falloff[i]).collect::<Vec<_>>()),
                    over_plain: median(&mut rounds.iter().map(|r| r.falloff[i] / r.deform).collect::<Vec<_>>()),
                    device_bytes_per_vertex: None,
                })
                .collect(),
            runs,
            timestamps: false,
        }
    }
}
