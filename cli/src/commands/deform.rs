//! `sweepffd deform`: pose the rig, move the bound vertices (Eq. 2), write the mesh.

use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::{DVec3, Vec3};

use super::CliResult;
use super::args::{MeshArg, PoseArg, RigArg};
use super::backend::{Backend, Device, resolve};
use super::bind::{InFrame, Inputs, bind_with_progress, is_empty_rig, load_inputs};
use sweepffd::bind::falloff::BandWeight;
use sweepffd::bind::{MeshBindings, UNOWNED};
use sweepffd::bindings_file::{BindingsFile, BindingsFileError, MadeFor};
use sweepffd::coeffs::SweepCoefficients;
use sweepffd::cpu_fast::FastMesh;
use sweepffd::deform::deform_vertices;
use sweepffd::formats::{Format, LoadedMesh};
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuDeformer, GpuError};
use sweepffd::sweep::Sweep;

/// The arguments of `sweepffd deform`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub mesh: MeshArg,
    #[command(flatten)]
    pub rig: RigArg,
    #[command(flatten)]
    pub pose: PoseArg,
    /// Where to write the deformed mesh (.obj, .ply, .off, .gltf or .glb).
    #[arg(long)]
    pub out: PathBuf,
    /// Bindings saved by `sweepffd bind` for this mesh and rig (otherwise binds anew).
    #[arg(long)]
    pub bindings: Option<PathBuf>,
    /// Where to bind and deform: the GPU kernels, the fast f32 CPU path, the f64 reference on
    /// the CPU, or the GPU when one is available.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    pub backend: Backend,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    // Refuse an unsupported output before any work is done.
    Format::of(&args.out)?;
    let inputs = match load_inputs(&args.mesh.mesh, &args.rig.rig) {
        Err(error) if is_empty_rig(&*error) => {
            // A rig of no sweeps moves nothing: the mesh is written as it is.
            let file = LoadedMesh::load(&args.mesh.mesh)?;
            file.save(&args.out, &file.mesh.positions)?;
            note!("notice: {error}; wrote the mesh unchanged to {}", args.out.display());
            return Ok(());
        }
        loaded => loaded?,
    };
    let posed = inputs.rig.load_pose(&args.pose.pose)?;
    warn_of_folds(&inputs, &posed, &args.pose.pose);
    let saved = match &args.bindings {
        Some(path) => {
            let file = BindingsFile::load(path)?;
            file.check_matches(&inputs.rig, &inputs.file.mesh.positions, path).map_err(|e| match e {
                // The engine says what the file was made for; the command line says what to do.
                BindingsFileError::Mismatch { made_for: MadeFor::AnotherRig | MadeFor::AnotherMesh, .. } => {
                    format!("{e} (run `sweepffd bind` again)")
                }
                e => e.to_string(),
            })?;
            Some(file.bindings)
        }
        None => None,
    };
    let context = resolve(args.backend, quiet)?;
    let start = Instant::now();
    let mut bound = BoundMesh::new(&inputs, &context, saved.as_ref(), quiet)?;
    let (positions, owners) = bound.deform(&posed)?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(error) = non_finite(&inputs, &positions, &owners, &args.pose.pose) {
        return Err(format!("{error}; nothing was written").into());
    }
    inputs.file.save(&args.out, &positions)?;
    if !quiet {
        let owned = owners.iter().filter(|&&o| o != UNOWNED).count();
        let (source, backend) = (if saved.is_some() { "saved" } else { "new" }, context.name());
        out!(
            "deformed {owned} of {} vertices on the {backend} ({source} bindings) in {seconds:.3} s -> {}",
            positions.len(),
            args.out.display()
        );
    }
    Ok(())
}

/// Prints a warning for each stretch of a sweep the pose `posed` (read from `pose`) folds:
/// folds do not stop `deform`, `batch` or `export`, whose output is still written.
pub fn warn_of_folds(inputs: &Inputs, posed: &[Sweep], pose: &Path) {
    for warning in sweepffd::edit::pose_warnings(&inputs.rig, posed) {
        note!("warning: {}: {warning}", pose.display());
    }
}

/// The error naming the pose, the vertex and its sweep where the deformed `positions` (with
/// their `owners`) hold a non-finite position; `None` where all are finite.
pub fn non_finite(inputs: &Inputs, positions: &[DVec3], owners: &[u32], pose: &Path) -> Option<String> {
    let i = positions.iter().position(|p| !p.is_finite())?;
    let sweep = &inputs.rig.sweeps()[owners[i] as usize].name;
    Some(format!("{}: vertex index {i} (sweep {sweep:?}) deforms to a non-finite position", pose.display()))
}

/// A mesh bound to its rig on one backend, deformed pose after pose: the binding, the costly
/// part, is done once (`deform` deforms one pose, `batch` every pose of a mesh and rig). The
/// f32 paths work in the frame of the mesh ([`InFrame`]).
pub struct BoundMesh<'a> {
    inputs: &'a Inputs,
    framed: InFrame,
    /// The saved bindings in the frame of the mesh, if the mesh was not bound anew.
    saved: Option<MeshBindings>,
    engine: Engine,
}

/// Where a [`BoundMesh`] deforms.
enum Engine {
    Gpu { deformer: Box<GpuDeformer>, weights: Vec<BandWeight> },
    Cpu { fast: FastMesh, weights: Vec<BandWeight>, rest: Vec<f32> },
    Reference { bindings: MeshBindings },
}

impl<'a> BoundMesh<'a> {
    /// Binds `inputs` on `device`, or takes the `saved` bindings.
    pub fn new(
        inputs: &'a Inputs,
        device: &Device,
        saved: Option<&MeshBindings>,
        quiet: bool,
    ) -> Result<BoundMesh<'a>, GpuError> {
        let framed = InFrame::of(inputs);
        let local_saved = saved.map(|saved| framed.frame.local_bindings(saved));
        let rest = &framed.rest[..];
        let weights = || match saved {
            Some(_) => Vec::new(),
            None => inputs.rig.band_weights(&inputs.file.mesh, &inputs.owners),
        };
        let engine = match device {
            Device::Gpu(context) => {
                let weights = weights();
                let converted =
                    local_saved.as_ref().map(|saved| SweepCoefficients::new(rest).gpu_mesh_bindings(rest, saved));
                let source = match &converted {
                    Some((bindings, bands)) => BindingSource::Precomputed { bindings, bands },
                    None => BindingSource::Bind { owners: &inputs.owners, bands: &weights },
                };
                let positions = sweepffd::gpu::rest_positions(&framed.positions);
                let deformer = GpuDeformer::new(context, &DeformerDescriptor::new(rest, &positions, source))?;
                Engine::Gpu { deformer: Box::new(deformer), weights }
            }
            Device::Cpu => {
                let positions = sweepffd::cpu_fast::packed(&framed.positions);
                let weights = weights();
                let fast = match &local_saved {
                    Some(saved) => {
                        let (bindings, bands) = SweepCoefficients::new(rest).gpu_mesh_bindings(rest, saved);
                        FastMesh::with_bindings(rest, bindings, bands)
                    }
                    None => FastMesh::bind(rest, &inputs.owners, &weights, &positions),
                };
                Engine::Cpu { fast, weights, rest: positions }
            }
            Device::Reference => {
                let bindings = saved.cloned().unwrap_or_else(|| bind_with_progress(inputs, quiet));
                Engine::Reference { bindings }
            }
        };
        Ok(BoundMesh { inputs, framed, saved: local_saved, engine })
    }

    /// The mesh deformed by `posed` (world positions, f64) and each vertex's owner. On the
    /// f32 paths the vertices no sweep moves (unowned, or at weight 0 against the rest
    /// position) keep their exact rest positions.
    pub fn deform(&mut self, posed: &[Sweep]) -> Result<(Vec<DVec3>, Vec<u32>), GpuError> {
        let local_posed = || self.framed.frame.local_sweeps(posed);
        match &mut self.engine {
            Engine::Gpu { deformer, weights } => {
                deformer.deform(&local_posed())?;
                let deformed = deformer.read_positions()?;
                Ok(f32_result(self.inputs, &self.framed, self.saved.as_ref(), weights, &deformed))
            }
            Engine::Cpu { fast, weights, rest } => {
                let mut positions = rest.clone();
                fast.deform(&local_posed(), &mut positions).expect("a pose loaded for this rig fits it");
                Ok(f32_result(self.inputs, &self.framed, self.saved.as_ref(), weights, &positions))
            }
            Engine::Reference { bindings } => {
                let mesh = &self.inputs.file.mesh;
                let mut positions = vec![DVec3::ZERO; mesh.positions.len()];
                deform_vertices(self.inputs.rig.rest(), posed, bindings, &mesh.positions, &mut positions);
                Ok((positions, bindings.vertices.iter().map(|b| b.sweep).collect()))
            }
        }
    }
}

/// The f32 positions `deformed` (in the frame of `local`) in the world in f64, the vertices no
/// sweep moves (unowned, or at weight 0 against the rest position) at their exact rest
/// positions; and the owners.
fn f32_result(
    inputs: &Inputs,
    framed: &InFrame,
    saved: Option<&MeshBindings>,
    weights: &[BandWeight],
    deformed: &[f32],
) -> (Vec<DVec3>, Vec<u32>) {
    let owners: Vec<u32> = match saved {
        Some(saved) => saved.vertices.iter().map(|b| b.sweep).collect(),
        None => inputs.owners.clone(),
    };
    let mut keeps_rest: Vec<bool> = owners.iter().map(|&o| o == UNOWNED).collect();
    match saved {
        Some(saved) => keeps_rest = saved.keeps_rest(),
        None => {
            for band in weights.iter().filter(|b| b.keeps_rest()) {
                keeps_rest[band.vertex as usize] = true;
            }
        }
    }
    let positions = deformed
        .chunks_exact(3)
        .zip(&inputs.file.mesh.positions)
        .zip(&keeps_rest)
        .map(|((p, rest), &keeps)| if keeps { *rest } else { framed.frame.to_world(Vec3::from_slice(p).as_dvec3()) })
        .collect();
    (positions, owners)
}
