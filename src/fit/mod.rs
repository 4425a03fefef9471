//! Fitting control sweeps to mesh parts (§3, Fig. 3): the construction step the paper does by
//! hand, in one call.
//!
//! Data flow: mesh part → **fit** → rig → sweep → … (the fitted keys go into a rig file).
//! [`autorig`] finds the parts themselves (a mesh's protrusions, `protrusions`) and fits
//! one sweep to each.
//!
//! [`fit`] follows the paper's steps:
//! 1. **Axis.** The user's polyline, or else the part's skeleton (`skeleton`): the
//!    centroids of its level sets of geodesic distance from the loop where it is attached
//!    (its rim), from its attached end to its tip, so that the first guess already follows a
//!    curved or L-shaped part however it was cut or placed (the principal axis of the
//!    vertices, `axis::principal_axis`, only where no skeleton can be found). A coarse part
//!    (fewer vertices than the first keys have radii, such as spot's legs of 46–83 vertices)
//!    is fitted from four starts: the skeleton and its points before centering, each with the
//!    keys' planes held normal to it or following the fit's own sweep, keeping the tightest
//!    by the worse of its RMS |d| at the vertices and at the triangles' centroids (each start
//!    costs milliseconds there, and the fit of a part so coarse swings by several percent of
//!    its radius with small changes of its first guess; scored at its vertices alone, the
//!    choice would favour radii that wave between them; a start whose keys fold back or zigzag
//!    through the part, `key_path::astray`, is kept only where every start's keys do). Key 0's plane
//!    is the plane of that loop; θ = 0 comes from the part's shape
//!    (`frames::reference_direction`), so the fit of a rigidly moved part is the moved fit.
//! 2. **Rough sweep** (Fig. 3a): circles along the axis enclosing every vertex, recorded as
//!    the first [`FitStep`].
//! 3. **Key sections** (Fig. 3b, c): `keys` planes along the axis, normal to it, cut the
//!    part's faces (`section::cut`). Each key's section is the smallest closed contour around
//!    the key's center (or the nearest contour) plus the contours as near as that one reaches
//!    and the closed contours separated from those by gaps no wider than that reach (a foot's
//!    toes, a hand's fingers: one section around them all, `section::around`); a ray of such
//!    a section that passes through a gap takes interpolated radii and leaves the section
//!    complete; its center is their area centroid, or where rays from that cross the boundary
//!    more than once the point inside from which they see most of it (`star`), and M radii
//!    are sampled from that center to the crossing of each ray (`radii::sample`). A ray that
//!    still crosses the boundary more than once (a section that is not star-shaped around any
//!    center the search finds) is counted in [`SectionReport::several_crossings`] and takes
//!    the mean distance of the boundary around it (`hidden`); a ray that meets nothing takes the value
//!    interpolated between its neighbours ([`SectionReport::missed`]). A plane that would
//!    leave the part through its rim (an oblique cut) is tilted towards the rim's plane or
//!    moved away from it until its section is complete; only where no such plane is found
//!    does the key borrow its center and radii from its complete neighbours.
//! 4. **Re-centering.** The keys move to their sections' centers; the normals follow the
//!    tangent C′(u_i) of the sweep through the new centers; frames are carried along by
//!    parallel transport (θ = 0 does not twist between keys); the sections are cut again.
//! 5. **End keys** sit on planes just past the part's extreme vertices (1% of its length),
//!    so ⟨v − C(t), N(t)⟩ changes sign on [0, 1] and every vertex binds with a root; they
//!    take their radii from the first section found a little inside.
//! 6. **Key insertion.** The part's vertices are bound; in every knot interval whose RMS |d|
//!    exceeds `tolerance` × the mean radius a key is inserted at the interval's middle, and
//!    all keys are re-centered again, until no interval is loose, the fit stops improving,
//!    or `max_keys` is reached.
//! 7. **Least-squares radii** (`least_squares`): with the centers and frames fixed, each
//!    vertex's binding (θ, t) and its distance from the axis are fixed, and d is linear in the
//!    key radii, so the radii that minimise Σ d² are found by linear least squares (with a
//!    ridge towards the sampled radii, for the radii no vertex sees) and kept where they
//!    tighten the fit ([`Fit::sections_quality`] keeps the fit before them). A part with fewer
//!    than 4 vertices per radius is fitted at its edges' midpoints too, and the result is kept
//!    only where it does not loosen the fit at its triangles' centroids, which it was not
//!    fitted to: otherwise the radii of a coarse part pass through its vertices and bulge
//!    between them.
//! 8. **Key 0 at the attached end** (`attached`): the part's rim, where it meets the rest of
//!    the mesh, is measured towards each end of the sweep by its edges' parameter t; when the
//!    rim nearer the last key is strictly longer, the sweep is traversed from its other end
//!    (the same surface, so the fit is unchanged), so that key 0 sits where the part is
//!    attached (a leg's hip, an ear's base). The skeleton already starts at the longest rim
//!    loop, so this turns only a part whose rim the fit measures otherwise; a part with no
//!    rim, or as much at both ends, keeps the skeleton's order. A user's axis keeps its own order: the user's axis
//!    order wins over the rim.
//! 9. **Falloff** ([`falloff`]): the width W of the band over which the sweep's deformation
//!    fades at the part's boundary, the user's or a fraction of the part's length.

pub mod autorig;
mod disjoint_sets;
mod error;
pub mod falloff;
pub mod part;
pub mod quality;
mod refine;

internal_mod! {
    alike;
    attached;
    axis;
    body;
    chain;
    frames;
    geodesic;
    grid;
    hanging;
    hidden;
    key_path;
    least_squares;
    limb;
    mirror;
    nearest_triangle;
    protrusions;
    radii;
    ray_fan;
    section;
    select;
    skeleton;
    star;
    twins;
}

use glam::DVec3;

pub use error::{FitError, OptionError};
pub use falloff::DEFAULT_FALLOFF_FRACTION;
pub use part::Part;
pub use quality::FitQuality;
pub use select::{connected_to, largest_connected};

use crate::limits::{MAX_KEYS_PER_SWEEP, MAX_RADII_PER_KEY};
use crate::mesh::Mesh;
use crate::rig::{KeyDocument, ParentLink, SweepDocument, VertexSelection};
use crate::sweep::Key;
pub(crate) use refine::KeyCount;

/// How to fit a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct FitOptions {
    /// The first guess at the axis, a polyline from the first end of the part to the other;
    /// key 0 sits at its first point's end, whatever the part's rim. `None`: the part's
    /// skeleton (`skeleton`), from the end where the part is attached to its tip.
    pub axis: Option<Vec<DVec3>>,
    /// Keys placed along the axis before any insertion (at least 2, at most
    /// [`MAX_KEYS_PER_SWEEP`]).
    pub keys: usize,
    /// Radii M per key (at least 3, at most [`MAX_RADII_PER_KEY`]).
    pub radii: usize,
    /// The most keys insertion may reach (at most [`MAX_KEYS_PER_SWEEP`]).
    pub max_keys: usize,
    /// A knot interval whose RMS |d| exceeds this fraction of the mean radius is loose.
    pub tolerance: f64,
    /// The falloff width W in mesh units (0: a hard boundary); `None`:
    /// [`DEFAULT_FALLOFF_FRACTION`] of the part's length (the chord length of the fitted key
    /// centers).
    pub falloff: Option<f64>,
}

impl Default for FitOptions {
    fn default() -> FitOptions {
        FitOptions { axis: None, keys: 6, radii: 32, max_keys: 24, tolerance: 0.05, falloff: None }
    }
}

impl FitOptions {
    /// Checks the keys and radii against what a part of `vertices` vertices determines: at
    /// most the larger of the default and `vertices` each (the keys of the default
    /// [`FitOptions::max_keys`]), so that a fit's time and memory follow its part.
    fn check_for_part(&self, vertices: usize) -> Result<(), FitError> {
        let defaults = FitOptions::default();
        let checks = [
            ("keys", self.keys, defaults.max_keys),
            ("max_keys", self.max_keys, defaults.max_keys),
            ("radii", self.radii, defaults.radii),
        ];
        for (field, value, default) in checks {
            let most = default.max(vertices);
            if value > most {
                return Err(FitError::Options(OptionError::BeyondPart { field, value, most, vertices }));
            }
        }
        Ok(())
    }

    fn check(&self) -> Result<(), FitError> {
        let fail = |error: OptionError| Err(FitError::Options(error));
        if self.keys < 2 {
            return fail(OptionError::TooFewKeys(self.keys));
        }
        if self.radii < 3 {
            return fail(OptionError::TooFewRadii(self.radii));
        }
        if self.radii > MAX_RADII_PER_KEY {
            return fail(OptionError::TooManyRadii(self.radii));
        }
        if self.keys > MAX_KEYS_PER_SWEEP {
            return fail(OptionError::TooManyKeys(self.keys));
        }
        if self.max_keys > MAX_KEYS_PER_SWEEP {
            return fail(OptionError::TooManyMaxKeys(self.max_keys));
        }
        if self.max_keys < self.keys {
            return fail(OptionError::MaxKeysBelowKeys { max_keys: self.max_keys, keys: self.keys });
        }
        if !(self.tolerance > 0.0 && self.tolerance.is_finite()) {
            return fail(OptionError::Tolerance(self.tolerance));
        }
        if let Some(falloff) = self.falloff.filter(|w| !(w.is_finite() && *w >= 0.0)) {
            return fail(OptionError::Falloff(falloff));
        }
        Ok(())
    }
}

/// How one key's section met the rays that sampled its radii.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SectionReport {
    /// Whether the key's plane cut the part; if not, the key took its radii from its
    /// neighbours.
    pub cut: bool,
    /// Whether the section's boundary is open: the plane leaves the part through its rim
    /// (where the part meets the rest of the mesh), so the section is partial.
    pub open: bool,
    /// Rays that crossed the section's boundary more than once and took the outermost crossing.
    pub several_crossings: usize,
    /// Rays that met no boundary and took interpolated radii.
    pub missed: usize,
    /// Whether the section was partial or missing, so the key took its center from the line
    /// through the nearest complete keys and its radii from the nearest complete key.
    pub borrowed: bool,
}

impl SectionReport {
    /// A plane that missed the part.
    pub const MISSED: SectionReport =
        SectionReport { cut: false, open: false, several_crossings: 0, missed: 0, borrowed: false };
}

/// One stage of the fit, for showing the steps of Fig. 3.
#[derive(Clone, Debug, PartialEq)]
pub struct FitStep {
    /// What the step did.
    pub label: String,
    /// The keys after the step.
    pub keys: Vec<Key>,
    /// Their fit.
    pub quality: FitQuality,
}

/// A fitted sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// The keys, from the end where the part is attached to the rest of the mesh (see
    /// [`Fit::rim`]; with a user's axis, from its first point's end) to the other.
    pub keys: Vec<Key>,
    /// How tightly they fit the part.
    pub quality: FitQuality,
    /// How each key's section met its rays.
    pub sections: Vec<SectionReport>,
    /// Every stage, from the rough sweep to the final one, each with its keys in the order of
    /// [`Fit::keys`].
    pub steps: Vec<FitStep>,
    /// The length of the part's rim (where it is attached to the rest of the mesh,
    /// [`Part::rim`]) nearer key 0 and nearer the last key, mesh units
    /// (`attached::rim_lengths`).
    pub rim: [f64; 2],
    /// The falloff width W, mesh units (0: a hard boundary).
    pub falloff: f64,
}

impl Fit {
    /// The fit with the radii sampled from the key sections, before they were fitted to the
    /// vertices by least squares (`least_squares`): how nearly the part is a tube whose
    /// sections the keys describe. [`Fit::quality`] where least squares did not tighten it.
    pub fn sections_quality(&self) -> FitQuality {
        match &self.steps[..] {
            [.., before, last] if last.label == refine::LEAST_SQUARES_STEP => before.quality,
            _ => self.quality,
        }
    }

    /// Whether its last step fitted the radii by least squares (the step was kept).
    pub(crate) fn least_squares_kept(&self) -> bool {
        self.steps.last().is_some_and(|step| step.label == refine::LEAST_SQUARES_STEP)
    }

    /// The fit of the part of `mesh` made of `vertices` (those it was fitted to), its radii
    /// fitted again to the part's surface with their second differences smoothed
    /// ([`refine::smoothed`]), where its radii were not fitted by least squares (that loosened
    /// its triangles' centroids) and this tightens it; `None` otherwise.
    pub(crate) fn smoothed(&self, mesh: &Mesh, vertices: &[u32]) -> Result<Option<Fit>, FitError> {
        if self.least_squares_kept() {
            return Ok(None);
        }
        let part = Part::new(mesh, vertices);
        let Some((keys, measured)) = refine::smoothed(&part, &self.keys)? else { return Ok(None) };
        let mut steps = self.steps.clone();
        steps.push(FitStep {
            label: refine::LEAST_SQUARES_STEP.to_string(),
            keys: keys.clone(),
            quality: measured.quality,
        });
        Ok(Some(Fit { keys, quality: measured.quality, steps, ..self.clone() }))
    }

    /// The fitted sweep as a rig file writes it: named `name`, owning `selection`, hanging
    /// from `parent` if given, knots by chord length, with the fit's falloff (absent when 0).
    pub fn sweep_document(
        &self,
        name: String,
        selection: VertexSelection,
        parent: Option<ParentLink>,
    ) -> SweepDocument {
        SweepDocument {
            name,
            vertices: Some(selection),
            keys: self.keys.iter().map(KeyDocument::from).collect(),
            knots: None,
            parent,
            falloff: (self.falloff > 0.0).then_some(self.falloff),
            rotation_interpolation: None,
        }
    }
}

/// `Err` naming the first of `vertices` (of `mesh`) with a coordinate beyond what a rig may
/// hold.
fn beyond_rig(mesh: &Mesh, vertices: impl Iterator<Item = u32>) -> Result<(), FitError> {
    for vertex in vertices {
        let p = mesh.positions[vertex as usize];
        if let Some(value) = p.to_array().into_iter().find(|c| c.abs() > crate::limits::MAX_RIG_COORDINATE) {
            return Err(FitError::BeyondRig { vertex, value });
        }
    }
    Ok(())
}

/// Fits a control sweep to the part of `mesh` made of `vertices` (see the module docs).
pub fn fit(mesh: &Mesh, vertices: &[u32], options: &FitOptions) -> Result<Fit, FitError> {
    fit_with(mesh, vertices, options, 0.0, KeyCount::Inserted)
}

/// [`fit`], where a least-squares fit of the radii is not kept, fitting them once more with
/// their second differences weighted by `smoothing` (a fraction of the normal matrix's mean
/// diagonal; 0 for none), its keys counted as `key_count` says.
pub(crate) fn fit_with(
    mesh: &Mesh,
    vertices: &[u32],
    options: &FitOptions,
    smoothing: f64,
    key_count: KeyCount,
) -> Result<Fit, FitError> {
    // A counted fit's keys are checked as a fit's most keys are.
    let counted = match key_count {
        KeyCount::Exactly(keys) => FitOptions { keys: options.keys.min(keys), max_keys: keys, ..options.clone() },
        KeyCount::Inserted => options.clone(),
    };
    counted.check()?;
    if let Some(&index) = vertices.iter().find(|&&v| v as usize >= mesh.positions.len()) {
        return Err(FitError::VertexOutOfRange { index, count: mesh.positions.len() });
    }
    beyond_rig(mesh, vertices.iter().copied())?;
    let part = Part::new(mesh, vertices);
    if part.positions.len() < 4 {
        return Err(FitError::TooFewVertices(part.positions.len()));
    }
    if part.triangles.is_empty() {
        return Err(FitError::NoFaces);
    }
    counted.check_for_part(part.positions.len())?;
    let (mut fitted, mut steps) = refine::run(&part, options, smoothing, key_count)?;
    let mut rim = attached::rim_lengths(&part, &fitted.sweep);
    if options.axis.is_none() && rim[1] > rim[0] {
        fitted = attached::turned(&part, &fitted, &mut steps)?;
        rim.reverse();
    }
    let falloff = falloff::falloff_width(options.falloff, &fitted.keys);
    let quality = fitted.measured.quality;
    Ok(Fit { keys: fitted.keys, quality, sections: fitted.sections, steps, rim, falloff })
}

#[cfg(test)]
mod tests;
