//! The fitting loop of §3 (Fig. 3): a rough sweep enclosing the part, key sections cut by
//! planes along the axis, re-centering of the keys on their sections, and key insertion where
//! the fit is loose, with the end keys kept just past the part.

use std::cell::RefCell;
use std::collections::HashMap;

use glam::{DQuat, DVec2, DVec3};

use super::axis::{Polyline, principal_axis};
use super::frames::{first_x_axis, reference_direction, transported_frames};
use super::key_path::astray;
use super::least_squares::{SMOOTHING, fitted_radii};
use super::part::Part;
use super::quality::{Measured, measure};
use super::radii::sample;
use super::ray_fan::with_fan;
use super::section::{Contour, Plane, around, center, cut};
use super::skeleton::{Skeleton, skeleton};
use super::star::star_center;
use super::{FitError, FitOptions, FitStep, SectionReport};
use crate::parallel::prelude::*;
use crate::sweep::{Key, Sweep};

/// The end planes sit this fraction of the part's length beyond its extreme vertices.
const END_MARGIN: f64 = 0.01;
/// An end key takes its radii from the first section found this far inside the end plane
/// (fractions of the part's length), since its own plane lies just past the part.
const END_INSETS: [f64; 8] = [0.02, 0.04, 0.07, 0.1, 0.14, 0.19, 0.25, 0.32];
/// Tilts (radians) tried around each inner key's normal for the least-area section.
const TILTS: [f64; 5] = [-0.3, -0.15, 0.0, 0.15, 0.3];
/// Re-centering passes after the first cut and after each key insertion.
const RECENTER_PASSES: usize = 3;
/// The chord over which the skeleton's tangent is taken, as a fraction of its length.
const SKELETON_CHORD: f64 = 0.1;
/// The label of the last step, the radii fitted to the part's surface by least squares.
pub const LEAST_SQUARES_STEP: &str = "radii fitted to the surface by least squares";
/// Vertices per key radius below which the least-squares radii are fitted to the part's edge
/// midpoints too.
const SAMPLES_PER_RADIUS: usize = 4;
/// How much tighter (relative RMS |d|) a coarse part's fit from another start must be than the
/// one kept so far (first, that from the centered skeleton with the planes following it), to be
/// kept: a margin that rounding in a rigidly moved copy of the part cannot cross.
const OTHER_START_MARGIN: f64 = 0.01;
/// Insertion rounds in a row that may fail to tighten the fit before insertion stops.
const STALE_ROUNDS: usize = 2;

/// Where a key's plane is: a point of it (the key's center) and its normal.
#[derive(Clone, Copy, Debug)]
struct Station {
    center: DVec3,
    normal: DVec3,
}

/// A key's section: its center (in the key's plane), its radii and how the rays met it.
#[derive(Clone, Debug)]
struct Cut {
    center: DVec3,
    radii: Vec<f64>,
    report: SectionReport,
    /// The plane the section lies in and its contours, for sampling from another center.
    plane: Plane,
    contours: Vec<Contour>,
}

impl Cut {
    /// Closed contours met by every ray, or several closed contours (toes, fingers) whose
    /// gaps some rays pass through: the section is the part's whole cross-section.
    fn complete(&self) -> bool {
        !self.report.open && (self.report.missed == 0 || self.contours.len() > 1)
    }
}

/// The complete keys nearest to key `i` on its inner side (towards the middle of the sweep),
/// nearest first; the nearest complete keys on the other side when the inner side has none.
fn inner_neighbours(complete: &[usize], i: usize, last: usize) -> Vec<usize> {
    let after: Vec<usize> = complete.iter().copied().filter(|&k| k > i).take(2).collect();
    let before: Vec<usize> = complete.iter().rev().copied().filter(|&k| k < i).take(2).collect();
    let (inner, outer) = if 2 * i <= last { (after, before) } else { (before, after) };
    if inner.is_empty() { outer } else { inner }
}

/// The radii of a partial section seen from `center` (in its plane): where a ray meets the
/// section's boundary, its outermost crossing; elsewhere the neighbour's radius.
fn partial_radii(cut: &Cut, center: DVec3, neighbour: &[f64]) -> Vec<f64> {
    let contours: Vec<&Contour> = cut.contours.iter().collect();
    let q = cut.plane.coordinates_of(center);
    with_fan(neighbour.len(), |fan| {
        fan.cast(&contours, q);
        neighbour.iter().enumerate().map(|(j, &r)| fan.crossings(j).last().copied().unwrap_or(r)).collect()
    })
}

/// Where the line through the centers `a` (nearer) and `b` meets the station's plane; `None`
/// when the line runs along the plane or meets it more than twice their distance beyond `a`.
fn extrapolate(a: DVec3, b: DVec3, station: &Station) -> Option<DVec3> {
    let direction = a - b;
    let along = direction.dot(station.normal);
    if along.abs() <= 1e-9 * direction.length() {
        return None;
    }
    let lambda = (station.center - a).dot(station.normal) / along;
    (lambda.abs() <= 2.0).then(|| a + direction * lambda)
}

/// A set of keys and what fitting them found.
#[derive(Clone, Debug)]
pub struct Fitted {
    pub keys: Vec<Key>,
    pub sections: Vec<SectionReport>,
    pub sweep: Sweep,
    pub measured: Measured,
}

/// How many keys a fit takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KeyCount {
    /// [`FitOptions::keys`] evenly spaced, then keys inserted where the fit is loose, up to
    /// [`FitOptions::max_keys`], until a round of them no longer tightens it (the paper's loop,
    /// Fig. 3).
    Inserted,
    /// Exactly this many (at least 2, at most [`crate::limits::MAX_KEYS_PER_SWEEP`]): at most
    /// [`FitOptions::keys`] evenly spaced, then keys inserted where the fit is loosest until
    /// there are this many, however little they tighten it; a twin keyed as its twin is
    /// (`super::alike`).
    Exactly(usize),
}

/// Fits a sweep to `part`, recording each step: from the user's axis, else from the part's
/// skeleton (a coarse part from its four starts, see the [module docs](super)), else from its
/// principal axis; its keys counted as `key_count` says.
pub fn run(
    part: &Part,
    options: &FitOptions,
    smoothing: f64,
    key_count: KeyCount,
) -> Result<(Fitted, Vec<FitStep>), FitError> {
    if let Some(points) = &options.axis {
        let axis = Polyline::new(points).ok_or(FitError::Axis)?;
        return run_from(part, options, axis, None, false, smoothing, key_count);
    }
    let Some(skeleton) = skeleton(part) else {
        let (centroid, direction) = principal_axis(&part.positions);
        let axis = Polyline::new(&[centroid - direction, centroid + direction]).ok_or(FitError::Flat)?;
        return run_from(part, options, axis, None, false, smoothing, key_count);
    };
    if part.positions.len() >= options.keys * options.radii {
        return run_from(part, options, skeleton.axis.clone(), skeleton.start_normal, true, smoothing, key_count);
    }
    let mut starts = coarse_starts(part, options, &skeleton, smoothing, key_count);
    let first = starts.remove(0)?;
    Ok(kept_start(part, first, starts.into_iter().filter_map(Result::ok)))
}

/// A fit and its steps.
pub type Run = (Fitted, Vec<FitStep>);

/// A coarse part's fits from its starts, fitted side by side (see the [module docs](super)):
/// the centered skeleton with the keys' planes following it, then normal to it, then the level
/// skeleton (its points before centering) each way. Where the level skeleton is the centered
/// one (a fifth of the dino's and the faerie's coarse parts), its starts are those already
/// tried, and there are two.
pub fn coarse_starts(
    part: &Part,
    options: &FitOptions,
    skeleton: &Skeleton,
    smoothing: f64,
    key_count: KeyCount,
) -> Vec<Result<Run, FitError>> {
    let mut starts = vec![(&skeleton.axis, true), (&skeleton.axis, false)];
    if skeleton.level_axis != skeleton.axis {
        starts.extend([(&skeleton.level_axis, true), (&skeleton.level_axis, false)]);
    }
    starts
        .par_iter()
        .map(|&(axis, follows)| {
            run_from(part, options, axis.clone(), skeleton.start_normal, follows, smoothing, key_count)
        })
        .collect()
}

/// Of a coarse part's fits from its starts, in order (`first`, then `others`), the one kept:
/// weighed by [`start_score`], another start is kept where its keys stay on the part and the
/// kept one's run astray, or where both or neither do and it is tighter by
/// [`OTHER_START_MARGIN`].
pub fn kept_start(part: &Part, first: Run, others: impl IntoIterator<Item = Run>) -> Run {
    let centroids = part.triangle_centroids();
    let first_score = start_score(&first, &centroids);
    let (mut best, mut best_score) = (first, first_score);
    for run in others {
        let run_score = start_score(&run, &centroids);
        let beats = match (run_score.0, best_score.0) {
            (false, true) => true,
            (true, false) => false,
            _ => run_score.1 < (1.0 - OTHER_START_MARGIN) * best_score.1,
        };
        if beats {
            (best, best_score) = (run, run_score);
        }
    }
    best
}

/// How a start's fit is weighed ([`kept_start`]): whether its keys run astray of the part
/// ([`astray`]: they fold back or zigzag), and its RMS |d| at the vertices or at the
/// triangles' `centroids`, the worse of the two (radii fitted through a coarse part's vertices
/// may bulge between them). A start whose keys run astray loses to any whose keys do not: the
/// faerie's head, a coarse ball, was fitted tightest from its level skeleton by keys that
/// zigzag through it (and was left out as folded), and along it from its centered skeleton;
/// and a whole component's skeleton starts at an extreme vertex that rounding picks among
/// near ties, so mirror images of one part took different starts.
pub fn start_score(run: &Run, centroids: &[DVec3]) -> (bool, f64) {
    let between = measure(&run.0.sweep, centroids).quality.rms_d;
    (astray(&run.0.keys), run.0.measured.quality.rms_d.max(between))
}

/// Fits a sweep to `part` from the first guess `axis`; `follows`: the keys' planes stay normal
/// to it; its keys counted as `key_count` says.
fn run_from(
    part: &Part,
    options: &FitOptions,
    axis: Polyline,
    start_normal: Option<DVec3>,
    follows: bool,
    smoothing: f64,
    key_count: KeyCount,
) -> Result<(Fitted, Vec<FitStep>), FitError> {
    let along: Vec<f64> = part.positions.iter().map(|&p| axis.project(p)).collect();
    let (lo, hi) = along.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &s| (lo.min(s), hi.max(s)));
    let length = hi - lo;
    if length.is_nan() || length <= 0.0 {
        return Err(FitError::Flat);
    }
    let reference = reference_direction(&part.positions, axis.point(0.0), axis.tangent(0.0), axis.length());
    let skeleton = follows.then(|| axis.clone());
    let fitter = Fitter {
        part,
        options,
        length,
        reference,
        start_normal,
        skeleton,
        smoothing,
        end_sections: RefCell::default(),
    };
    let margin = END_MARGIN * length;
    let (count, most_keys) = match key_count {
        KeyCount::Inserted => (options.keys, options.max_keys),
        KeyCount::Exactly(count) => (options.keys.min(count), count),
    };
    let stations: Vec<Station> = (0..count)
        .map(|k| {
            let s = lo - margin + (length + 2.0 * margin) * k as f64 / (count - 1) as f64;
            let normal = if follows { axis.chord_tangent(s, SKELETON_CHORD * axis.length()) } else { axis.tangent(s) };
            Station { center: axis.point(s), normal }
        })
        .collect();

    let mut steps = vec![fitter.rough(&axis, &stations)?];
    let mut fitted = fitter.pass(&stations)?;
    steps.push(fitter.step(format!("{} key sections cut along the axis", fitted.keys.len()), &fitted));
    fitted = fitter.recenter(fitted)?;
    steps.push(fitter.step("keys re-centered on their sections".to_string(), &fitted));

    // Insertion goes on through one round that does not tighten the fit (a key inserted at a
    // bend may need its neighbours' before it pays), keeping the tightest fit seen.
    let forced = matches!(key_count, KeyCount::Exactly(_));
    let mut trial = fitted.clone();
    let mut stale = 0;
    while trial.keys.len() < most_keys && (forced || stale < STALE_ROUNDS) {
        let Some(refined) = fitter.insert_keys(&trial, most_keys, forced)? else { break };
        if forced {
            if refined.keys.len() <= trial.keys.len() {
                break;
            }
            let inserted = refined.keys.len() - fitted.keys.len();
            fitted = refined.clone();
            trial = refined;
            let label = format!("{inserted} keys inserted where the fit was loosest, {} in all", fitted.keys.len());
            steps.push(fitter.step(label, &fitted));
            continue;
        }
        trial = refined;
        if trial.measured.quality.rms_d >= fitted.measured.quality.rms_d {
            stale += 1;
            continue;
        }
        stale = 0;
        let inserted = trial.keys.len() - fitted.keys.len();
        fitted = trial.clone();
        let label = format!("{inserted} keys inserted where the fit was loose, {} in all", fitted.keys.len());
        steps.push(fitter.step(label, &fitted));
    }
    if let Some(polished) = fitter.least_squares(&fitted)? {
        fitted = polished;
        steps.push(fitter.step(LEAST_SQUARES_STEP.to_string(), &fitted));
    }
    Ok((fitted, steps))
}

struct Fitter<'a> {
    part: &'a Part,
    options: &'a FitOptions,
    length: f64,
    /// The direction θ = 0 of key 0 is taken from ([`reference_direction`]).
    reference: Option<DVec3>,
    /// The unit normal of the plane of the loop the skeleton starts from (the part's rim),
    /// pointing into the part; key 0 lies in a plane with this normal, and planes near it
    /// tilt towards it where they would leave the part through its rim.
    start_normal: Option<DVec3>,
    /// The part's skeleton, when it is the first guess: the keys' planes stay normal to it
    /// (its chord tangent over [`SKELETON_CHORD`] of its length) as they are re-centered.
    skeleton: Option<Polyline>,
    /// The weight of the radii's second differences in a second least-squares fit where the
    /// first is not kept ([`fitted_radii`]); 0 for none.
    smoothing: f64,
    /// The end sections found so far, by their station, frame and inward direction: an end
    /// key's plane often stays put from pass to pass (key 0 in the plane of the part's rim; on
    /// the beast, a public mesh, three in five end sections were found before).
    end_sections: RefCell<HashMap<[u64; 10], Option<Cut>>>,
}

impl Fitter<'_> {
    /// Fig. 3a: a circular sweep along the first axis enclosing every vertex.
    fn rough(&self, axis: &Polyline, stations: &[Station]) -> Result<FitStep, FitError> {
        let radius = self.part.positions.iter().map(|&p| p.distance(axis.point(axis.project(p)))).fold(0.0, f64::max);
        let stations = self.with_ends_past_the_part(self.attached_start(stations.to_vec()));
        let frames = transported_frames(&stations.iter().map(|s| s.normal).collect::<Vec<_>>(), self.reference);
        let keys: Vec<Key> =
            stations.iter().zip(frames).map(|(s, q)| Key::circle(s.center, q, radius, self.options.radii)).collect();
        let sweep = Sweep::try_new(&keys, None)?;
        let quality = measure(&sweep, &self.part.positions).quality;
        Ok(FitStep { label: "rough sweep enclosing the part".to_string(), keys, quality })
    }

    /// One pass: end planes just past the part, frames transported along the normals, each
    /// key re-centered on its section with radii sampled from the new center. A key whose
    /// section is partial (its plane leaves the part through the part's open rim, as near a
    /// slanted selection boundary) takes its center from the line through the two nearest
    /// complete keys on its inner side and its radii from the nearest complete key.
    fn pass(&self, stations: &[Station]) -> Result<Fitted, FitError> {
        let mut stations = self.with_ends_past_the_part(self.attached_start(stations.to_vec()));
        let mut frames = transported_frames(&stations.iter().map(|s| s.normal).collect::<Vec<_>>(), self.reference);
        let last = stations.len() - 1;
        let mut cuts: Vec<Option<Cut>> = Vec::with_capacity(stations.len());
        for i in 0..=last {
            let (station, rotation) = (stations[i], frames[i]);
            cuts.push(match i {
                0 => self.end_section(&station, rotation, station.normal),
                i if i == last => self.end_section(&station, rotation, -station.normal),
                _ => {
                    let cut = self.section(station.center, rotation);
                    match cut {
                        Some(cut) if cut.complete() => Some(cut),
                        _ => match self.complete_nearby(&stations, i, rotation) {
                            Some((moved, turned, complete)) => {
                                stations[i] = moved;
                                frames[i] = turned;
                                Some(complete)
                            }
                            None => cut,
                        },
                    }
                }
            });
        }
        for i in 1..frames.len() {
            if frames[i - 1].dot(frames[i]) < 0.0 {
                frames[i] = -frames[i];
            }
        }
        let complete: Vec<usize> = (0..cuts.len()).filter(|&i| cuts[i].as_ref().is_some_and(Cut::complete)).collect();
        let mut centers = Vec::with_capacity(stations.len());
        let mut radii: Vec<Option<Vec<f64>>> = Vec::with_capacity(stations.len());
        let mut sections = Vec::with_capacity(stations.len());
        for (i, (station, cut)) in stations.iter().zip(&cuts).enumerate() {
            let mut report = cut.as_ref().map_or(SectionReport::MISSED, |c| c.report);
            match cut {
                Some(cut) if cut.complete() => {
                    centers.push(cut.center);
                    radii.push(Some(cut.radii.clone()));
                }
                _ if !complete.is_empty() => {
                    let inner = inner_neighbours(&complete, i, last);
                    let line = match inner[..] {
                        [a, b, ..] => Some((cuts[a].as_ref(), cuts[b].as_ref())),
                        _ => None,
                    };
                    let center = match line {
                        Some((Some(a), Some(b))) => extrapolate(a.center, b.center, station),
                        _ => None,
                    };
                    let center = center.unwrap_or_else(|| cut.as_ref().map_or(station.center, |c| c.center));
                    let neighbour = cuts[inner[0]].as_ref().map(|c| c.radii.clone());
                    radii.push(match (cut, neighbour) {
                        (Some(cut), Some(neighbour)) => Some(partial_radii(cut, center, &neighbour)),
                        (_, neighbour) => neighbour,
                    });
                    centers.push(center);
                    report.borrowed = true;
                }
                _ => {
                    centers.push(cut.as_ref().map_or(station.center, |c| c.center));
                    radii.push(cut.as_ref().map(|c| c.radii.clone()));
                }
            }
            sections.push(report);
        }
        let radii = fill_missing_keys(radii).ok_or(FitError::NoSection)?;
        let keys: Vec<Key> = centers
            .into_iter()
            .zip(frames)
            .zip(radii)
            .map(|((center, rotation), radii)| Key { center, rotation, radii })
            .collect();
        let sweep = Sweep::try_new(&keys, None)?;
        let measured = measure(&sweep, &self.part.positions);
        Ok(Fitted { keys, sections, sweep, measured })
    }

    /// Key 0's plane turned to the start loop's plane, where the skeleton starts at one: a
    /// part cut obliquely from the rest of the mesh starts in the plane of its cut.
    fn attached_start(&self, mut stations: Vec<Station>) -> Vec<Station> {
        if let Some(normal) = self.start_normal {
            stations[0].normal = normal;
        }
        stations
    }

    /// A complete section near inner station `i`, whose own plane leaves the part through its
    /// rim or misses some rays: the plane moved along its normal away from the nearer end by
    /// 0, 0.2, 0.4 and 0.6 of the distance to the nearest neighbouring station, at each
    /// distance first untilted, then tilted half and all the way towards key 0's plane (for a
    /// key in the first half, where [`Fitter::start_normal`] is known). The first complete one, with its
    /// station and its frame (`rotation` turned by the tilt); `None` when none is complete.
    fn complete_nearby(&self, stations: &[Station], i: usize, rotation: DQuat) -> Option<(Station, DQuat, Cut)> {
        let station = stations[i];
        let last = stations.len() - 1;
        let first_half = 2 * i <= last;
        let spacing =
            station.center.distance(stations[i - 1].center).min(station.center.distance(stations[i + 1].center));
        let away = if first_half { station.normal } else { -station.normal };
        let start = self.start_normal.filter(|_| first_half);
        let tilts: &[f64] = if start.is_some() { &[0.0, 0.5, 1.0] } else { &[0.0] };
        let mut candidates: Vec<Station> = Vec::new();
        for f in [0.0, 0.2, 0.4, 0.6] {
            for &w in tilts {
                let normal =
                    start.map_or(Some(station.normal), |s| (station.normal * (1.0 - w) + s * w).try_normalize());
                if let Some(normal) = normal.filter(|_| f > 0.0 || w > 0.0) {
                    candidates.push(Station { center: station.center + away * (f * spacing), normal });
                }
            }
        }
        candidates.into_iter().find_map(|candidate| {
            let turned = DQuat::from_rotation_arc(station.normal, candidate.normal) * rotation;
            let cut = self.closed_section(candidate.center, turned)?;
            cut.complete().then_some((candidate, turned, cut))
        })
    }

    /// An end key's section: its plane lies just past the part, so the section is taken from
    /// the first complete section found inside it (see [`END_INSETS`]), moved back onto the
    /// end plane; where a second complete section lies further in, the radii are extrapolated
    /// linearly to the end plane, never growing and never below zero, so that a part narrowing
    /// to a tip gets a narrow end. Found once per station, frame and direction
    /// ([`Fitter::end_sections`]).
    fn end_section(&self, station: &Station, rotation: DQuat, inward: DVec3) -> Option<Cut> {
        let mut key = [0u64; 10];
        let values = station.center.to_array().into_iter().chain(rotation.to_array()).chain(inward.to_array());
        for (slot, value) in key.iter_mut().zip(values) {
            *slot = value.to_bits();
        }
        if let Some(found) = self.end_sections.borrow().get(&key) {
            return found.clone();
        }
        let found = self.end_section_anew(station, rotation, inward);
        self.end_sections.borrow_mut().insert(key, found.clone());
        found
    }

    /// [`Fitter::end_section`], found anew.
    fn end_section_anew(&self, station: &Station, rotation: DQuat, inward: DVec3) -> Option<Cut> {
        let mut complete: Vec<(f64, Cut)> = Vec::new();
        let mut partial: Option<Cut> = None;
        for &inset in &END_INSETS {
            let offset = inward * inset * self.length;
            let Some(mut cut) = self.section(station.center + offset, rotation) else { continue };
            cut.center -= offset;
            if cut.complete() {
                complete.push((inset, cut));
                if complete.len() == 2 {
                    break;
                }
            } else if partial.as_ref().is_none_or(|best| cut.report.missed < best.report.missed) {
                partial = Some(cut);
            }
        }
        let mut complete = complete.into_iter();
        match (complete.next(), complete.next()) {
            (Some((a, mut near)), Some((b, far))) => {
                let reach = a / (b - a);
                for (r, f) in near.radii.iter_mut().zip(&far.radii) {
                    *r = (*r + (*r - f) * reach).clamp(0.0, *r);
                }
                Some(near)
            }
            (Some((_, near)), None) => Some(near),
            (None, _) => partial,
        }
    }

    /// The section of the part in the plane through `origin` with frame `rotation`: its
    /// center, its radii and how the rays met it; `None` when the plane misses the part or
    /// grazes it in a single segment (whose rays along the segment meet its ends or not as
    /// rounding falls, so a rigidly moved part would get another fit).
    fn section(&self, origin: DVec3, rotation: DQuat) -> Option<Cut> {
        self.section_if(origin, rotation, true)
    }

    /// [`Fitter::section`], `None` also where the section is open: such a section is never
    /// complete ([`Cut::complete`]), and a search for a complete one need not sample it.
    fn closed_section(&self, origin: DVec3, rotation: DQuat) -> Option<Cut> {
        self.section_if(origin, rotation, false)
    }

    /// [`Fitter::section`]; an open section only where `open_too`.
    fn section_if(&self, origin: DVec3, rotation: DQuat, open_too: bool) -> Option<Cut> {
        let plane = Plane { origin, x: rotation * DVec3::X, y: rotation * DVec3::Y, normal: rotation * DVec3::Z };
        let contours = cut(self.part, &plane);
        let chosen = around(&contours, DVec2::ZERO)?;
        if chosen.iter().map(|c| c.points.len()).sum::<usize>() < 3 {
            return None;
        }
        let open = chosen.iter().any(|c| !c.closed);
        if open && !open_too {
            return None;
        }
        let middle = star_center(&chosen, center(&chosen));
        let sampled = sample(&chosen, middle, self.options.radii)?;
        let report = SectionReport {
            cut: true,
            open,
            several_crossings: sampled.several_crossings,
            missed: sampled.missed,
            borrowed: false,
        };
        let contours = chosen.into_iter().cloned().collect();
        Some(Cut { center: plane.point_at(middle), radii: sampled.radii, report, plane, contours })
    }

    /// Further re-centering passes, keeping the tightest fit (smallest RMS |d|) seen.
    fn recenter(&self, mut fitted: Fitted) -> Result<Fitted, FitError> {
        let mut current = fitted.clone();
        for _ in 1..RECENTER_PASSES {
            current = self.pass(&self.stations_of(&current))?;
            if current.measured.quality.rms_d < fitted.measured.quality.rms_d {
                fitted = current.clone();
            }
        }
        Ok(fitted)
    }

    /// The stations of fitted keys, with normals along the skeleton's chord tangent at the
    /// point nearest each key's center when the skeleton is the first guess; otherwise along
    /// the tangent C′(u_i) of their sweep, each inner one then tilted to the plane of least
    /// section area nearby. An end key
    /// takes the normal of its inner neighbour: the tangent at the very end of a natural
    /// spline swings with every move of the end key, the one inside does not.
    fn stations_of(&self, fitted: &Fitted) -> Vec<Station> {
        let knots = fitted.sweep.knots();
        let last = fitted.keys.len() - 1;
        let tangent = |i: usize| {
            let key = &fitted.keys[i];
            fitted.sweep.center_derivative(knots[i]).try_normalize().unwrap_or(key.rotation * DVec3::Z)
        };
        let mut stations: Vec<Station> = (0..=last)
            .map(|i| {
                let center = fitted.keys[i].center;
                if let Some(skeleton) = &self.skeleton {
                    let s = skeleton.project(center);
                    return Station { center, normal: skeleton.chord_tangent(s, SKELETON_CHORD * skeleton.length()) };
                }
                let station = Station { center, normal: tangent(i) };
                if i == 0 || i == last { station } else { self.least_area(station) }
            })
            .collect();
        if last >= 2 {
            stations[0].normal = stations[1].normal;
            stations[last].normal = stations[last - 1].normal;
        }
        stations
    }

    /// The station's plane tilted (by up to [`TILTS`] in two directions) to the one whose
    /// closed section around the center has the least area: the plane most nearly
    /// perpendicular to the part there.
    fn least_area(&self, station: Station) -> Station {
        let side = first_x_axis(station.normal, self.reference);
        let up = station.normal.cross(side);
        let area = |normal: DVec3| -> f64 {
            let x = normal.any_orthonormal_vector();
            let plane = Plane { origin: station.center, x, y: normal.cross(x), normal };
            let contours = cut(self.part, &plane);
            match around(&contours, DVec2::ZERO) {
                Some(chosen) if chosen.iter().all(|c| c.closed) => chosen.iter().map(|c| c.signed_area().abs()).sum(),
                _ => f64::INFINITY,
            }
        };
        let mut best = (area(station.normal), station.normal);
        if !best.0.is_finite() {
            return station;
        }
        for a in TILTS {
            for b in TILTS {
                let normal = (station.normal + side * a.tan() + up * b.tan()).normalize();
                let candidate = area(normal);
                if candidate < best.0 {
                    best = (candidate, normal);
                }
            }
        }
        Station { center: station.center, normal: best.1 }
    }

    /// Moves the end stations along their normals so that every vertex lies strictly between
    /// the end planes, a small margin inside each: then ⟨v − C(t), N(t)⟩ changes sign on
    /// [0, 1] and every vertex binds with a root.
    fn with_ends_past_the_part(&self, mut stations: Vec<Station>) -> Vec<Station> {
        let margin = END_MARGIN * self.length;
        let first = stations[0];
        let nearest =
            self.part.positions.iter().map(|&v| (v - first.center).dot(first.normal)).fold(f64::INFINITY, f64::min);
        stations[0].center += first.normal * (nearest - margin);
        let last_index = stations.len() - 1;
        let last = stations[last_index];
        let farthest =
            self.part.positions.iter().map(|&v| (v - last.center).dot(last.normal)).fold(f64::NEG_INFINITY, f64::max);
        stations[last_index].center += last.normal * (farthest + margin);
        stations
    }

    /// Inserts a key in the middle of each loose knot interval (RMS d above the tolerance),
    /// loosest first, up to `most_keys`, then re-centers all keys. `None` when no interval is
    /// loose; where `forced`, every interval is loose then, loosest first.
    fn insert_keys(&self, fitted: &Fitted, most_keys: usize, forced: bool) -> Result<Option<Fitted>, FitError> {
        let rms = &fitted.measured.interval_rms;
        let mut loose: Vec<usize> = (0..rms.len()).filter(|&k| rms[k] > self.options.tolerance).collect();
        if loose.is_empty() && forced {
            loose = (0..rms.len()).collect();
        }
        if loose.is_empty() {
            return Ok(None);
        }
        loose.sort_by(|&a, &b| rms[b].total_cmp(&rms[a]).then(a.cmp(&b)));
        loose.truncate(most_keys - fitted.keys.len());
        loose.sort_unstable();
        let knots = fitted.sweep.knots();
        let mut stations = Vec::with_capacity(fitted.keys.len() + loose.len());
        for (k, station) in self.stations_of(fitted).into_iter().enumerate() {
            stations.push(station);
            if loose.binary_search(&k).is_ok() {
                let middle = 0.5 * (knots[k] + knots[k + 1]);
                let center = fitted.sweep.center(middle);
                let normal = match &self.skeleton {
                    Some(skeleton) => {
                        skeleton.chord_tangent(skeleton.project(center), SKELETON_CHORD * skeleton.length())
                    }
                    None => fitted.sweep.center_derivative(middle).try_normalize().unwrap_or(station.normal),
                };
                stations.push(Station { center, normal });
            }
        }
        let refined = self.pass(&stations)?;
        Ok(Some(self.recenter(refined)?))
    }

    /// The fitted keys with their radii fitted to the part's surface by least squares
    /// ([`fitted_radii`]), where that tightens the fit; `None` where it does not. A part with
    /// fewer than [`SAMPLES_PER_RADIUS`] vertices per radius is sampled at its edges' midpoints
    /// too ([`Part::surface_samples`]): fitted to its vertices alone, the radii of a coarse part
    /// pass through them and bulge between (spot's hind legs: RMS |d| 3% at the vertices, 24% at
    /// the edges' midpoints, against 13% and 8% with the sections' radii). The fit is then kept
    /// only where it tightens the vertices without loosening the triangles' centroids, points
    /// of the surface it was not fitted to. Where it is not kept, and the fit smooths, the
    /// radii are fitted once more with their second differences weighted by
    /// [`Fitter::smoothing`], and kept on the same terms.
    fn least_squares(&self, fitted: &Fitted) -> Result<Option<Fitted>, FitError> {
        match radii_fitted_by_least_squares(self.part, fitted, 0.0)? {
            None if self.smoothing > 0.0 => radii_fitted_by_least_squares(self.part, fitted, self.smoothing),
            plain => Ok(plain),
        }
    }

    fn step(&self, label: String, fitted: &Fitted) -> FitStep {
        FitStep { label, keys: fitted.keys.clone(), quality: fitted.measured.quality }
    }
}

/// [`Fitter::least_squares`] with the radii's second differences weighted by `smoothing`
/// ([`fitted_radii`]).
fn radii_fitted_by_least_squares(part: &Part, fitted: &Fitted, smoothing: f64) -> Result<Option<Fitted>, FitError> {
    let radii_count = fitted.keys.iter().map(|k| k.radii.len()).sum::<usize>();
    let samples = part.surface_samples(SAMPLES_PER_RADIUS * radii_count);
    let Some(radii) = fitted_radii(&fitted.sweep, &fitted.keys, &samples, smoothing) else { return Ok(None) };
    let keys: Vec<Key> = fitted.keys.iter().zip(radii).map(|(k, radii)| Key { radii, ..k.clone() }).collect();
    let sweep = Sweep::try_new(&keys, None)?;
    let measured = measure(&sweep, &part.positions);
    if measured.quality.rms_d >= fitted.measured.quality.rms_d {
        return Ok(None);
    }
    if samples.len() > part.positions.len() {
        let centroids = part.triangle_centroids();
        if measure(&sweep, &centroids).quality.rms_d > measure(&fitted.sweep, &centroids).quality.rms_d {
            return Ok(None);
        }
    }
    Ok(Some(Fitted { keys, sections: fitted.sections.clone(), sweep, measured }))
}

/// `keys`, fitted to `part` with their sections' radii, with their radii fitted to its
/// surface by least squares and their second differences weighted by [`SMOOTHING`], where
/// that tightens the fit as [`Fitter::least_squares`] keeps one; `None` where it does not.
/// For a kept part whose plain least squares was not kept: with 17 keys of 32 radii for its
/// 60 vertices, the radii of the beast's knob (a public mesh) bulged between the vertices and
/// edges' midpoints they were fitted to (RMS |d| 0.8% at its vertices, 61% at its triangles'
/// centroids, against 32% and 17% with its sections' radii); smoothed in the start autorig
/// keeps when it fits the knob again, 6.9% and 14%. Only after the search: fits compared
/// while chains are searched keep the plain least squares.
pub fn smoothed(part: &Part, keys: &[Key]) -> Result<Option<(Vec<Key>, Measured)>, FitError> {
    // With [`SAMPLES_PER_RADIUS`] vertices per radius, fitted to its vertices alone, a part's
    // plain least squares was kept wherever it tightened the fit.
    if part.positions.len() >= SAMPLES_PER_RADIUS * keys.iter().map(|k| k.radii.len()).sum::<usize>() {
        return Ok(None);
    }
    let sweep = Sweep::try_new(keys, None)?;
    let measured = measure(&sweep, &part.positions);
    let fitted = Fitted { keys: keys.to_vec(), sections: Vec::new(), sweep, measured };
    Ok(radii_fitted_by_least_squares(part, &fitted, SMOOTHING)?.map(|smoothed| (smoothed.keys, smoothed.measured)))
}

/// Gives keys whose plane missed the part the radii of the nearest keys that have some,
/// interpolated linearly by key index between them; `None` when no key has radii.
fn fill_missing_keys(radii: Vec<Option<Vec<f64>>>) -> Option<Vec<Vec<f64>>> {
    let present: Vec<usize> = (0..radii.len()).filter(|&i| radii[i].is_some()).collect();
    let (&first, &last) = (present.first()?, present.last()?);
    let filled = (0..radii.len())
        .map(|i| {
            if let Some(r) = &radii[i] {
                return r.clone();
            }
            if i < first {
                return radii[first].clone().unwrap_or_default();
            }
            if i > last {
                return radii[last].clone().unwrap_or_default();
            }
            let before = present[present.partition_point(|&p| p < i) - 1];
            let after = present[present.partition_point(|&p| p < i)];
            let u = (i - before) as f64 / (after - before) as f64;
            let (a, b) = (radii[before].as_deref().unwrap_or_default(), radii[after].as_deref().unwrap_or_default());
            a.iter().zip(b).map(|(a, b)| a + (b - a) * u).collect()
        })
        .collect();
    Some(filled)
}
