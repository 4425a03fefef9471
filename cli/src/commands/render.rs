//! `sweepffd render`: a PNG of a mesh, rest or posed, optionally with its control sweeps, or
//! rest and pose side by side.

use std::path::PathBuf;
use std::time::Instant;

use glam::DVec3;

use super::CliResult;
use super::args::MeshArg;
use super::bind::{is_empty_rig, load_inputs};
use crate::render::{CLAY, Renderer, Scene, SweepStyle, ViewAngles, add_sweeps, save_png, union_bounds};
use sweepffd::deform::deform_vertices;
use sweepffd::frame::Frame;
use sweepffd::mesh::Mesh;
use sweepffd::sweep::Sweep;

/// The arguments of `sweepffd render`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub mesh: MeshArg,
    /// The rest rig (JSON); needed by --pose and --show-sweeps.
    #[arg(long)]
    pub rig: Option<PathBuf>,
    /// Draw the mesh deformed by this pose of the rig (bound and deformed on the CPU).
    #[arg(long)]
    pub pose: Option<PathBuf>,
    /// Draw the control sweeps as translucent surfaces with a dark ring at each key.
    #[arg(long)]
    pub show_sweeps: bool,
    /// Picture size WIDTHxHEIGHT in pixels (each panel's with --compare).
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Camera AZIMUTH,ELEVATION in degrees: azimuth around +Y from +Z towards +X, elevation
    /// above the XZ plane (Y is up).
    #[arg(long, default_value = "30,20", value_parser = parse_view, allow_hyphen_values = true)]
    pub view: crate::render::ViewAngles,
    /// Draw rest (left) and pose (right) side by side, one camera, picture width 2×WIDTH.
    #[arg(long)]
    pub compare: bool,
    /// Frame a box this many times smaller than the mesh's (at least 1), centred on --look-at:
    /// a close-up.
    #[arg(long, default_value_t = 1.0)]
    pub zoom: f64,
    /// The point X,Y,Z (mesh coordinates) the close-up of --zoom is centred on (default: the
    /// middle of the mesh's bounds).
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true)]
    pub look_at: Option<DVec3>,
    /// Where to write the picture (.png).
    #[arg(long)]
    pub out: PathBuf,
}

/// The most pixels a picture may have: 4096 × 4096. A pixel takes about 44 bytes while it is
/// drawn (a colour and a depth sample at 4× multisampling, the resolved colour, its readback
/// and the image), so this bounds a picture at about 0.7 GB; 8192 × 8192 took 3.25 GB.
pub const MAX_PICTURE_PIXELS: u64 = 1 << 24;

/// Parses `--size WxH` (both at least 1, at most [`MAX_PICTURE_PIXELS`] in all).
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let invalid = || format!("expected WIDTHxHEIGHT in pixels, such as 640x480, not {text:?}");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(invalid)?;
    let (w, h): (u32, u32) = (w.trim().parse().map_err(|_| invalid())?, h.trim().parse().map_err(|_| invalid())?);
    if w == 0 || h == 0 {
        return Err(format!("the picture size {w}x{h} has a zero side"));
    }
    let pixels = u64::from(w) * u64::from(h);
    if pixels > MAX_PICTURE_PIXELS {
        return Err(format!(
            "the picture size {w}x{h} is {pixels} pixels, over the limit of {MAX_PICTURE_PIXELS} (4096x4096: about 44 \
             bytes each while drawn)"
        ));
    }
    Ok((w, h))
}

/// Parses `--view AZIMUTH,ELEVATION` in degrees.
pub fn parse_view(text: &str) -> Result<ViewAngles, String> {
    let invalid = || format!("expected AZIMUTH,ELEVATION in degrees, such as 30,20, not {text:?}");
    let (a, e) = text.split_once(',').ok_or_else(invalid)?;
    let (a, e): (f32, f32) = (a.trim().parse().map_err(|_| invalid())?, e.trim().parse().map_err(|_| invalid())?);
    ViewAngles::try_new(a, e).map_err(|e| e.to_string())
}

/// Parses `--look-at X,Y,Z`.
pub fn parse_point(text: &str) -> Result<DVec3, String> {
    let invalid = || format!("expected X,Y,Z, three finite numbers, such as 0,1.5,-2, not {text:?}");
    let values: Vec<f64> =
        text.split(',').map(|v| v.trim().parse::<f64>().map_err(|_| invalid())).collect::<Result<_, _>>()?;
    match values[..] {
        [x, y, z] if values.iter().all(|v| v.is_finite()) => Ok(DVec3::new(x, y, z)),
        _ => Err(invalid()),
    }
}

/// The option combinations the contract refuses, checked before anything is read.
fn check_options(args: &Args) -> CliResult {
    if args.pose.is_some() && args.rig.is_none() {
        return Err("--pose needs --rig (the rest rig the pose belongs to)".into());
    }
    if args.show_sweeps && args.rig.is_none() {
        return Err("--show-sweeps needs --rig".into());
    }
    if args.compare && args.pose.is_none() {
        return Err("--compare needs --pose (it draws rest and pose side by side)".into());
    }
    if !(args.zoom.is_finite() && args.zoom >= 1.0) {
        return Err(format!("--zoom must be a finite number of at least 1, not {}", args.zoom).into());
    }
    if args.look_at.is_some() && args.zoom == 1.0 {
        return Err("--look-at centres the close-up of --zoom; give --zoom too".into());
    }
    if !args.out.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
        return Err(format!("{}: the picture is written as PNG; name it .png", args.out.display()).into());
    }
    Ok(())
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    check_options(args)?;
    let (scenes, frame) = build_scenes(args)?;
    let renderer = Renderer::new()?;
    let start = Instant::now();
    let (width, height) = args.size;
    let zoom = (args.zoom > 1.0).then(|| {
        let center = match args.look_at {
            Some(point) => frame.to_local(point).as_vec3(),
            None => union_bounds(&scenes).map_or(glam::Vec3::ZERO, |(lo, hi)| 0.5 * (lo + hi)),
        };
        (center, args.zoom as f32)
    });
    let picture = renderer.render_panels_zoomed(&scenes, args.view, width, height, zoom)?;
    let seconds = start.elapsed().as_secs_f64();
    save_png(&picture, &args.out)?;
    if !quiet {
        out!(
            "rendered {}x{} on {} in {seconds:.3} s -> {}",
            picture.width(),
            picture.height(),
            renderer.context().info.name,
            args.out.display()
        );
    }
    Ok(())
}

/// The panels to draw: the mesh alone; rest or pose with the rig; rest and pose to compare.
/// Everything is drawn in the frame of the rest mesh ([`Frame`]), so that a mesh far from the
/// origin or at a tiny scale draws as it would near the origin at unit size (the renderer is
/// f32).
/// Returns the scenes and the frame they are drawn in.
fn build_scenes(args: &Args) -> Result<(Vec<Scene>, Frame), Box<dyn std::error::Error>> {
    let Some(rig_path) = &args.rig else {
        return Ok(mesh_alone(&Mesh::load(&args.mesh.mesh)?));
    };
    let inputs = match load_inputs(&args.mesh.mesh, rig_path) {
        Err(error) if is_empty_rig(&*error) => {
            // A rig of no sweeps moves nothing and has no sweeps to show: the mesh alone.
            note!("notice: {error}; drawing the mesh as it is");
            return Ok(mesh_alone(&Mesh::load(&args.mesh.mesh)?));
        }
        loaded => loaded?,
    };
    let mesh = &inputs.file.mesh;
    let frame = Frame::of_points(&mesh.positions);
    let (rest, rest_positions) = (frame.local_sweeps(inputs.rig.rest()), frame.local_positions(&mesh.positions));
    let Some(pose_path) = &args.pose else {
        let mut scenes = vec![mesh_scene(mesh, &rest_positions)];
        add_sweeps_if(args.show_sweeps, &mut scenes, &[&rest]);
        return Ok((scenes, frame));
    };
    let posed = inputs.rig.load_pose(pose_path)?;
    let bindings = inputs.rig.bind_mesh(mesh, &inputs.owners, &|_| {});
    let mut deformed = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(inputs.rig.rest(), &posed, &bindings, &mesh.positions, &mut deformed);
    if let Some(i) = deformed.iter().position(|p| !p.is_finite()) {
        return Err(format!("{}: vertex index {i} deforms to a non-finite position", pose_path.display()).into());
    }
    let posed = frame.local_sweeps(&posed);
    let posed_scene = mesh_scene(mesh, &frame.local_positions(&deformed));
    let mut scenes =
        if args.compare { vec![mesh_scene(mesh, &rest_positions), posed_scene] } else { vec![posed_scene] };
    let sweeps: Vec<&[Sweep]> = if args.compare { vec![&rest, &posed] } else { vec![&posed] };
    add_sweeps_if(args.show_sweeps, &mut scenes, &sweeps);
    Ok((scenes, frame))
}

/// The mesh at rest, in its frame, in clay, and the frame.
fn mesh_alone(mesh: &Mesh) -> (Vec<Scene>, Frame) {
    let frame = Frame::of_points(&mesh.positions);
    (vec![mesh_scene(mesh, &frame.local_positions(&mesh.positions))], frame)
}

/// The mesh at `positions` in clay.
fn mesh_scene(mesh: &Mesh, positions: &[DVec3]) -> Scene {
    let mut scene = Scene::new();
    scene.add_mesh(mesh, positions, CLAY);
    scene
}

/// Adds `sweeps[i]` to `scenes[i]` when `show`, sized by the diagonal of all meshes together.
fn add_sweeps_if(show: bool, scenes: &mut [Scene], sweeps: &[&[Sweep]]) {
    if !show {
        return;
    }
    let diagonal = union_bounds(scenes).map_or(1.0, |(lo, hi)| f64::from((hi - lo).length()));
    let style = SweepStyle::for_diagonal(diagonal);
    for (scene, sweeps) in scenes.iter_mut().zip(sweeps) {
        add_sweeps(scene, sweeps, &style);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_zero_is_refused() {
        assert_eq!(parse_size("320x240"), Ok((320, 240)));
        assert_eq!(parse_size("64X32"), Ok((64, 32)));
        assert!(parse_size("0x10").is_err());
        assert!(parse_size("320").is_err());
        assert!(parse_size("ax3").is_err());
        assert_eq!(parse_size("4096x4096"), Ok((4096, 4096)));
        assert_eq!(
            parse_size("8192x8192"),
            Err(
                "the picture size 8192x8192 is 67108864 pixels, over the limit of 16777216 (4096x4096: about 44 bytes \
                 each while drawn)"
                    .to_string()
            )
        );
        assert!(parse_size("16384x1025").is_err());
    }

    #[test]
    fn views_parse_and_steep_elevation_is_refused() {
        assert_eq!(parse_view("90,-20"), Ok(ViewAngles { azimuth: 90.0, elevation: -20.0 }));
        assert!(parse_view("0,95").is_err());
        assert!(parse_view("30").is_err());
    }

    #[test]
    fn out_must_be_png() {
        let args = Args {
            mesh: MeshArg { mesh: "m.obj".into() },
            rig: None,
            pose: None,
            show_sweeps: false,
            size: (1, 1),
            view: ViewAngles::default(),
            compare: false,
            zoom: 1.0,
            look_at: None,
            out: "x.jpg".into(),
        };
        assert!(check_options(&args).is_err());
    }
}
