//! Rigging a whole mesh in one call: the mesh's body (`super::body`: seams welded, small
//! touching components joined) is searched for protrusions (`super::protrusions`), longest
//! first; a protrusion mostly inside a longer one (a finger of a hand) stays in it. Each limb
//! gets one fitted sweep ([`super::fit`]), key 0 at the part's attachment (its rim), with the
//! fit's falloff, or where one sweep fits it more loosely than [`TARGET`], a chain of sweeps
//! (`super::chain`): the limb cut at its bends and widenings (upper arm, forearm, hand) and
//! forked at its toes or fingers, each link a branch child (§5) of the one it hangs from, so
//! that turning the limb carries its end, with [`LINK_FALLOFF_SHARE`] of the falloff; a part
//! that is no tube as one sweep (the dino's legs, their toes splayed) is rigged where its
//! chain fits much better ([`RESCUED_SHARE`]), and a coarse part that is no tube only at its
//! attached end (a leg cut above its crotch) where it fits without it. The rest of the mesh (the body)
//! stays unowned. The fits run on the welded mesh, so a part's sections close; a part whose
//! fit with the radii of its sections misses its surface by more than [`MAX_RMS`] (a lid's
//! flange, a ring) is no limb, nor is one whose fitted keys fold back (`folds`: a ball keyed
//! back and forth); each is left out and reported in [`Autorig::rejected`]. At most
//! `max_parts` limbs are rigged, mirror twins at that limit kept or left out together. Mirror
//! twins made of each other's vertices mirrored are rigged alike (`super::twins`): the better
//! fitted one and its mirror image; other limbs alike in shape are keyed alike
//! (`super::alike`): their matched links with as many keys. Small pieces hanging from a part
//! (a fingernail, an eye) or lying around it (a lock of hair) go with it (`super::hanging`).
//!
//! Data flow: mesh → body → protrusions → **fit** per limb (or chain) → rig document.

use std::collections::HashMap;
use std::sync::Mutex;
use std::time::Instant;

use glam::DVec3;

use super::alike;
use super::body::Body;
use super::chain::{FittedLink, LinkFitter, Profile};
use super::hanging;
pub use super::key_path::{FOLDED, Folds};
use super::key_path::{folds, zigzags};
use super::least_squares::SMOOTHING;
use super::limb::COARSE;
use super::part::Part;
use super::protrusions::{Protrusion, protrusions};
use super::quality::{FitQuality, measure};
use super::twins;
use super::{Fit, FitError, FitOptions, KeyCount, OptionError, fit};
use crate::mesh::Mesh;
use crate::parallel::prelude::*;
use crate::rig::{FORMAT, LinkKind, ParentLink, RigDocument, VERSION, VertexSelection};
use crate::sweep::{Sweep, chord_length};

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
    /// `limb0`, `limb1`, …, longest first; the links of a limb's chain after it, from the body
    /// out: `limb0.1`, `limb0.2`, ….
    pub name: String,
    /// The sweep this one is a branch child of (the previous link of its chain), if any.
    pub parent: Option<String>,
    /// The part's vertices, increasing.
    pub vertices: Vec<u32>,
    /// Its tip: the limb's tip (the vertex farthest from the body's center) in its last link,
    /// else the link's vertex farthest from its first key.
    pub tip: u32,
    /// Its length: the chord length of its key centers, mesh units.
    pub length: f64,
    /// The fitted sweep.
    pub fit: Fit,
    /// How closely the sweep follows the part's own vertices, as the search gave them (the
    /// small pieces hung on it afterwards, [`hanging`], not among them). A link of a chain is
    /// fitted to its neighbours' vertices within the overlap too, which they own and deform
    /// (the fit's own quality, [`Fit::quality`], counts them); one sweep's is its fit's.
    pub quality: FitQuality,
    /// Seconds the fit took.
    pub seconds: f64,
}

impl RiggedPart {
    /// Its key sections that are not star-shaped: rays from the section's center cross its
    /// boundary more than once (a crescent, a hand with its thumb apart).
    pub fn sections_not_star_shaped(&self) -> usize {
        self.fit.sections.iter().filter(|s| s.several_crossings > 0).count()
    }

    /// The RMS |d| (over the mean radius) its fit aims within: [`TARGET`], or
    /// [`NOT_STAR_TARGET`] where some of its sections are not star-shaped.
    pub fn target(&self) -> f64 {
        target_of(&self.fit)
    }

    /// Whether it fits its own vertices ([`RiggedPart::quality`]) within its
    /// [`RiggedPart::target`].
    pub fn within_target(&self) -> bool {
        self.quality.rms_d <= self.target()
    }
}

/// The RMS |d| (over the mean radius) `fit` aims within: [`TARGET`], or [`NOT_STAR_TARGET`]
/// where some of its sections are not star-shaped.
pub fn target_of(fit: &Fit) -> f64 {
    if fit.sections.iter().any(|s| s.several_crossings > 0) { NOT_STAR_TARGET } else { TARGET }
}

/// How loosely `fit` follows the vertices it was fitted to: its RMS |d| over its target
/// ([`target_of`]; 1 at the target).
pub fn looseness_of(fit: &Fit) -> f64 {
    fit.quality.rms_d / target_of(fit)
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
    /// Limbs rigged and then left out at the `max_parts` limit, being mirror twins of the next
    /// limb found ([`TWINS`]): a pair is kept or left out together.
    pub twins_left_out: usize,
}

impl Autorig {
    /// The rig file: one sweep per part, owning its vertices.
    pub fn document(&self) -> RigDocument {
        let sweeps = self
            .parts
            .iter()
            .map(|p| {
                let parent = p.parent.clone().map(|sweep| ParentLink { sweep, kind: LinkKind::Branch });
                p.fit.sweep_document(p.name.clone(), VertexSelection::Indices(p.vertices.clone()), parent)
            })
            .collect();
        RigDocument { format: FORMAT.to_string(), version: VERSION, rotation_interpolation: None, sweeps }
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
    let body = Body::new(mesh);
    let (found, mirror) = protrusions(mesh, &body, options.min_length * body.diagonal, 2 * options.max_parts);
    let search_seconds = started.elapsed().as_secs_f64();
    let fit_options = FitOptions { falloff: options.falloff, ..FitOptions::default() };
    // Fitted across welded seams, so that a part's sections close.
    let welded = body.welded_mesh(mesh);
    let fitted_on = welded.as_ref().unwrap_or(mesh);
    let fitted = |protrusion: &Protrusion, selection: &Selection| match selection {
        Selection::Fit(vertices) => {
            let options = FitOptions { axis: protrusion.axis.clone(), ..fit_options.clone() };
            Some(rig_limb(fitted_on, vertices, &protrusion.vertices, &options))
        }
        _ => None,
    };
    // The limbs are fitted at once, on every core, each as if the longer ones were all kept;
    // one whose vertices that assumption got wrong (a longer one was left out) is fitted
    // again below, so the rig is the one of fitting them in turn.
    let mut assumed_taken = vec![false; mesh.positions.len()];
    let assumed: Vec<Selection> = found
        .iter()
        .map(|protrusion| {
            let selection = Selection::of(protrusion, &assumed_taken);
            if let Selection::Fit(vertices) = &selection {
                for &v in vertices {
                    assumed_taken[v as usize] = true;
                }
            }
            selection
        })
        .collect();
    let mut speculative: Vec<Option<Result<Vec<FittedLink>, Option<LeftOut>>>> =
        (0..found.len()).into_par_iter().map(|i| fitted(&found[i], &assumed[i])).collect();
    // Mirror twins rigged alike: one twin's rig and its mirror image, of the two the pair
    // whose looser twin fits better. Where the mesh is only nearly a mirror image of itself,
    // only where that pair fits no more loosely than the twins each rigged on its own.
    // Per limb, whether it is a twin so rigged.
    let mut mirror_twins = vec![false; found.len()];
    if let Some(mirror) = &mirror {
        let parts: Vec<Option<&[u32]>> = assumed
            .iter()
            .map(|selection| match selection {
                Selection::Fit(vertices) => Some(&vertices[..]),
                _ => None,
            })
            .collect();
        for (j, i) in twins::twin_pairs(&parts, &body.weld, mirror) {
            let mirrored = |from: usize, to: usize| match (&speculative[from], parts[to]) {
                (Some(Ok(links)), Some(twin)) => twins::mirrored(links, twin, &body.weld, mirror, fitted_on)
                    .map(|image| (twins::looseness(links).max(twins::looseness(&image)), image)),
                _ => None,
            };
            let (onto_i, onto_j) = (mirrored(j, i), mirrored(i, j));
            let own = |k: usize| match &speculative[k] {
                Some(Ok(links)) => twins::looseness(links),
                _ => f64::INFINITY,
            };
            let before = own(i).max(own(j));
            let no_looser = |(pair, _): &(f64, Vec<FittedLink>)| !mirror.near || *pair <= before;
            let (onto_i, onto_j) = (onto_i.filter(no_looser), onto_j.filter(no_looser));
            let imaged = match (onto_i, onto_j) {
                (Some((a, image)), Some((b, _))) if a <= b => Some((i, image)),
                (Some((a, image)), None) if a.is_finite() => Some((i, image)),
                (_, Some((b, image))) if b.is_finite() => Some((j, image)),
                _ => None,
            };
            if let Some((k, image)) = imaged {
                speculative[k] = Some(Ok(image));
                (mirror_twins[i], mirror_twins[j]) = (true, true);
            }
        }
    }
    // Shape twins keyed alike: limbs alike in shape not rigged as mirror images (a lopsided
    // pose, a model never modelled symmetric), each matched link with as many keys as its twin
    // where that fits. A piece joined to the body, fitted along its own axis, is left as it is.
    let limbs: Vec<Option<&[FittedLink]>> = (0..found.len())
        .map(|i| match &speculative[i] {
            Some(Ok(links)) if !mirror_twins[i] && found[i].axis.is_none() => Some(&links[..]),
            _ => None,
        })
        .collect();
    let refitter = AlikeRefitter { mesh: fitted_on, options: &fit_options };
    let pairs = alike::shape_twins(&limbs);
    let alike: Vec<(Vec<FittedLink>, Vec<FittedLink>)> = (0..pairs.len())
        .into_par_iter()
        .map(|k| {
            let pair = &pairs[k];
            let (first, second) = (limbs[pair.first].unwrap_or_default(), limbs[pair.second].unwrap_or_default());
            alike::rigged_alike(first.to_vec(), second.to_vec(), &pair.links, &refitter)
        })
        .collect();
    for (pair, (first, second)) in pairs.iter().zip(alike) {
        speculative[pair.first] = Some(Ok(first));
        speculative[pair.second] = Some(Ok(second));
    }
    let mut parts: Vec<RiggedPart> = Vec::new();
    let mut rejected = Vec::new();
    let mut taken = vec![false; mesh.positions.len()];
    let mut limbs = 0;
    // Per limb rigged: its protrusion's length and its first part.
    let mut rigged: Vec<(f64, usize)> = Vec::new();
    let mut twins_left_out = 0;
    for (i, protrusion) in found.iter().enumerate() {
        let selection = Selection::of(protrusion, &taken);
        if limbs == options.max_parts {
            // Mirror twins are kept or left out together: where the next limb is a twin of
            // the last ones (as long within [`TWINS`]), they are all left out.
            let twin = |&(length, _): &(f64, usize)| (length - protrusion.length).abs() <= TWINS * length;
            if matches!(selection, Selection::Fit(_)) && rigged.last().is_some_and(twin) {
                while let Some(&(_, first)) = rigged.last().filter(|l| twin(l)) {
                    parts.truncate(first);
                    rigged.pop();
                    twins_left_out += 1;
                }
            }
            break;
        }
        let result = if selection == assumed[i] { speculative[i].take() } else { fitted(protrusion, &selection) };
        let vertices = match selection {
            Selection::Skip => continue,
            Selection::TooSmall(count) => {
                rejected.push(Rejected { tip: protrusion.tip, vertices: count, rms_d: None, folded: None, open: None });
                continue;
            }
            Selection::Fit(vertices) => vertices,
        };
        let chain = match result {
            Some(Ok(chain)) => chain,
            Some(Err(Some(why))) => {
                let (rms_d, folded, open) = match why {
                    LeftOut::Loose(rms_d) => (Some(rms_d), None, None),
                    LeftOut::Folded(folds) => (None, Some(folds), None),
                    LeftOut::Open { rms_d, keys } => (Some(rms_d), None, Some(keys)),
                };
                rejected.push(Rejected { tip: protrusion.tip, vertices: vertices.len(), rms_d, folded, open });
                continue;
            }
            // A part the fit refuses (too flat for an axis) is no limb, as before fitting.
            Some(Err(None)) | None => continue,
        };
        rigged.push((protrusion.length, parts.len()));
        let name = format!("limb{limbs}");
        let names: Vec<String> =
            (0..chain.len()).map(|link| if link == 0 { name.clone() } else { format!("{name}.{link}") }).collect();
        for (FittedLink { vertices, fitted: fitted_to, fit: fitted, seconds, parent }, this) in
            chain.into_iter().zip(&names)
        {
            for &v in &vertices {
                taken[v as usize] = true;
            }
            let tip = if vertices.binary_search(&protrusion.tip).is_ok() {
                protrusion.tip
            } else {
                farthest_from_first_key(fitted_on, &vertices, &fitted)
            };
            let quality = own_quality(fitted_on, &vertices, &fitted_to, &fitted);
            parts.push(RiggedPart {
                name: this.clone(),
                parent: parent.map(|p| names[p].clone()),
                tip,
                length: chord_length(&fitted.keys),
                vertices,
                fit: fitted,
                quality,
                seconds,
            });
        }
        limbs += 1;
    }
    // Small pieces that hang from a part (a fingernail on a finger) go with it.
    let mut owner = vec![None; mesh.positions.len()];
    for (k, part) in parts.iter().enumerate() {
        for &v in &part.vertices {
            owner[v as usize] = Some(k);
        }
    }
    let radii: Vec<f64> = parts.iter().map(|part| part.fit.quality.mean_radius).collect();
    for (k, piece) in hanging::hanging_pieces(mesh, &body, &mut owner, &radii) {
        let vertices = &mut parts[k].vertices;
        vertices.extend(piece);
        vertices.sort_unstable();
        vertices.dedup();
    }
    Ok(Autorig { parts, rejected, search_seconds, twins_left_out })
}

/// How closely `fit` follows the part's own `vertices` (of `mesh`), where it was fitted to
/// `fitted_to` (both increasing): its fit's quality where they are the same vertices, else the
/// part's own measured again on its sweep ([`RiggedPart::quality`]).
fn own_quality(mesh: &Mesh, vertices: &[u32], fitted_to: &[u32], fit: &Fit) -> FitQuality {
    if vertices == fitted_to {
        return fit.quality;
    }
    let positions: Vec<DVec3> = vertices.iter().map(|&v| mesh.positions[v as usize]).collect();
    match Sweep::try_new(&fit.keys, None) {
        Ok(sweep) => measure(&sweep, &positions).quality,
        Err(_) => fit.quality,
    }
}

/// What becomes of a protrusion, given the vertices the longer limbs kept have taken.
#[derive(Clone, Debug, PartialEq)]
enum Selection {
    /// Mostly inside a longer limb (a finger of a hand), or fewer vertices than a
    /// tetrahedron's: no part.
    Skip,
    /// A part of this many vertices, fewer than [`MIN_VERTICES`]: left out.
    TooSmall(usize),
    /// The vertices to fit, those not taken.
    Fit(Vec<u32>),
}

impl Selection {
    fn of(protrusion: &Protrusion, taken: &[bool]) -> Selection {
        let inside = protrusion.vertices.iter().filter(|&&v| taken[v as usize]).count();
        if inside * 2 > protrusion.vertices.len() {
            return Selection::Skip;
        }
        let vertices: Vec<u32> = protrusion.vertices.iter().copied().filter(|&v| !taken[v as usize]).collect();
        match vertices.len() {
            0..4 => Selection::Skip,
            count if count < MIN_VERTICES => Selection::TooSmall(count),
            _ => Selection::Fit(vertices),
        }
    }
}

/// Fits the limb made of `vertices` (increasing): one sweep where its fitted radii miss it by
/// at most [`TARGET`] and its sections' radii by at most [`MAX_RMS`], otherwise its best chain (`super::chain`) where each link fits within [`MAX_RMS`] and the
/// loosest better than the one sweep, otherwise the one sweep within [`MAX_RMS`]; a sweep whose
/// keys fold back ([`folds`]) fits no link; a coarse part that none of those rig well is
/// trimmed of its attached end where the rest fits; a part in a plane
/// ([`Part::lies_in_a_plane`]) is none of them. The part is what a longer limb left of its
/// protrusion, `found` (both increasing); it is trimmed as found (a leg and its mirror twin,
/// found above their crotch, share the pelvis's slab, and the first takes its own hip's ring
/// out of the other's slab), and the trimmed limb is kept only where it holds none of what
/// the longer limbs took. `Err` with why the one sweep is no limb, `Err(None)` where the fit
/// refuses the part.
fn rig_limb(
    mesh: &Mesh,
    vertices: &[u32],
    found: &[u32],
    options: &FitOptions,
) -> Result<Vec<FittedLink>, Option<LeftOut>> {
    let mut links = rig_limb_with(&Fitter { mesh, options, fitted: Default::default() }, vertices, found)?;
    let one_sweep = links.len() == 1;
    for link in &mut links {
        let started = Instant::now();
        if let Some(smoothed) = smoothed(mesh, link, options, one_sweep) {
            link.fit = smoothed;
            link.seconds += started.elapsed().as_secs_f64();
        }
    }
    Ok(links)
}

/// Once a limb's links are chosen, the fit of `link` with its radii smoothed where its plain
/// least squares was not kept (the radii bulged between the vertices and edges' midpoints
/// they were fitted to) and that tightens it: its own radii smoothed ([`Fit::smoothed`]);
/// failing that, for a limb of `one_sweep` that misses its target ([`target_of`]; a fit costs
/// as much again), the limb fitted again with smoothed least squares
/// in each of its starts ([`super::fit_smoothing`]), kept where its keys neither fold nor
/// zigzag and its sections are not all open and stay within [`MAX_RMS`]. The beast's
/// 60-vertex knob (a public mesh) went from 30.9% to 6.9%, the AT-AT's upper legs, plates with
/// open edges, from 27.4% to 8.3%. `None` where nothing tightens it; the search compares plain
/// fits, so that the chains chosen are the same.
fn smoothed(mesh: &Mesh, link: &FittedLink, options: &FitOptions, one_sweep: bool) -> Option<Fit> {
    if let Some(smoothed) = link.fit.smoothed(mesh, &link.fitted).ok().flatten() {
        return Some(smoothed);
    }
    if !one_sweep || link.fit.least_squares_kept() || link.fit.quality.rms_d <= target_of(&link.fit) {
        return None;
    }
    let refit = super::fit_with(mesh, &link.fitted, options, SMOOTHING, KeyCount::Inserted).ok()?;
    let tighter = refit.quality.rms_d < link.fit.quality.rms_d
        && folds(&refit.keys).is_none()
        && !zigzags(&refit.keys)
        && !all_open(&refit)
        && one_sweep_loose(&refit) <= MAX_RMS;
    tighter.then_some(refit)
}

/// [`rig_limb`] with the links fitted by `fitter`.
fn rig_limb_with(fitter: &Fitter, vertices: &[u32], found: &[u32]) -> Result<Vec<FittedLink>, Option<LeftOut>> {
    let (mesh, options) = (fitter.mesh, fitter.options);
    let whole = fitter.fit_whole(vertices);
    let whole_rms = whole.as_ref().map_or(f64::INFINITY, |(fitted, _)| one_sweep_loose(fitted));
    let one = |(fit, seconds): (Fit, f64)| {
        vec![FittedLink { vertices: vertices.to_vec(), fitted: vertices.to_vec(), fit, seconds, parent: None }]
    };
    // A part whose every key section is open is a sheet: no tube, however close its sections'
    // radii (one looser than [`MAX_RMS`] or whose keys fold is left out as before).
    let sheet = whole_rms <= MAX_RMS && whole.as_ref().is_some_and(|(fitted, _)| all_open(fitted));
    // Close enough as one sweep: its fitted radii within the target, its sections a tube's.
    let close =
        !sheet && whole.as_ref().is_some_and(|(fitted, _)| fitted.quality.rms_d <= TARGET) && whole_rms <= MAX_RMS;
    if close {
        return Ok(whole.map(one).unwrap_or_default());
    }
    // A part in a plane, or a sheet, has pieces in it too: no chain of them is a tube, and
    // none is trimmed.
    let flat = whole_rms > MAX_RMS
        && whole.as_ref().is_some_and(|(fitted, _)| folds(&fitted.keys).is_none())
        && Part::new(mesh, vertices).lies_in_a_plane();
    if !flat && !sheet {
        let profile = Profile::new(mesh, vertices);
        let chain = profile.as_ref().and_then(|profile| profile.chain(fitter, TARGET));
        // A part that is no tube as one sweep becomes a limb only as a chain of tubes.
        let most = if whole_rms <= MAX_RMS { MAX_RMS } else { MAX_RMS.min(RESCUED_SHARE * whole_rms) };
        if let Some(chain) = chain.filter(|chain| kept_as_chain(chain.worst, whole_rms, most)) {
            return Ok(with_link_falloff(chain.links, options));
        }
        // A coarse part that is no tube for what lies at its attached end (a leg cut above its
        // crotch, one span of long triangles below it) is a limb without it, where the rest
        // fits within the target and the one sweep is no limb or misses it by over
        // [`TRIMMED_OVER`].
        let loose_whole = whole.as_ref().is_none_or(|(fitted, _)| fitted.quality.rms_d > TRIMMED_OVER);
        if (whole_rms > MAX_RMS || loose_whole)
            && vertices.len() < COARSE
            && let Some(trimmed) = Profile::new(mesh, found).and_then(|profile| profile.trimmed(fitter, TARGET))
            && trimmed.links[0].vertices.iter().all(|v| vertices.binary_search(v).is_ok())
        {
            return Ok(trimmed.links);
        }
        // A coarse limb that no chain of cuts rigs may be one with its end branched: a hand
        // fitted as a finger is, past its widening.
        if whole_rms > MAX_RMS
            && vertices.len() < COARSE
            && let Some(chain) = profile.as_ref().and_then(|profile| profile.with_end_branched(fitter, TARGET, most))
        {
            return Ok(with_link_falloff(chain.links, options));
        }
    }
    match whole {
        Some((fitted, _)) if sheet => Err(Some(LeftOut::Open { rms_d: whole_rms, keys: fitted.keys.len() })),
        Some(whole) if whole_rms <= MAX_RMS => Ok(one(whole)),
        Some((fitted, _)) => match folds(&fitted.keys) {
            Some(folded) => Err(Some(LeftOut::Folded(folded))),
            None if whole_rms.is_finite() => Err(Some(LeftOut::Loose(whole_rms))),
            None => Err(None),
        },
        None => Err(None),
    }
}

/// A chain's `links` with [`LINK_FALLOFF_SHARE`] of their falloff, where `options` leave it at
/// the default (a width given by `--falloff` is every sweep's).
fn with_link_falloff(mut links: Vec<FittedLink>, options: &FitOptions) -> Vec<FittedLink> {
    if options.falloff.is_none() {
        for link in &mut links {
            link.fit.falloff *= LINK_FALLOFF_SHARE;
        }
    }
    links
}

/// A fit and the seconds it took.
type TimedFit = (Fit, f64);

/// Fits a limb's links with the rig's options, each set of vertices once (the chains tried
/// share links).
struct Fitter<'a> {
    mesh: &'a Mesh,
    options: &'a FitOptions,
    fitted: Mutex<HashMap<Vec<u32>, Option<TimedFit>>>,
}

impl LinkFitter for Fitter<'_> {
    fn fit(&self, vertices: &[u32]) -> Option<(Fit, f64)> {
        if let Some(known) = self.fitted.lock().ok()?.get(vertices) {
            return known.clone();
        }
        let started = Instant::now();
        let fitted =
            fit(self.mesh, vertices, self.options).ok().map(|fitted| (fitted, started.elapsed().as_secs_f64()));
        self.fitted.lock().ok()?.insert(vertices.to_vec(), fitted.clone());
        fitted
    }

    /// A folded sweep fits no link, however closely, nor one whose keys zigzag through its part
    /// ([`zigzags`]: the faerie's 12-vertex hand fitted within 3% by 22 keys that travel 4.6
    /// times as far as they reach). A coarse link (fewer vertices than
    /// [`COARSE`]) whose key sections are not all star-shaped (rays crossing its boundary more
    /// than once: a low-poly hand with its thumb) is measured with its fitted radii where they
    /// fit closer: radii sampled from so few triangles take the outermost crossing, and the
    /// faerie's hand of 17 vertices, which its fitted sweep follows within 5%, misses its
    /// sections by 106%. A limb's one sweep is always measured by its sections
    /// ([`one_sweep_loose`]), so what is no tube is still no limb.
    fn loose(&self, fitted: &Fit) -> f64 {
        if folds(&fitted.keys).is_some() || zigzags(&fitted.keys) { f64::INFINITY } else { link_looseness(fitted) }
    }
}

/// How loosely a link's fit follows its part where a chain is weighed against its limb's one
/// sweep ([`LinkFitter::loose`], for a fit that neither folds nor zigzags): its sections' RMS
/// |d|, or for a coarse link whose sections are not all star-shaped its fitted radii's where
/// they fit closer.
pub fn link_looseness(fitted: &Fit) -> f64 {
    let sections = fitted.sections_quality().rms_d;
    if fitted.quality.vertices < COARSE && fitted.sections.iter().any(|s| s.several_crossings > 0) {
        fitted.quality.rms_d.min(sections)
    } else {
        sections
    }
}

impl Fitter<'_> {
    /// The limb's one sweep, fitted as [`LinkFitter::fit`] fits a link, then given more keys
    /// where it needs them ([`Fitter::with_more_keys`]; the links a chain tries are not).
    fn fit_whole(&self, vertices: &[u32]) -> Option<TimedFit> {
        let (fitted, seconds) = self.fit(vertices)?;
        let started = Instant::now();
        let Some(refit) = self.with_more_keys(vertices, &fitted) else { return Some((fitted, seconds)) };
        let refit = (refit, seconds + started.elapsed().as_secs_f64());
        self.fitted.lock().ok()?.insert(vertices.to_vec(), Some(refit.clone()));
        Some(refit)
    }

    /// Where `fitted` took every key it may and still misses its target, by at most
    /// [`MORE_KEYS_WITHIN`] times it: the fit of the same vertices with [`MORE_KEYS`] times as
    /// many keys allowed, where that brings it within the targets of both (a refit whose
    /// sections are no longer all star-shaped is not judged by its looser target alone) and fits
    /// no more loosely as a link; otherwise `None`.
    fn with_more_keys(&self, vertices: &[u32], fitted: &Fit) -> Option<Fit> {
        let target = target_of(fitted);
        let missed = fitted.quality.rms_d;
        if fitted.keys.len() < self.options.max_keys || missed <= target || missed > MORE_KEYS_WITHIN * target {
            return None;
        }
        let more = FitOptions {
            max_keys: (self.options.max_keys as f64 * MORE_KEYS).round() as usize,
            ..self.options.clone()
        };
        let refit = fit(self.mesh, vertices, &more).ok()?;
        (refit.quality.rms_d <= target.min(target_of(&refit)) && self.loose(&refit) <= self.loose(fitted))
            .then_some(refit)
    }
}

/// A limb whose one sweep reaches the key limit still looser than its target is fitted again
/// with this many times the limit, and takes that fit where it is within the target
/// (`Fitter::with_more_keys`): the AT-AT's two 118-vertex head parts, 13.95% with 24 keys, fit
/// at 8.9% with 32.
pub const MORE_KEYS: f64 = 4.0 / 3.0;

/// …where it misses its target by at most this many times it: more keys tighten a fit by a
/// fraction, not a factor (the AT-AT's head parts ×0.64; its upper legs, 27.4% against their
/// 15% with 24 keys, would fit at 25.1% with 32, ×0.92, still over, and their four refits
/// took half the command's time).
pub const MORE_KEYS_WITHIN: f64 = 1.5;

/// Whether every key section of `fitted` is open ([`super::SectionReport::open`]): its planes
/// cut the part's surface in arcs that leave it through its boundary, not in loops around the
/// axis. Such a part is a sheet (the AT-AT's 8-vertex chin plate, a strip of three quads bent
/// in a curve, whose every section misses 14 of its 32 rays: 31.8% RMS |d| with its
/// sections' radii), not a tube, whatever its fit: a limb's sections close at least away
/// from its rim.
fn all_open(fitted: &Fit) -> bool {
    fitted.sections.iter().all(|section| section.open)
}

/// How loosely a limb's one sweep follows it: the RMS |d| of its sections' radii over the
/// mean radius, infinite where its keys fold back.
fn one_sweep_loose(fitted: &Fit) -> f64 {
    if folds(&fitted.keys).is_some() { f64::INFINITY } else { fitted.sections_quality().rms_d }
}

/// Why a limb's one sweep is no limb.
#[derive(Clone, Copy, Debug)]
enum LeftOut {
    /// Its sections' RMS |d| over the mean radius, over [`MAX_RMS`].
    Loose(f64),
    /// Its keys fold back.
    Folded(Folds),
    /// Every one of its `keys` key sections is open ([`all_open`]): a sheet. `rms_d` as in
    /// [`LeftOut::Loose`].
    Open { rms_d: f64, keys: usize },
}

/// Fits shape twins' links again alike ([`alike::rigged_alike`]) as a limb's links are fitted
/// ([`Fitter`], then their radii smoothed where that tightens them), and keeps a refit that
/// neither folds nor zigzags, fits within its target or no looser than the fit it replaces,
/// and whose sections are still a tube's.
struct AlikeRefitter<'a> {
    mesh: &'a Mesh,
    options: &'a FitOptions,
}

impl alike::Refitter for AlikeRefitter<'_> {
    fn refit(&self, links: &[FittedLink], link: usize, keys: usize) -> Option<Fit> {
        let old = &links[link];
        let vertices = &old.fitted;
        let mut fit = super::fit_with(self.mesh, vertices, self.options, 0.0, KeyCount::Exactly(keys)).ok()?;
        // Key 0 where it was: a link's key 0 was turned to where it is attached.
        let start = old.fit.keys[0].center;
        let last = fit.keys.last()?.center;
        if last.distance(start) < fit.keys[0].center.distance(start) {
            fit = fit.reversed();
        }
        if let Some(smoothed) = fit.smoothed(self.mesh, vertices).ok().flatten() {
            fit = smoothed;
        }
        if links.len() > 1 && self.options.falloff.is_none() {
            fit.falloff *= LINK_FALLOFF_SHARE;
        }
        Some(fit)
    }

    fn accepts(&self, refit: &Fit, old: &Fit) -> bool {
        folds(&refit.keys).is_none()
            && !zigzags(&refit.keys)
            && (looseness_of(refit) <= 1.0 || looseness_of(refit) <= looseness_of(old))
            && one_sweep_loose(refit) <= MAX_RMS.max(one_sweep_loose(old))
    }

    fn looseness(&self, fit: &Fit) -> f64 {
        looseness_of(fit)
    }
}

/// Two protrusions whose lengths differ by at most this fraction are mirror twins, kept or
/// left out together at the `max_parts` limit (the blocky man's legs differ by 0.02%).
pub const TWINS: f64 = 1e-3;

/// The vertex of `vertices` farthest along the fitted sweep from its first key.
fn farthest_from_first_key(mesh: &Mesh, vertices: &[u32], fitted: &Fit) -> u32 {
    let first = fitted.keys[0].center;
    vertices
        .iter()
        .copied()
        .max_by(|&a, &b| {
            let (da, db) = (mesh.positions[a as usize].distance(first), mesh.positions[b as usize].distance(first));
            da.total_cmp(&db).then(b.cmp(&a))
        })
        .unwrap_or(vertices[0])
}

/// A part of fewer vertices (a quad of a game mesh's face) is no limb.
pub const MIN_VERTICES: usize = 8;

/// Whether a limb is rigged as its chain, whose loosest link fits with RMS |d| `worst` (over its
/// mean radius), rather than as its one sweep (`whole`, with its sections' radii): where the
/// chain fits within `most` and its loosest link within [`CHAIN_MARGIN`] of the one sweep.
fn kept_as_chain(worst: f64, whole: f64, most: f64) -> bool {
    worst <= most && worst <= CHAIN_MARGIN * whole
}

/// A chain is kept over its limb's one sweep where its loosest link fits within this many times
/// the one sweep's RMS |d| (`kept_as_chain`): a chain bends where one sweep cannot (at the
/// wrist, at each finger), worth a loosest link about as loose as the one sweep. Near-mirror
/// limbs whose chain and one sweep fit within a few percent of each other are then rigged
/// alike: the cartoon man's arms, one a chain (its loosest link tighter than its one sweep),
/// the other a chain whose loosest finger fits at 24% against its one sweep's 23%, not one
/// sweep. A chain whose loosest link fits 15% looser than its one sweep (the dino's arms'
/// stems, the palm past the wrist at 25% against 22%) is not kept.
pub const CHAIN_MARGIN: f64 = 1.1;

/// A chain's links get this share of the default falloff width (a fraction of each link's
/// length): at a joint the bands of both links meet, each fading half way into the other, so
/// the blend across it is as wide as a limb's into the body; and a link's neighbour, turned at
/// the joint, reaches far into a wide band with its cross-sections (the dino's bent legs
/// stretch an edge 2.2× with the whole width, 1.9× with half).
pub const LINK_FALLOFF_SHARE: f64 = 0.5;

/// A part whose one sweep is no limb (looser than [`MAX_RMS`]) is rigged as a chain only where
/// each link's sections fit within this share of the one sweep's RMS |d| (and [`MAX_RMS`]): the
/// dino's legs, their toes splayed (19% and 15% against 101% and 134%), and arms (22% against
/// 56%) are; so are Mr. Fixit's T-posed arms, ending in mittens (their loosest links, a finger
/// each fitted with a ring of its palm, 27% against 54% and 28% against 50%; each link within
/// its target at its own vertices); a teapot handle's junction (25% against 39%) is not. At
/// half, the share before, those arms were left out and their fingertips rigged in their place.
pub const RESCUED_SHARE: f64 = 0.6;

/// A coarse limb's one sweep that misses it by more than this RMS |d| (over the mean radius) is
/// trimmed of its attached end where that fits it within [`TARGET`] (see `rig_limb`).
pub const TRIMMED_OVER: f64 = 0.15;

/// A limb's one sweep within this RMS |d| (over the mean radius) with its fitted radii, and
/// within [`MAX_RMS`] with its sections', is kept without trying a chain; a stretch of a chain
/// within it with its sections' radii is not cut further.
pub const TARGET: f64 = 0.10;

/// A part found whose fit is looser than [`MAX_RMS`] (a flange, a ring or a flat panel), or
/// that has fewer than [`MIN_VERTICES`] (a quad or two of a game mesh's face): no limb.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rejected {
    /// Its tip.
    pub tip: u32,
    /// Its vertex count.
    pub vertices: usize,
    /// Its fit's RMS |d| over the mean radius, with the radii sampled from its key sections;
    /// `None` for a part of fewer than [`MIN_VERTICES`], which is not fitted, and for a folded
    /// fit.
    pub rms_d: Option<f64>,
    /// Its fit's folds, where its keys fold back (see [`FOLDED`]).
    pub folded: Option<Folds>,
    /// Where every key section of its fit is open (a sheet, no tube): how many keys it has.
    pub open: Option<usize>,
}

/// The fit target of a part some of whose key sections are not star-shaped (RMS |d| over the
/// mean radius; [`TARGET`] otherwise): one sweep's radii from a center cannot follow a
/// crescent's two sides.
pub const NOT_STAR_TARGET: f64 = 0.15;

/// A found part whose fitted sweep, with the radii sampled from its key sections
/// ([`Fit::sections_quality`]), misses its surface by more than this RMS |d| (over the mean
/// radius) is no limb and is left out of the rig: its sections are not those of a tube, though
/// radii fitted to its vertices by least squares may follow them more closely.
pub const MAX_RMS: f64 = 0.35;

#[cfg(test)]
mod tests {
    use super::*;

    /// The cartoon man's arm whose loosest finger fits at 23.9% against its one sweep's 22.8%
    /// is a chain, like its other arm; the rule before (strictly tighter) made it one sweep. The
    /// dino's arm stem cut at the wrist (the palm at 25.2% against 21.9%) stays one sweep, and
    /// no chain looser than the most a link may miss by is kept, however loose the one sweep.
    #[test]
    fn a_chain_about_as_loose_as_the_one_sweep_is_kept() {
        let strictly_tighter = |worst: f64, whole: f64| worst < whole;
        assert!(kept_as_chain(0.2391, 0.2279, MAX_RMS));
        assert!(!strictly_tighter(0.2391, 0.2279));
        assert!(kept_as_chain(0.2360, 0.2666, MAX_RMS));
        assert!(!kept_as_chain(0.2524, 0.2187, MAX_RMS));
        assert!(!kept_as_chain(0.36, 0.5, MAX_RMS));
        assert!(!kept_as_chain(0.2, 1.0, RESCUED_SHARE * 0.3));
    }

    /// An L-shaped strip 6 quads wide meshed in a plane: along x for 66 quads, then up y for
    /// 60 more at its far end. The part is all of it past its first 10 quads, attached to the
    /// rest along that column's edge; it bends at its corner.
    fn flat_l() -> (Mesh, Vec<u32>) {
        let size = 66u32;
        let in_l = |i: u32, j: u32| j < 6 || i >= size - 6;
        let at = |i: u32, j: u32| j * (size + 1) + i;
        let positions = (0..=size)
            .flat_map(|j| (0..=size).map(move |i| DVec3::new(0.25 * f64::from(i), 0.25 * f64::from(j), 0.0)))
            .collect();
        let mut faces = crate::mesh::Faces::new();
        for j in 0..size {
            for i in 0..size {
                if in_l(i, j) {
                    faces.push(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        let mut on_faces: Vec<u32> = faces.triangles().flatten().collect();
        on_faces.sort_unstable();
        on_faces.dedup();
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        let part = on_faces.into_iter().filter(|&v| v % (size + 1) >= 10).collect();
        (mesh, part)
    }

    /// A flat part is left out after its one sweep: its pieces are flat too, and chains of
    /// them (what was tried before) fit one set of vertices after another for nothing.
    #[test]
    fn a_flat_part_is_left_out_without_trying_chains() {
        let (mesh, part) = flat_l();
        let options = FitOptions::default();
        let fitter = Fitter { mesh: &mesh, options: &options, fitted: Default::default() };
        let left_out = rig_limb_with(&fitter, &part, &part).err();
        assert!(matches!(left_out, Some(Some(LeftOut::Loose(rms_d))) if rms_d > MAX_RMS), "left out: {left_out:?}");
        assert_eq!(fitter.fitted.lock().unwrap().len(), 1, "its one sweep alone is fitted");
        // The chains tried before fit more, and none is a limb.
        let before = Fitter { mesh: &mesh, options: &options, fitted: Default::default() };
        let chain = Profile::new(&mesh, &part).and_then(|profile| profile.chain(&before, TARGET));
        assert!(before.fitted.lock().unwrap().len() > 1);
        assert!(chain.is_none_or(|chain| chain.worst > MAX_RMS));
    }

    /// The AT-AT's chin plate (its 8 vertices and 6 triangles as the file has them): a strip
    /// of three quads bent in a curve, a component of its own.
    fn chin_plate() -> (Mesh, Vec<u32>) {
        let positions = vec![
            DVec3::new(242.965607, -1258.38623, 1429.64954),
            DVec3::new(251.556717, -1253.07605, 1409.83215),
            DVec3::new(251.556381, -1165.44177, 1433.31372),
            DVec3::new(243.016037, -1176.94958, 1457.6875),
            DVec3::new(251.638046, -1247.63708, 1389.53308),
            DVec3::new(251.637817, -1160.00269, 1413.01453),
            DVec3::new(243.20047, -1242.27808, 1369.5332),
            DVec3::new(243.158478, -1158.01526, 1387.02332),
        ];
        let mut faces = crate::mesh::Faces::new();
        for triangle in [[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2], [4, 6, 7], [4, 7, 5]] {
            faces.push(&triangle);
        }
        (Mesh::from_parts(positions, faces, Vec::new()).unwrap(), (0..8).collect())
    }

    /// A sheet is left out, named as one: its one sweep's sections all open, it fits within
    /// [`MAX_RMS`] by them (31.8%) and was kept before, over its target.
    #[test]
    fn a_sheet_is_left_out_where_its_sweep_would_have_been_kept() {
        let (mesh, part) = chin_plate();
        let options = FitOptions::default();
        let fitter = Fitter { mesh: &mesh, options: &options, fitted: Default::default() };
        let (whole, _) = fitter.fit_whole(&part).unwrap();
        assert!(all_open(&whole));
        let rms_d = one_sweep_loose(&whole);
        assert!(rms_d > TARGET && rms_d <= MAX_RMS, "{rms_d}: the old rule kept it");
        let left_out = rig_limb_with(&fitter, &part, &part).err();
        assert!(
            matches!(left_out, Some(Some(LeftOut::Open { keys, rms_d: r })) if keys == whole.keys.len() && r == rms_d),
            "left out: {left_out:?}"
        );
        // Two more sides close the strip into a tube (a quad tube of three spans): its sections
        // are loops, and it is no sheet.
        let mut tube = mesh.clone();
        for triangle in [[3, 2, 5], [3, 5, 7], [6, 0, 3], [6, 3, 7]] {
            tube.faces.push(&triangle);
        }
        let fitter = Fitter { mesh: &tube, options: &options, fitted: Default::default() };
        let (closed, _) = fitter.fit_whole(&part).unwrap();
        assert!(closed.sections.iter().any(|section| !section.open), "{:?}", closed.sections);
    }
}
