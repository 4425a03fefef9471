//! The CPU bench: the fast f32 path ([`crate::cpu_fast`], `--backend cpu`) on all cores, with
//! the f64 reference path (`--backend reference`) and the f32 twins of the copy and skinning
//! baselines timed in the same rounds.

use std::time::Instant;

use glam::DVec3;

use super::skinning::{skinning_influences, skinning_joints};
use super::{BenchReport, BenchScene, CpuPathReport, FalloffReport, Round, median, median_seconds};
use crate::bind::MeshBindings;
use crate::coeffs::{BandRecord, BindSegment, GpuBinding, SweepCoefficients, bind_segments};
use crate::cpu;
use crate::cpu::bind::BindInputs;
use crate::cpu_fast::{self, Isa};
use crate::deform::deform_vertices;

const WARMUP: usize = 1;

/// A scene bound once on both paths: the f64 reference bindings, and the fast path's (GPU
/// form, band vertices flagged) with its band records and rest cells.
struct Bound {
    reference: MeshBindings,
    bindings: Vec<GpuBinding>,
    bands: Vec<BandRecord>,
    rest: SweepCoefficients,
    tables: Vec<BindSegment>,
    flagged_owners: Vec<u32>,
    rest_f32: Vec<f32>,
}

impl Bound {
    fn new(scene: &BenchScene) -> Bound {
        let rest_sweeps = scene.rig.rest();
        let reference = scene.rig.bind_mesh(&scene.mesh, &scene.owners, &|_| {});
        let rest = SweepCoefficients::new(rest_sweeps);
        let tables = bind_segments(rest_sweeps);
        let rest_f32 = cpu::packed(&scene.mesh.positions);
        let weights = scene.rig.band_weights(&scene.mesh, &scene.owners);
        let flagged_owners = cpu_fast::bands::flagged_owners(&scene.owners, &weights);
        let inputs = BindInputs { cells: &rest.cells, bind_segments: &tables, sweeps: &rest.sweeps };
        let mut bindings = vec![GpuBinding::default(); flagged_owners.len()];
        cpu_fast::bind::bind(&inputs, &flagged_owners, &rest_f32, &mut bindings);
        let bands = cpu_fast::bands::band_records(&inputs, &weights, &rest_f32);
        Bound { reference, bindings, bands, rest, tables, flagged_owners, rest_f32 }
    }

    fn inputs(&self) -> BindInputs<'_> {
        BindInputs { cells: &self.rest.cells, bind_segments: &self.tables, sweeps: &self.rest.sweeps }
    }
}

/// The CPU paths on one scene.
pub struct CpuBench {
    scene: BenchScene,
    bound: Bound,
    falloff: Vec<Bound>,
}

impl CpuBench {
    /// Binds the scene and its falloff variants once on both paths (for the deform, copy and
    /// skinning timings).
    pub fn new(scene: BenchScene) -> CpuBench {
        let bound = Bound::new(&scene);
        let falloff = scene.with_falloff.iter().map(|(_, variant)| Bound::new(variant)).collect();
        CpuBench { scene, bound, falloff }
    }

    /// Every figure of the report, each the median of `runs` runs after warm-up.
    pub fn report(&self, runs: usize) -> BenchReport {
        let scene = &self.scene;
        let n = scene.vertex_count();
        let isa = Isa::detect();
        let bind = self.fast_bind_seconds(runs);
        let reference_bind = median_seconds(WARMUP, runs, || {
            scene.rig.bind_mesh(&scene.mesh, &scene.owners, &|_| {});
        });
        let (rounds, reference) = self.timed_rounds(runs);
        let column = |f: fn(&Round) -> f64| median(&mut rounds.iter().map(f).collect::<Vec<_>>());
        let (deform, copy, lbs, frame) =
            (column(|r| r.deform), column(|r| r.copy), column(|r| r.lbs), column(|r| r.frame));
        let n_f = n as f64;
        BenchReport {
            backend: "cpu",
            adapter: format!("{} threads", crate::parallel::thread_count()),
            n,
            cell_records: None,
            deform_order: None,
            bind_verts_per_s: n_f / bind,
            deform_verts_per_s: n_f / deform,
            copy_verts_per_s: n_f / copy,
            lbs_verts_per_s: n_f / lbs,
            deform_over_copy: column(|r| r.deform / r.copy),
            deform_over_lbs: column(|r| r.deform / r.lbs),
            cpu: Some(CpuPathReport {
                isa: isa.name(),
                reference_deform_verts_per_s: n_f / median(&mut reference.iter().map(|r| r.0).collect::<Vec<_>>()),
                reference_bind_verts_per_s: n_f / reference_bind,
                reference_over_fast: median(&mut reference.iter().map(|r| r.1).collect::<Vec<_>>()),
            }),
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
            falloff: self.falloff_reports(&rounds),
            runs,
            alternatives: Vec::new(),
            creation: None,
            memory: None,
            repeats: 1,
            timestamps: false,
        }
    }

    /// The median seconds of the fast path's binding of every vertex.
    fn fast_bind_seconds(&self, runs: usize) -> f64 {
        let mut bindings = vec![GpuBinding::default(); self.scene.vertex_count()];
        let inputs = self.bound.inputs();
        median_seconds(WARMUP, runs, || {
            cpu_fast::bind::bind(&inputs, &self.bound.flagged_owners, &self.bound.rest_f32, &mut bindings);
        })
    }

    /// `runs` rounds after warm-up, each timing the fast deform, its falloff variants, the copy
    /// and skinning baselines and a whole frame; and the reference deform of each round with
    /// its ratio to the round's fast deform.
    fn timed_rounds(&self, runs: usize) -> (Vec<Round>, Vec<(f64, f64)>) {
        let scene = &self.scene;
        let n = scene.vertex_count();
        let mut out = vec![DVec3::ZERO; n];
        let mut out_f32 = vec![0.0f32; 3 * n];
        let (joints, influences) = (skinning_joints(), skinning_influences(n));
        let posed = posed_cells(&scene.rig, &scene.posed);
        let falloff_posed: Vec<SweepCoefficients> =
            scene.with_falloff.iter().map(|(_, variant)| posed_cells(&variant.rig, &variant.posed)).collect();
        let mut pose = scene.rig.pose_buffer();
        let mut frame_cells = posed.clone();
        let mut rounds = Vec::with_capacity(runs);
        let mut reference = Vec::with_capacity(runs);
        for round in 0..WARMUP + runs {
            let reference_deform = time(&mut || {
                deform_vertices(scene.rig.rest(), &scene.posed, &self.bound.reference, &scene.mesh.positions, &mut out)
            });
            let times = Round {
                instances: (0.0, 1.0),
                partial: (0.0, 1.0),
                fused: 0.0,
                wide_copy: 1.0,
                buffer_copy: 0.0,
                alternatives: Vec::new(),
                deform: time(&mut || cpu_fast::deform::deform(&posed.cells, &self.bound.bindings, &mut out_f32)),
                falloff: self
                    .falloff
                    .iter()
                    .zip(&falloff_posed)
                    .map(|(bound, posed)| time_bands(bound, posed))
                    .collect(),
                copy: time(&mut || cpu::copy::copy(&self.bound.bindings, &mut out_f32)),
                lbs: time(&mut || cpu::skinning::skinning(&joints, &self.bound.rest_f32, &influences, &mut out_f32)),
                frame: time(&mut || {
                    scene.rig.pose_into(&scene.keys, &mut pose).expect("the bench pose fits its rig");
                    frame_cells.update(pose.sweeps()).expect("the bench pose fits its rig");
                    cpu_fast::deform::deform(&frame_cells.cells, &self.bound.bindings, &mut out_f32);
                }),
                normals: 0.0,
            };
            if round >= WARMUP {
                reference.push((reference_deform, reference_deform / times.deform));
                rounds.push(times);
            }
        }
        (rounds, reference)
    }

    /// Each falloff variant's figures from the timed `rounds`.
    fn falloff_reports(&self, rounds: &[Round]) -> Vec<FalloffReport> {
        let n_f = self.scene.vertex_count() as f64;
        let column = |f: &dyn Fn(&Round) -> f64| median(&mut rounds.iter().map(f).collect::<Vec<_>>());
        (self.scene.with_falloff.iter().zip(&self.falloff).enumerate())
            .map(|(i, ((kind, _), bound))| FalloffReport {
                kind: *kind,
                band_fraction: bound.bands.len() as f64 / n_f,
                deform_verts_per_s: n_f / column(&|r| r.falloff[i]),
                over_plain: column(&|r| r.falloff[i] / r.deform),
                device_bytes_per_vertex: None,
            })
            .collect()
    }
}

/// The seconds `work` takes, once.
fn time(work: &mut dyn FnMut()) -> f64 {
    let start = Instant::now();
    work();
    start.elapsed().as_secs_f64()
}

/// The cell records of `rig` posed by `posed`.
fn posed_cells(rig: &crate::rig::Rig, posed: &[crate::sweep::Sweep]) -> SweepCoefficients {
    let mut cells = SweepCoefficients::new(rig.rest());
    cells.update(posed).expect("the bench pose fits its rig");
    cells
}

/// The seconds of one fast deform of `bound`'s falloff scene, bands included, posed by `posed`.
fn time_bands(bound: &Bound, posed: &SweepCoefficients) -> f64 {
    let mut positions = bound.rest_f32.clone();
    let (cells, rest) = (&posed.cells, &bound.rest.cells);
    time(&mut || cpu_fast::deform::deform_with_bands(cells, rest, &bound.bindings, &bound.bands, &mut positions))
}
