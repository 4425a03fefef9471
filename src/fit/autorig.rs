//! Rigging a whole mesh in one call: its protrusions (`super::protrusions`) each get one
//! fitted sweep ([`super::fit`]), key 0 at the part's attachment (its rim), with the fit's
//! falloff; the rest of the mesh (the body) stays unowned. The fits run on the mesh with its
//! bit-identical vertices joined (a patch mesh's unwelded seams), so a part's sections close;
//! a part whose fit with the radii of its sections misses its surface by more than [`MAX_RMS`]
//! (a lid's flange, a ring) is no limb and is left out, and reported in [`Autorig::rejected`].
//!
//! Data flow: mesh → protrusions → **fit** per part → rig document.

use std::time::Instant;

use super::protrusions::protrusions;
use super::{Fit, FitError, FitOptions, OptionError, fit};
use crate::mesh::Mesh;
use crate::rig::{FORMAT, RigDocument, VERSION, VertexSelection};

/// How to rig a mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct AutorigOptions {
    /// The shortest protrusion kept, as a fraction of the mesh's bounding-box diagonal
    /// (its persistence: the drop in geodesic distance from its tip to where it meets the
    /// body).
    pub min_length: f64,
    /// The most parts kept, the longest first.
    pub max_parts: usize,
    /// The falloff width W of every sweep in mesh units; `None`: the fit's default, a
    /// fraction of each part's length.
    pub falloff: Option<f64>,
}

impl Default for AutorigOptions {
    fn default() -> AutorigOptions {
        AutorigOptions { min_length: 0.04, max_parts: 16, falloff: None }
    }
}

/// One part found and fitted.
#[derive(Clone, Debug)]
pub struct RiggedPart {
    /// `part0`, `part1`, …, longest first.
    pub name: String,
    /// The part's vertices, increasing.
    pub vertices: Vec<u32>,
    /// Its tip (the vertex farthest from the body's center).
    pub tip: u32,
    /// Its length (persistence), mesh units.
    pub length: f64,
    /// The fitted sweep.
    pub fit: Fit,
    /// Seconds the fit took.
    pub seconds: f64,
}

/// A rigged mesh: its parts, longest first.
#[derive(Clone, Debug)]
pub struct Autorig {
    /// The parts.
    pub parts: Vec<RiggedPart>,
    /// The parts found but left out: their fits were looser than [`MAX_RMS`].
    pub rejected: Vec<Rejected>,
    /// Seconds finding the parts took.
    pub search_seconds: f64,
}

impl Autorig {
    /// The rig file: one sweep per part, owning its vertices.
    pub fn document(&self) -> RigDocument {
        let sweeps = self
            .parts
            .iter()
            .map(|p| p.fit.sweep_document(p.name.clone(), VertexSelection::Indices(p.vertices.clone()), None))
            .collect();
        RigDocument { format: FORMAT.to_string(), version: VERSION, sweeps }
    }
}

/// Finds `mesh`'s protrusions and fits a sweep to each; a part the fit refuses is left out.
/// An empty rig for a mesh with none (a sphere), which `sweepffd deform` and `render` take as
/// leaving the mesh as it is.
pub fn autorig(mesh: &Mesh, options: &AutorigOptions) -> Result<Autorig, FitError> {
    if !(options.min_length.is_finite() && options.min_length > 0.0) {
        return Err(FitError::Options(OptionError::MinLength(options.min_length)));
    }
    // What autorig writes, sweepffd must read: no more parts than a rig may hold.
    if options.max_parts > crate::limits::MAX_SWEEPS {
        return Err(FitError::Options(OptionError::TooManyParts(options.max_parts)));
    }
    super::beyond_rig(mesh, 0..mesh.positions.len() as u32)?;
    let started = Instant::now();
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let diagonal = (hi - lo).length();
    let found = protrusions(mesh, options.min_length * diagonal, options.max_parts);
    let search_seconds = started.elapsed().as_secs_f64();
    let fit_options = FitOptions { falloff: options.falloff, ..FitOptions::default() };
    // Fitted across unwelded seams (a patch mesh's), so that a part's sections close.
    let welded = welded(mesh);
    let fitted_on = welded.as_ref().unwrap_or(mesh);
    let mut parts = Vec::new();
    let mut rejected = Vec::new();
    for protrusion in found {
        let started = Instant::now();
        let Ok(fitted) = fit(fitted_on, &protrusion.vertices, &fit_options) else { continue };
        let sections = fitted.sections_quality();
        if sections.rms_d > MAX_RMS {
            rejected.push(Rejected { tip: protrusion.tip, vertices: protrusion.vertices.len(), rms_d: sections.rms_d });
            continue;
        }
        parts.push(RiggedPart {
            name: format!("part{}", parts.len()),
            vertices: protrusion.vertices,
            tip: protrusion.tip,
            length: protrusion.length,
            fit: fitted,
            seconds: started.elapsed().as_secs_f64(),
        });
    }
    Ok(Autorig { parts, rejected, search_seconds })
}

/// A part found whose fit is looser than [`MAX_RMS`]: a flange, a ring or a flat panel, no
/// limb.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rejected {
    /// Its tip.
    pub tip: u32,
    /// Its vertex count.
    pub vertices: usize,
    /// Its fit's RMS |d| over the mean radius, with the radii sampled from its key sections.
    pub rms_d: f64,
}

/// A found part whose fitted sweep, with the radii sampled from its key sections
/// ([`Fit::sections_quality`]), misses its surface by more than this RMS |d| (over the mean
/// radius) is no limb and is left out of the rig: its sections are not those of a tube, though
/// radii fitted to its vertices by least squares may follow them more closely.
pub const MAX_RMS: f64 = 0.35;

/// `mesh` with the vertices at bit-identical positions joined in its faces (the vertices stay,
/// those joined away left without faces); `None` when no two are.
fn welded(mesh: &Mesh) -> Option<Mesh> {
    let weld = crate::mesh::weld::weld(&mesh.positions);
    if weld.iter().enumerate().all(|(v, &w)| w as usize == v) {
        return None;
    }
    let mut faces = crate::mesh::Faces::new();
    for face in mesh.faces.iter() {
        let joined: Vec<u32> = face.iter().map(|&v| weld[v as usize]).collect();
        let distinct = joined.iter().enumerate().all(|(i, v)| !joined[..i].contains(v));
        if distinct {
            faces.push(&joined);
        }
    }
    Mesh::from_parts(mesh.positions.clone(), faces, Vec::new()).ok()
}
