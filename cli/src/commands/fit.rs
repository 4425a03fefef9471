//! `sweepffd fit`: fit a control sweep to a part of a mesh (§3, Fig. 3) and write it as a rig.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::DVec3;

use super::CliResult;
use super::args::{MeshArg, RotationArg};
use super::flags::fit_error;
use sweepffd::atomic_file::write_atomically;
use sweepffd::fit::{DEFAULT_FALLOFF_FRACTION, Fit, FitOptions, fit};
use sweepffd::mesh::Mesh;
use sweepffd::rig::{FORMAT, LinkKind, ParentLink, Rig, RigDocument, VERSION, VertexSelection};

/// How a fitted sweep hangs from its parent (§5).
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum LinkKindArg {
    /// The first key is bound to the parent.
    Branch,
    /// The first and last keys are bound to the parent.
    Loop,
}

impl From<LinkKindArg> for LinkKind {
    fn from(kind: LinkKindArg) -> LinkKind {
        match kind {
            LinkKindArg::Branch => LinkKind::Branch,
            LinkKindArg::Loop => LinkKind::Loop,
        }
    }
}

/// The arguments of `sweepffd fit`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub mesh: MeshArg,
    /// A face group of the mesh that makes up the part; repeat for several.
    #[arg(long = "group")]
    pub groups: Vec<String>,
    /// A file of the part's zero-based vertex indices (JSON array, or separated by spaces or commas).
    #[arg(long)]
    pub indices: Option<PathBuf>,
    /// First guess at the axis, a polyline "x0,y0,z0;x1,y1,z1;..." (default: the part's skeleton, from where it is attached to its tip).
    #[arg(long, allow_hyphen_values = true)]
    pub axis: Option<String>,
    /// Keys placed along the axis before any is inserted.
    #[arg(long, default_value_t = 6)]
    pub keys: usize,
    /// Radii M sampled per key.
    #[arg(long, default_value_t = 32)]
    pub radii: usize,
    /// The most keys insertion may reach.
    #[arg(long, default_value_t = 24)]
    pub max_keys: usize,
    /// A knot interval whose RMS |d| exceeds this fraction of the mean radius gets a key inserted.
    #[arg(long, default_value_t = 0.05)]
    pub tolerance: f64,
    /// Falloff width W in mesh units over which the sweep's deformation fades at the part's boundary; 0: a hard boundary (default: 0.3 of the part's length).
    #[arg(long, allow_negative_numbers = true)]
    pub falloff: Option<f64>,
    /// The sweep's name (default: the groups joined by "+", or the indices file's stem).
    #[arg(long)]
    pub name: Option<String>,
    /// How the sweep interpolates its key rotations.
    #[arg(long, value_enum, default_value_t)]
    pub rotation_interpolation: RotationArg,
    /// Hang the sweep from this sweep of the rig (--append-to) in the hierarchy.
    #[arg(long)]
    pub parent: Option<String>,
    /// How the sweep hangs from --parent.
    #[arg(long, value_enum, default_value_t = LinkKindArg::Branch)]
    pub kind: LinkKindArg,
    /// Where to write the rig.
    #[arg(long)]
    pub out: PathBuf,
    /// Add the sweep to this rig's sweeps instead of starting a new rig (may equal --out).
    #[arg(long)]
    pub append_to: Option<PathBuf>,
}

impl Args {
    /// The fit options of the arguments (the axis is parsed separately).
    fn options(&self) -> FitOptions {
        let Args { keys, radii, max_keys, tolerance, falloff, .. } = *self;
        FitOptions { axis: None, keys, radii, max_keys, tolerance, falloff }
    }
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    let mesh = Mesh::load(&args.mesh.mesh)?;
    let (selection, vertices) = select(&mesh, args)?;
    let name = args.name.clone().unwrap_or_else(|| default_name(args));
    let mut options = args.options();
    if let Some(axis) = &args.axis {
        options.axis = Some(parse_axis(axis)?);
    }
    let started = Instant::now();
    let fitted = fit(&mesh, &vertices, &options).map_err(|e| {
        let e = fit_error(&e);
        format!("{}: fitting sweep {name:?}: {e}; nothing was written", args.mesh.mesh.display())
    })?;
    let elapsed = started.elapsed().as_secs_f64();

    let mut document = match &args.append_to {
        Some(path) => RigDocument::load(path)?,
        None => RigDocument {
            format: FORMAT.to_string(),
            version: VERSION,
            rotation_interpolation: None,
            sweeps: Vec::new(),
        },
    };
    if document.sweeps.iter().any(|s| s.name == name) {
        let file = args.append_to.as_deref().unwrap_or(&args.out).display();
        return Err(format!("{file}: the rig already has a sweep named {name:?}; choose another with --name").into());
    }
    let parent = args.parent.clone().map(|sweep| ParentLink { sweep, kind: args.kind.into() });
    let mut sweep = fitted.sweep_document(name.clone(), selection, parent);
    sweep.rotation_interpolation = args.rotation_interpolation.field();
    document.sweeps.push(sweep);
    // The written rig must load and own the mesh's vertices without conflict.
    let rig = Rig::from_document(&document, args.append_to.clone())?;
    rig.owners(&mesh, &args.mesh.mesh.display().to_string())?;
    let text = document.try_to_json(&args.out)?;
    write_atomically(&args.out, |out| out.write_all(text.as_bytes()))
        .map_err(|e| format!("cannot write {}: {e}", args.out.display()))?;
    print_report(&name, &fitted, &options, elapsed);
    if !quiet {
        out!("wrote {} ({} sweeps)", args.out.display(), document.sweeps.len());
    }
    Ok(())
}

/// The selection written into the rig and the vertices it names.
fn select(mesh: &Mesh, args: &Args) -> Result<(VertexSelection, Vec<u32>), Box<dyn std::error::Error>> {
    match (&args.indices, args.groups.is_empty()) {
        (Some(_), false) => Err("give either --group or --indices, not both".into()),
        (None, true) => Err("say which part to fit with --group or --indices".into()),
        (Some(path), true) => {
            let indices = read_indices(path)?;
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= mesh.positions.len()) {
                let count = mesh.positions.len();
                return Err(format!(
                    "{}: vertex {bad} is out of range: {} has {count} vertices",
                    path.display(),
                    args.mesh.mesh.display()
                )
                .into());
            }
            Ok((VertexSelection::Indices(indices.clone()), indices))
        }
        (None, false) => {
            let mut vertices = Vec::new();
            for group in &args.groups {
                let Some(members) = mesh.group_vertices(group) else {
                    let available = sweepffd::names::listed(mesh.groups.iter().map(|g| g.name.as_str()));
                    let group = sweepffd::names::shown(group);
                    return Err(
                        format!("{}: no group {group:?} (groups: {available})", args.mesh.mesh.display()).into()
                    );
                };
                vertices.extend(members);
            }
            Ok((VertexSelection::Groups(args.groups.clone()), vertices))
        }
    }
}

/// Zero-based vertex indices from a file: a JSON array, or integers separated by white space
/// or commas.
fn read_indices(path: &Path) -> Result<Vec<u32>, String> {
    let text = sweepffd::limits::read_input_text(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut indices: Vec<u32> = if text.trim_start().starts_with('[') {
        serde_json::from_str(&text)
            .map_err(|e| format!("{}: not a JSON array of vertex indices: {e}", path.display()))?
    } else {
        text.split(|c: char| c.is_whitespace() || c == ',')
            .filter(|token| !token.is_empty())
            .map(|token| token.parse().map_err(|_| format!("{}: {token:?} is not a vertex index", path.display())))
            .collect::<Result<_, _>>()?
    };
    if indices.is_empty() {
        return Err(format!("{}: lists no vertices", path.display()));
    }
    indices.sort_unstable();
    indices.dedup();
    Ok(indices)
}

/// `x0,y0,z0;x1,y1,z1;…` as points.
fn parse_axis(text: &str) -> Result<Vec<DVec3>, String> {
    let points = text
        .split(';')
        .filter(|p| !p.trim().is_empty())
        .enumerate()
        .map(|(i, point)| {
            let coordinates: Vec<f64> = point
                .split(',')
                .map(|c| c.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("--axis: point {i} ({point:?}) is not three numbers x,y,z"))?;
            match coordinates[..] {
                [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => Ok(DVec3::new(x, y, z)),
                _ => Err(format!("--axis: point {i} ({point:?}) is not three finite numbers x,y,z")),
            }
        })
        .collect::<Result<Vec<_>, _>>()?;
    if points.len() < 2 {
        return Err(format!("--axis needs at least two points \"x0,y0,z0;x1,y1,z1\", found {}", points.len()));
    }
    Ok(points)
}

fn default_name(args: &Args) -> String {
    match &args.indices {
        Some(path) => path.file_stem().map_or("part".to_string(), |s| s.to_string_lossy().into_owned()),
        None => args.groups.join("+"),
    }
}

fn print_report(name: &str, fitted: &Fit, options: &FitOptions, seconds: f64) {
    let q = &fitted.quality;
    let placed = fitted.steps.get(1).map_or(fitted.keys.len(), |s| s.keys.len());
    out!(
        "fit {name:?}: {} vertices, {} keys ({placed} placed, {} inserted), {} radii per key, {seconds:.3} s",
        q.vertices,
        fitted.keys.len(),
        fitted.keys.len() - placed,
        options.radii
    );
    out!(
        "  |d| / mean radius ({:.6}): max {:.2}%, RMS {:.2}%; {}",
        q.mean_radius,
        100.0 * q.max_d,
        100.0 * q.rms_d,
        if q.without_root == 0 {
            "every vertex binds with a root".to_string()
        } else {
            format!("{} vertices lie beyond an end", q.without_root)
        }
    );
    let last = fitted.keys.len() - 1;
    let [near_first, near_last] = fitted.rim;
    let order = match (&options.axis, near_first + near_last > 0.0) {
        (Some(_), _) => "key 0 at the first end of --axis",
        (None, true) if near_first > near_last => "key 0 at the attached end",
        (None, true) => "as much rim at both ends: key 0 where the skeleton starts",
        (None, false) => "no rim: key 0 where the skeleton starts",
    };
    out!(
        "  rim (where the part meets the rest of the mesh): {near_first:.6} near key 0, {near_last:.6} near key {last}; {order}"
    );
    let source = match options.falloff {
        Some(_) => "--falloff".to_string(),
        None => format!("default: {DEFAULT_FALLOFF_FRACTION} of the part's length"),
    };
    if fitted.falloff > 0.0 {
        out!("  falloff {:.6} ({source})", fitted.falloff);
    } else {
        out!("  falloff 0: a hard boundary ({source})");
    }
    for (k, section) in fitted.sections.iter().enumerate() {
        if !section.cut {
            out!("  key {k}: its plane misses the part; radii interpolated from the neighbouring keys");
            continue;
        }
        if section.several_crossings > 0 {
            out!(
                "  key {k}: section not star-shaped around its center: {} of {} rays cross the boundary more than once; outermost crossing taken",
                section.several_crossings,
                options.radii
            );
        }
        if section.borrowed {
            out!(
                "  key {k}: partial section (its plane leaves the part through the part's open rim); center extrapolated from the neighbouring keys, rays that miss take the nearest complete key's radii"
            );
        } else if section.missed > 0 {
            out!(
                "  key {k}: {} of {} rays meet no boundary (open section); their radii are interpolated",
                section.missed,
                options.radii
            );
        }
    }
    for step in &fitted.steps {
        let q = &step.quality;
        out!("  step: {}: max {:.2}%, RMS {:.2}%", step.label, 100.0 * q.max_d, 100.0 * q.rms_d);
    }
}
