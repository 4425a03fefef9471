//! `sweepffd bench`: vertices per second of binding and deformation against a copy kernel and
//! linear-blend skinning on the same device, as one JSON line with `--json`.

use std::path::PathBuf;

use super::CliResult;
use super::backend::{Backend, Device, resolve};
use sweepffd::bench::{
    BenchReport, BenchScene, CpuBench, FalloffKind, GpuBench, check_runs, gpu_vertex_limit, tube_vertex_count,
};
use sweepffd::limits::MAX_BENCH_VERTICES;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;

/// The arguments of `sweepffd bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Vertices of the synthetic tube to measure, from 770 up to what the device's largest
    /// buffer holds (16 bytes a vertex; at most 2^30) (ignored with --mesh and --rig); rounded
    /// down to a whole tube, 256·k + 2 vertices, with a note.
    #[arg(long, default_value_t = 1_000_000)]
    pub vertices: usize,
    /// Measure this mesh instead of a synthetic tube (needs --rig).
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// The rest rig of --mesh.
    #[arg(long)]
    pub rig: Option<PathBuf>,
    /// Where to measure (cpu and reference run the same CPU bench, which times the fast path
    /// and the f64 reference in the same rounds).
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    pub backend: Backend,
    /// Timed runs per figure (each figure is their median), 1 to 10000.
    #[arg(long, default_value_t = 10)]
    pub runs: usize,
    /// Print one JSON line.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    // The engine names the field; the command line, the flag that sets it.
    check_runs(args.runs).map_err(|e| format!("--{e}"))?;
    let device = resolve(args.backend, quiet || args.json)?;
    let max_vertices = match &device {
        Device::Gpu(context) => gpu_vertex_limit(&context.device.limits()),
        Device::Cpu | Device::Reference => MAX_BENCH_VERTICES,
    };
    let scene = match (&args.mesh, &args.rig) {
        (Some(mesh_path), Some(rig_path)) => {
            let mesh = Mesh::load(mesh_path)?;
            let rig = Rig::load(rig_path)?;
            BenchScene::new(mesh, rig, &mesh_path.display().to_string())?
        }
        (None, None) => {
            let vertices = tube_vertex_count(args.vertices, max_vertices).map_err(|e| format!("--{e}"))?;
            if vertices != args.vertices && !quiet {
                note!(
                    "note: measuring {vertices} vertices, the largest synthetic tube with at most --vertices {} \
                     (tubes have 256·k + 2 vertices)",
                    args.vertices
                );
            }
            BenchScene::tube(vertices)
        }
        _ => return Err("--mesh and --rig go together".into()),
    };
    let runs = args.runs;
    let report = match device {
        Device::Gpu(context) => GpuBench::new(&context, scene)?.report(runs)?,
        Device::Cpu | Device::Reference => CpuBench::new(scene).report(runs),
    };
    if args.json {
        out!("{}", serde_json::to_string(&report)?);
    } else {
        print_table(&report);
    }
    Ok(())
}

fn print_table(r: &BenchReport) {
    let rate = |v: f64| format!("{:>10.2} M vertices/s", v / 1e6);
    out!("{} backend, {}, {} vertices, medians of {} runs", r.backend, r.adapter, r.n, r.runs);
    out!("  bind      {}", rate(r.bind_verts_per_s));
    out!(
        "  deform    {}   ({:.2} × copy time, {:.2} × skinning time)",
        rate(r.deform_verts_per_s),
        r.deform_over_copy,
        r.deform_over_lbs
    );
    if let Some(cpu) = &r.cpu {
        out!("  (bind and deform: the fast f32 path on {})", cpu.isa);
        out!("  reference bind   {}   (f64, with the falloff bands)", rate(cpu.reference_bind_verts_per_s));
        out!(
            "  reference deform {}   ({:.2} × the fast path's time)",
            rate(cpu.reference_deform_verts_per_s),
            cpu.reference_over_fast
        );
    }
    out!("  copy      {}   (baseline: the deform kernel's bytes)", rate(r.copy_verts_per_s));
    out!("  skinning  {}   (baseline: 4-influence linear-blend skinning)", rate(r.lbs_verts_per_s));
    out!("  frame     {:>10.3} ms (pose to coefficients, upload, deform)", r.frame_ms);
    if let Some(ms) = r.frame_cpu_ms {
        out!("  frame CPU {ms:>10.4} ms (host: pose_into, set_pose, encode)");
    }
    if r.backend == "gpu" {
        out!("  normals   {:>10.3} ms (area-weighted vertex normals of the deformed mesh)", r.normals_ms);
    }
    if let (Some(copy), Some(separate), Some(angle)) =
        (r.fused_over_copy, r.fused_over_separate, r.normals_angle_p99_deg)
    {
        out!(
            "  fused     {copy:>10.2} × (deform + Jacobian normals over a copy of its bytes; {separate:.2} × deform + \
             triangle normals; 99th percentile {angle:.2}° from the triangle normals)"
        );
    }
    if let Some(readback) = r.readback_ms {
        out!("  readback  {readback:>10.3} ms");
    }
    if let Some(bytes) = r.device_bytes_per_vertex {
        out!("  device memory for bindings + positions: {bytes:.1} bytes per vertex");
    }
    if let (Some(instances), Some(partial)) = (r.instances_over_single, r.partial_over_full) {
        out!(
            "  instances {instances:>10.2} × ({} instances of n / {} vertices over one n-vertex mesh, deform)",
            sweepffd::bench::INSTANCES,
            sweepffd::bench::INSTANCES
        );
        out!(
            "  partial   {partial:>10.2} × (a rig owning {:.0}% of the vertices over one owning all, deform + normals)",
            100.0 * sweepffd::bench::PARTIAL_SHARE
        );
    }
    for f in &r.falloff {
        let into = match f.kind {
            FalloffKind::Rest => "the rest position",
            FalloffKind::Sweep => "a neighbouring sweep",
        };
        out!(
            "  falloff   {}   ({:.0}% of the vertices in bands fading into {into}: {:.2} × the deform time without)",
            rate(f.deform_verts_per_s),
            100.0 * f.band_fraction,
            f.over_plain
        );
        if let Some(bytes) = f.device_bytes_per_vertex {
            out!("            device memory with the bands: {bytes:.1} bytes per vertex");
        }
    }
}
