//! `sweepffd autorig`: find a mesh's protrusions and fit one control sweep to each
//! ([`sweepffd::fit::autorig`]), writing the rig.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use serde::Serialize;

use super::CliResult;
use super::args::{MeshArg, RotationArg};
use super::flags::fit_error;
use sweepffd::atomic_file::write_atomically;
use sweepffd::fit::autorig::{AutorigOptions, MIN_VERTICES, autorig};
use sweepffd::mesh::Mesh;

/// The arguments of `sweepffd autorig`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub mesh: MeshArg,
    /// Where to write the rig.
    #[arg(long)]
    pub out: PathBuf,
    /// The shortest protrusion kept, as a fraction of the mesh's bounding-box diagonal.
    #[arg(long, default_value_t = 0.04)]
    pub min_length: f64,
    /// The most parts kept, the longest first.
    #[arg(long, default_value_t = 16)]
    pub max_parts: usize,
    /// Falloff width W of every sweep in mesh units; 0: hard boundaries (default: 0.3 of each part's length).
    #[arg(long, allow_negative_numbers = true)]
    pub falloff: Option<f64>,
    /// How every sweep interpolates its key rotations.
    #[arg(long, value_enum, default_value_t)]
    pub rotation_interpolation: RotationArg,
    /// Print what was found as JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Report {
    mesh: String,
    parts: Vec<PartReport>,
    /// The parts found whose sections are no tube's, left out of the rig.
    left_out: Vec<LeftOut>,
    /// Limbs left out at `--max-parts` as mirror twins of the next limb found.
    twins_left_out: usize,
    seconds: f64,
}

#[derive(Serialize)]
struct LeftOut {
    vertices: usize,
    tip: u32,
    /// RMS |d| over the mean radius with the radii sampled from its sections; null for a part
    /// too small to be a limb, which is not fitted, and for a folded fit.
    sections_rms_d: Option<f64>,
    /// For a fit whose keys fold back: its knot intervals that step backwards, of all of them.
    folded: Option<[usize; 2]>,
    /// For a fit whose every key section is open (a sheet, no tube): its keys.
    open_keys: Option<usize>,
}

#[derive(Serialize)]
struct PartReport {
    name: String,
    /// The sweep it hangs from (the previous link of its limb's chain), if any.
    parent: Option<String>,
    vertices: usize,
    tip: u32,
    length: f64,
    keys: usize,
    /// RMS and largest |d| over the mean radius at its own vertices.
    rms_d: f64,
    max_d: f64,
    /// The vertices its sweep was fitted to (a chain's link: its own and its neighbours' within
    /// the overlap, welded seam copies once) and the RMS |d| there.
    fitted_vertices: usize,
    fitted_rms_d: f64,
    /// Its key sections that are not star-shaped (rays from the section's center crossing its
    /// boundary more than once): a fit target of 15% rather than 10% RMS |d|.
    sections_not_star_shaped: usize,
    /// The RMS |d| over the mean radius its fit aims within (0.10, or 0.15 where some sections
    /// are not star-shaped).
    target: f64,
    without_root: usize,
    seconds: f64,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    let started = Instant::now();
    let mesh = Mesh::load(&args.mesh.mesh)?;
    let file = args.mesh.mesh.display();
    if mesh.positions.is_empty() || mesh.faces.triangles().next().is_none() {
        return Err(format!("{file}: the mesh has no faces; nothing to rig").into());
    }
    if let Some(v) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(format!("{file}: vertex {v} has a non-finite coordinate; nothing was written").into());
    }
    let options = AutorigOptions { min_length: args.min_length, max_parts: args.max_parts, falloff: args.falloff };
    let rigged = autorig(&mesh, &options).map_err(|e| format!("{file}: {}; nothing was written", fit_error(&e)))?;
    let mut document = rigged.document();
    document.rotation_interpolation = args.rotation_interpolation.field();
    let text = document.try_to_json(&args.out)?;
    write_atomically(&args.out, |out| out.write_all(text.as_bytes()))
        .map_err(|e| format!("cannot write {}: {e}", args.out.display()))?;
    let seconds = started.elapsed().as_secs_f64();
    let parts: Vec<PartReport> = rigged
        .parts
        .iter()
        .map(|p| PartReport {
            name: p.name.clone(),
            parent: p.parent.clone(),
            vertices: p.vertices.len(),
            tip: p.tip,
            length: p.length,
            keys: p.fit.keys.len(),
            rms_d: p.quality.rms_d,
            max_d: p.quality.max_d,
            fitted_vertices: p.fit.quality.vertices,
            fitted_rms_d: p.fit.quality.rms_d,
            sections_not_star_shaped: p.sections_not_star_shaped(),
            target: p.target(),
            without_root: p.quality.without_root,
            seconds: p.seconds,
        })
        .collect();
    if args.json {
        let left_out = rigged
            .rejected
            .iter()
            .map(|r| LeftOut {
                vertices: r.vertices,
                tip: r.tip,
                sections_rms_d: r.rms_d,
                folded: r.folded.map(|f| [f.backwards, f.intervals]),
                open_keys: r.open,
            })
            .collect();
        out!(
            "{}",
            serde_json::to_string(&Report {
                mesh: file.to_string(),
                parts,
                left_out,
                twins_left_out: rigged.twins_left_out,
                seconds
            })?
        );
        return Ok(());
    }
    for r in &rigged.rejected {
        let why = match (r.rms_d, r.folded) {
            (Some(rms_d), _) if let Some(keys) = r.open => format!(
                "its sections are no tube's: all {keys} key sections are open, a sheet (RMS |d| {:.0}% of the \
                 mean radius with their radii)",
                100.0 * rms_d
            ),
            // Sections of a flat part (a sheet) have next to no area: their mean radius is
            // near zero, and |d| over it says nothing more.
            (Some(rms_d), _) if rms_d >= FLAT => format!(
                "its sections are no tube's: they have next to no area, a flat part (RMS |d| over {:.0}% of \
                 the mean radius with their radii)",
                100.0 * FLAT
            ),
            (Some(rms_d), _) => format!(
                "its sections are no tube's (RMS |d| {:.0}% of the mean radius with their radii)",
                100.0 * rms_d
            ),
            (None, Some(folds)) => format!(
                "its fitted keys fold back on each other ({} of {} knot intervals run backwards)",
                folds.backwards, folds.intervals
            ),
            (None, None) => format!("a limb has at least {MIN_VERTICES} vertices"),
        };
        note!("notice: {file}: left out a part of {} vertices at tip vertex {}: {why}", r.vertices, r.tip);
    }
    if rigged.twins_left_out > 0 {
        note!(
            "notice: {file}: left out {} limb(s) at --max-parts {}: mirror twins of the next limb found, \
             for which there was no room (a pair is kept or left out together)",
            rigged.twins_left_out,
            args.max_parts
        );
    }
    match (parts.is_empty() && rigged.twins_left_out == 0, rigged.rejected.len()) {
        (true, 0) => note!(
            "notice: {file}: found no protrusion longer than --min-length {}; wrote an empty rig",
            args.min_length
        ),
        (true, left_out) => {
            note!("notice: {file}: left out every protrusion found ({left_out}); wrote an empty rig")
        }
        _ => {}
    }
    for p in &parts {
        let parent = p.parent.as_ref().map(|parent| format!(" (child of {parent})")).unwrap_or_default();
        let crescents = match p.sections_not_star_shaped {
            0 => String::new(),
            n => format!(" ({n} of its {} sections not star-shaped)", p.keys),
        };
        // A link fitted with its neighbours' vertices too says how closely it follows them all.
        let fitted = if p.fitted_rms_d != p.rms_d {
            format!(" ({:.2}% at the {} vertices it was fitted to)", 100.0 * p.fitted_rms_d, p.fitted_vertices)
        } else {
            String::new()
        };
        out!(
            "{}{parent}: {} vertices, tip vertex {}, length {:.4}, {} keys, RMS |d| {:.2}%{fitted}, max {:.1}% of the mean radius{crescents}, {:.3} s",
            p.name,
            p.vertices,
            p.tip,
            p.length,
            p.keys,
            100.0 * p.rms_d,
            100.0 * p.max_d,
            p.seconds
        );
    }
    let loose: Vec<String> = rigged
        .parts
        .iter()
        .filter(|p| !p.within_target())
        .map(|p| format!("{} ({:.1}% of {:.0}%)", p.name, 100.0 * p.quality.rms_d, 100.0 * p.target()))
        .collect();
    if !loose.is_empty() {
        note!(
            "notice: {file}: {} of {} sweeps fit looser than their target RMS |d| (10%, 15% where sections are not \
             star-shaped): {}",
            loose.len(),
            parts.len(),
            loose.join(", ")
        );
    }
    if !quiet {
        out!("wrote {} ({} sweeps) in {seconds:.3} s", args.out.display(), parts.len());
    }
    Ok(())
}

/// A part left out whose sections miss it by at least this RMS |d| over their mean radius is
/// reported as flat: its sections have next to no area (a sheet, such as a drawing's outline
/// meshed in a plane: 21,685 times its mean radius).
const FLAT: f64 = 10.0;
