//! `sweepffd bind`: bind every owned vertex and save the bindings file.

use std::path::{Path, PathBuf};
use std::time::Instant;

use super::CliResult;
use super::args::{MeshArg, RigArg};
use super::backend::{Backend, Device, resolve};
use super::progress::vertex_bar;
use sweepffd::bind::MeshBindings;
use sweepffd::bind::band::bind_bands;
use sweepffd::bindings_file::BindingsFile;
use sweepffd::coeffs::SweepCoefficients;
use sweepffd::cpu_fast::FastMesh;
use sweepffd::formats::LoadedMesh;
use sweepffd::frame::Frame;
use sweepffd::glam::DVec3;
use sweepffd::gpu::{BindingSource, DeformerDescriptor, GpuContext, GpuDeformer, GpuError};
use sweepffd::rig::{Rig, RigError, RigErrorKind};
use sweepffd::sweep::Sweep;

/// The arguments of `sweepffd bind`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub mesh: MeshArg,
    #[command(flatten)]
    pub rig: RigArg,
    /// Where to write the bindings file.
    #[arg(long)]
    pub out: PathBuf,
    /// Where to bind: the GPU kernels, the fast f32 CPU path, the f64 reference on the CPU, or
    /// the GPU when one is available.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    pub backend: Backend,
}

/// A mesh, its rig and the owning sweep of each vertex.
pub struct Inputs {
    /// The mesh, with its file for a faithful save.
    pub file: LoadedMesh,
    pub rig: Rig,
    pub owners: Vec<u32>,
}

/// Loads the mesh and rig and resolves vertex ownership.
pub fn load_inputs(mesh_path: &Path, rig_path: &Path) -> Result<Inputs, Box<dyn std::error::Error>> {
    let file = LoadedMesh::load(mesh_path)?;
    let rig = Rig::load(rig_path)?;
    let owners = rig.owners(&file.mesh, &mesh_path.display().to_string())?;
    Ok(Inputs { file, rig, owners })
}

/// Whether an error of [`load_inputs`] is the rig file's having no sweeps (as `sweepffd
/// autorig` writes for a mesh with no protrusion), which `deform` and `render` take as leaving
/// the mesh as it is.
pub fn is_empty_rig(error: &(dyn std::error::Error + 'static)) -> bool {
    error.downcast_ref::<RigError>().is_some_and(|e| matches!(e.kind, RigErrorKind::NoSweeps))
}

/// The rig's rest sweeps and the mesh's positions in the frame of the mesh ([`Frame`]), where
/// the f32 paths bind and deform, so that their accuracy is relative to the mesh wherever it
/// sits and whatever its size.
pub struct InFrame {
    pub frame: Frame,
    pub rest: Vec<Sweep>,
    pub positions: Vec<DVec3>,
}

impl InFrame {
    pub fn of(inputs: &Inputs) -> InFrame {
        let frame = Frame::of_points(&inputs.file.mesh.positions);
        let positions = frame.local_positions(&inputs.file.mesh.positions);
        InFrame { frame, rest: frame.local_sweeps(inputs.rig.rest()), positions }
    }
}

/// Binds on the GPU, read back in the reference form; the falloff bands' second bindings are
/// made on the CPU (f64), as the file stores them. Binds in the frame of the mesh ([`Frame`]),
/// as `deform` deforms, and returns the bindings in world units.
pub fn bind_on_gpu(context: &GpuContext, inputs: &Inputs) -> Result<MeshBindings, GpuError> {
    let InFrame { frame, rest, positions: local } = InFrame::of(inputs);
    let weights = inputs.rig.band_weights(&inputs.file.mesh, &inputs.owners);
    let source = BindingSource::Bind { owners: &inputs.owners, bands: &weights };
    let positions = sweepffd::gpu::rest_positions(&local);
    let deformer = GpuDeformer::new(context, &DeformerDescriptor::new(&rest, &positions, source))?;
    let coefficients = SweepCoefficients::new(&rest);
    let vertices = deformer.read_bindings()?.iter().map(|b| coefficients.reference_binding(&rest, b)).collect();
    Ok(frame.world_bindings(&MeshBindings { vertices, bands: bind_bands(&rest, &local, &weights) }))
}

/// Binds on the fast CPU path, in the reference form as the GPU's bindings are read back; the
/// falloff bands' second bindings are made in f64, as the file stores them. In the frame of
/// the mesh, as on the GPU.
pub fn bind_on_cpu(inputs: &Inputs) -> MeshBindings {
    let InFrame { frame, rest, positions: local } = InFrame::of(inputs);
    let weights = inputs.rig.band_weights(&inputs.file.mesh, &inputs.owners);
    let positions = sweepffd::cpu_fast::packed(&local);
    let fast = FastMesh::bind(&rest, &inputs.owners, &weights, &positions);
    let vertices = fast.bindings.iter().map(|b| fast.rest.reference_binding(&rest, b)).collect();
    frame.world_bindings(&MeshBindings { vertices, bands: bind_bands(&rest, &local, &weights) })
}

/// Binds with a progress bar (f64 reference path, all cores), with the falloff bands.
pub fn bind_with_progress(inputs: &Inputs, quiet: bool) -> MeshBindings {
    let bar = vertex_bar(inputs.file.mesh.positions.len(), "binding", quiet);
    let bindings = inputs.rig.bind_mesh(&inputs.file.mesh, &inputs.owners, &|done| {
        bar.inc(done as u64);
    });
    bar.finish_and_clear();
    bindings
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    let out = &args.out;
    let inputs = load_inputs(&args.mesh.mesh, &args.rig.rig)?;
    let context = resolve(args.backend, quiet)?;
    let start = Instant::now();
    let bindings = match &context {
        Device::Gpu(context) => bind_on_gpu(context, &inputs)?,
        Device::Cpu => bind_on_cpu(&inputs),
        Device::Reference => bind_with_progress(&inputs, quiet),
    };
    let seconds = start.elapsed().as_secs_f64();
    let owned = inputs.owners.iter().filter(|&&o| o != sweepffd::bind::UNOWNED).count();
    BindingsFile::new(&inputs.rig, &inputs.file.mesh.positions, bindings).save(out)?;
    if !quiet {
        out!(
            "bound {owned} of {} vertices to {} sweeps on the {} in {seconds:.3} s -> {}",
            inputs.file.mesh.positions.len(),
            inputs.rig.sweeps().len(),
            context.name(),
            out.display()
        );
    }
    Ok(())
}
