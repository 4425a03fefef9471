//! The CPU bench: the f64 reference path on all cores, with the f32 twins of the copy and
//! skinning baselines.

use glam::DVec3;

use super::scene::BENCH_POSE;
use super::skinning::{skinning_influences, skinning_joints};
use super::{BenchReport, BenchScene, median_seconds};
use crate::bind::{Binding, bind_vertices};
use crate::coeffs::{GpuBinding, SweepCoefficients, bind_segments};
use crate::cpu;
use crate::deform::deform_vertices;

const WARMUP: usize = 1;

/// The CPU path on one scene.
pub struct CpuBench {
    scene: BenchScene,
    bindings: Vec<Binding>,
    twin_bindings: Vec<GpuBinding>,
    rest_f32: Vec<f32>,
}

impl CpuBench {
    /// Binds the scene once (for the deform and copy timings).
    pub fn new(scene: BenchScene) -> CpuBench {
        let bindings = bind_vertices(
            scene.rig.rest(),
            &scene.owners,
            &scene.mesh.positions,
            &|_| {},
        );
        let rest = scene.rig.rest();
        let coefficients = SweepCoefficients::new(rest);
        let tables = bind_segments(rest);
        let inputs = cpu::bind::BindInputs {
            segments: &coefficients.segments,
            patches: &coefficients.patches,
            bind_segments: &tables,
            sweeps: &coefficients.sweeps,
        };
        let rest_f32: Vec<f32> = scene
            .mesh
            .positions
            .iter()
            .flat_map(|p| p.as_vec3().to_array())
            .collect();
        let twin_bindings = cpu::bind::bind(&inputs, &scene.owners, &rest_f32);
        CpuBench {
            scene,
            bindings,
            twin_bindings,
            rest_f32,
        }
    }

    /// Every figure of the report, each the median of `runs` runs after warm-up.
    pub fn report(&self, runs: usize) -> BenchReport {
        let scene = &self.scene;
        let n = scene.vertex_count();
        let mut out = vec![DVec3::ZERO; n];
        let mut out_f32 = vec![0.0f32; 3 * n];
        let bind = median_seconds(WARMUP, runs, || {
            bind_vertices(
                scene.rig.rest(),
                &scene.owners,
                &scene.mesh.positions,
                &|_| {},
            );
        });
        let deform = median_seconds(WARMUP, runs, || {
            deform_vertices(
                &scene.posed,
                &self.bindings,
                &scene.mesh.positions,
                &mut out,
            )
        });
        let copy = median_seconds(WARMUP, runs, || {
            cpu::copy::copy(&self.twin_bindings, &mut out_f32)
        });
        let (joints, influences) = (skinning_joints(), skinning_influences(n));
        let lbs = median_seconds(WARMUP, runs, || {
            cpu::skinning::skinning(&joints, &self.rest_f32, &influences, &mut out_f32)
        });
        let keys = BENCH_POSE.keys(&scene.rig);
        let frame = median_seconds(WARMUP, runs, || {
            let posed = scene.rig.pose(&keys).expect("the bench pose fits its rig");
            deform_vertices(&posed, &self.bindings, &scene.mesh.positions, &mut out);
        });
        let n_f = n as f64;
        BenchReport {
            backend: "cpu",
            adapter: format!("{} threads", rayon::current_num_threads()),
            n,
            bind_verts_per_s: n_f / bind,
            deform_verts_per_s: n_f / deform,
            copy_verts_per_s: n_f / copy,
            lbs_verts_per_s: n_f / lbs,
            deform_over_copy: deform / copy,
            deform_over_lbs: deform / lbs,
            frame_ms: frame * 1e3,
            readback_ms: None,
            device_bytes_per_vertex: None,
            runs,
            timestamps: false,
        }
    }
}
