//! The interactive viewer, `sweepffd view` (feature `viewer`): direct manipulation of a mesh
//! through its control sweeps in real time, as in the paper's §4–5, in a winit window.
//!
//! It is also the integration example for real-time applications: the window's wgpu device is
//! handed to a [`GpuDeformer`](sweepffd::gpu::GpuDeformer) ([`GpuContext::from_device`]), each
//! edit uploads a few KB of sweep coefficients, and the mesh is drawn straight from the
//! deformer's position and normal buffers ([`draw`]), with no readback and no buffer, pipeline
//! or bind group created per frame.
//!
//! Data flow: input ([`input`], or a [`script`]) → gesture ([`gesture`]) → edit → session
//! ([`session`]: hierarchy, volume rule, undo) → posed sweeps → coefficients → GPU deform and
//! normals → draw ([`draw`], with the [`weights`] paint) and panel ([`panel`]). A falloff width
//! changed in the panel re-bands the deformer without binding the mesh again.
//!
//! [`GpuContext::from_device`]: sweepffd::gpu::GpuContext::from_device

mod app;
mod commands;
pub mod draw;
mod frame;
pub mod gesture;
pub mod input;
mod model;
pub mod orbit;
pub mod panel;
pub mod part;
pub mod picking;
mod pointer;
pub mod script;
pub mod session;
pub mod stats;
mod surface;
pub mod weights;

use std::path::PathBuf;

pub use stats::Report;
use sweepffd::edit::VolumeRule;

/// What `sweepffd view` was asked to show.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    /// The mesh file.
    pub mesh: PathBuf,
    /// Its rest rig (none: fit sweeps in the viewer).
    pub rig: Option<PathBuf>,
    /// A pose of the rig to start from.
    pub pose: Option<PathBuf>,
    /// Subdivision of the mesh before use (rig index selections carried along).
    pub subdivide: Subdivide,
    /// The volume rule to start with.
    pub volume: VolumeRule,
    /// Replay this script, then exit.
    pub script: Option<PathBuf>,
    /// Window size in pixels.
    pub size: (u32, u32),
    /// Where Ctrl+S saves the pose (the panel can change it).
    pub pose_out: PathBuf,
}

/// How the viewer subdivides the mesh, to try it at higher vertex counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Subdivide {
    /// Not at all.
    #[default]
    No,
    /// This many levels of midpoint subdivision ([`Mesh::subdivided`](sweepffd::mesh::Mesh::subdivided)).
    Levels(usize),
    /// To this many vertices ([`Mesh::subdivided_to`](sweepffd::mesh::Mesh::subdivided_to)).
    Vertices(usize),
}

/// Why the viewer could not run.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// A file could not be read or does not fit the mesh.
    #[error("{0}")]
    Input(String),
    /// No window could be opened.
    #[error("cannot open a window: {0}")]
    Window(String),
    /// No GPU device could draw into the window.
    #[error("{0}")]
    Gpu(String),
    /// A scripted session went wrong.
    #[error("{0}")]
    Script(String),
}

/// Opens the window and runs until it is closed (or the script ends). A scripted session
/// returns its report.
pub fn run(options: ViewOptions) -> Result<Option<Report>, ViewError> {
    // The files first, so that bad input fails before any window opens.
    let (mesh, rig, pose) = (&options.mesh, options.rig.as_deref(), options.pose.as_deref());
    let model = model::Model::load(mesh, rig, pose, options.subdivide, options.volume)?;
    let player = match &options.script {
        Some(path) => {
            let steps = script::load(path).map_err(ViewError::Script)?;
            let folder = path.parent().map(|p| p.to_path_buf()).unwrap_or_default();
            Some(script::Player::new(steps, folder))
        }
        None => None,
    };
    let event_loop = winit::event_loop::EventLoop::new().map_err(|e| ViewError::Window(e.to_string()))?;
    let mut app = app::App::new(options, model, player, &event_loop);
    event_loop.run_app(&mut app).map_err(|e| ViewError::Window(e.to_string()))?;
    app.finish()
}
