//! Rigs and poses: named sweeps, their key cross-sections, and the vertices each one owns.
//!
//! Data flow: **rig** → sweep → sweep coefficients → bind → deform → normals → output.
//!
//! A [`Rig`] is the rest configuration: its sweeps' keys fix the knots u_i and the binding of
//! every vertex. A pose gives new keys for the same sweeps (matched by name, same key counts
//! and radius counts); posed sweeps reuse the rest knots, so a vertex bound between keys i and
//! i+1 stays between them.

mod bend_twist_taper;
mod binding;
#[cfg(feature = "json")]
pub(crate) mod bounded;
mod document;
mod error;
mod links;
mod ownership;
mod pose_into;

use std::path::{Path, PathBuf};

pub use bend_twist_taper::BendTwistTaper;
pub use document::{FORMAT, KeyDocument, LinkKind, ParentLink, RigDocument, SweepDocument, VERSION, VertexSelection};
pub use error::{RigError, RigErrorKind};
pub use links::{KeyBinding, Link};
pub use pose_into::PoseBuffer;

use crate::sweep::{Key, RotationInterpolation, Sweep, SweepSystems};

/// One named sweep of a rig, as written in the rig file.
#[derive(Clone, Debug, PartialEq)]
pub struct RigSweep {
    /// Unique name; poses refer to the sweep by it.
    pub name: String,
    /// The vertices it owns; `None`: none.
    pub vertices: Option<VertexSelection>,
    /// Rest key cross-sections.
    pub keys: Vec<Key>,
    /// Explicit knots, or `None` for the chord length of the rest centers.
    pub knots: Option<Vec<f64>>,
    /// Its parent in the hierarchy, or `None` for a root.
    pub parent: Option<ParentLink>,
    /// Width W of the band, in mesh units measured along the surface from the part's boundary,
    /// over which the sweep's deformation fades into its neighbour's (or the rest position);
    /// 0: a hard boundary (see [`crate::bind::falloff`]).
    pub falloff: f64,
    /// How R(t) interpolates the key rotations (the paper's linear one unless the rig file
    /// says otherwise).
    pub rotation: RotationInterpolation,
}

impl RigSweep {
    /// A root sweep named `name` through the rest `keys`, owning no vertices, with chord-length
    /// knots and a hard boundary; the `owning`, `with_*` methods set the rest.
    pub fn new(name: impl Into<String>, keys: Vec<Key>) -> RigSweep {
        RigSweep {
            name: name.into(),
            vertices: None,
            keys,
            knots: None,
            parent: None,
            falloff: 0.0,
            rotation: RotationInterpolation::Linear,
        }
    }

    /// The same sweep owning `vertices`.
    pub fn owning(self, vertices: VertexSelection) -> RigSweep {
        RigSweep { vertices: Some(vertices), ..self }
    }

    /// The same sweep with explicit knots t_i (one per key, increasing).
    pub fn with_knots(self, knots: Vec<f64>) -> RigSweep {
        RigSweep { knots: Some(knots), ..self }
    }

    /// The same sweep as a child of `parent` in the hierarchy (§5).
    pub fn with_parent(self, parent: ParentLink) -> RigSweep {
        RigSweep { parent: Some(parent), ..self }
    }

    /// The same sweep with R(t) interpolating its key rotations as `rotation` says.
    pub fn with_rotation_interpolation(self, rotation: RotationInterpolation) -> RigSweep {
        RigSweep { rotation, ..self }
    }

    /// The same sweep with a falloff band of width `falloff` (mesh units along the surface).
    pub fn with_falloff(self, falloff: f64) -> RigSweep {
        RigSweep { falloff, ..self }
    }
}

/// A validated rest rig: its sweeps and their rest sweep surfaces.
#[derive(Clone, Debug)]
pub struct Rig {
    file: Option<PathBuf>,
    sweeps: Vec<RigSweep>,
    rest: Vec<Sweep>,
    links: Vec<Option<Link>>,
    /// The factorized spline systems of each rest sweep's knots and radius count, which every
    /// posed sweep shares ([`Rig::pose_into`]).
    systems: Vec<SweepSystems>,
}

impl Rig {
    /// Validates `sweeps` and builds their rest surfaces. Errors name the sweep and key at fault.
    pub fn new(sweeps: Vec<RigSweep>) -> Result<Rig, RigError> {
        Rig::build(sweeps, None)
    }

    #[cfg(feature = "json")]
    /// Reads and validates a rig file. Errors name the file, sweep and key at fault.
    pub fn load(path: &Path) -> Result<Rig, RigError> {
        let file = Some(path.to_path_buf());
        let document = read_document(path)?;
        Rig::from_document(&document, file)
    }

    /// Validates a parsed rig file; `file` is named in errors.
    pub fn from_document(document: &RigDocument, file: Option<PathBuf>) -> Result<Rig, RigError> {
        check_header(document, &file)?;
        let sweeps = document
            .sweeps
            .iter()
            .map(|sweep| RigSweep {
                name: sweep.name.clone(),
                vertices: sweep.vertices.clone(),
                keys: sweep.keys.iter().map(Key::from).collect(),
                knots: sweep.knots.clone(),
                parent: sweep.parent.clone(),
                falloff: sweep.falloff.unwrap_or(0.0),
                rotation: sweep.rotation_interpolation.or(document.rotation_interpolation).unwrap_or_default(),
            })
            .collect();
        Rig::build(sweeps, file)
    }

    fn build(sweeps: Vec<RigSweep>, file: Option<PathBuf>) -> Result<Rig, RigError> {
        let fail = |kind| RigError::new(file.clone(), kind);
        if sweeps.is_empty() {
            return Err(fail(RigErrorKind::NoSweeps));
        }
        check_sizes(&sweeps).map_err(fail)?;
        for (i, sweep) in sweeps.iter().enumerate() {
            if sweeps[..i].iter().any(|other| other.name == sweep.name) {
                return Err(fail(RigErrorKind::DuplicateName { name: sweep.name.clone() }));
            }
            check_falloff(sweep).map_err(fail)?;
        }
        let rest = sweeps
            .iter()
            .map(|sweep| {
                Sweep::try_new_with(&sweep.keys, sweep.knots.as_deref(), sweep.rotation)
                    .map_err(|source| fail(RigErrorKind::Sweep { sweep: sweep.name.clone(), source }))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let links = links::bind_links(&sweeps, &rest).map_err(fail)?;
        let systems = rest.iter().map(SweepSystems::of).collect();
        Ok(Rig { file, sweeps, rest, links, systems })
    }

    /// The rig file this rig was read from, if any.
    pub fn file(&self) -> Option<&Path> {
        self.file.as_deref()
    }

    /// The sweeps as given.
    pub fn sweeps(&self) -> &[RigSweep] {
        &self.sweeps
    }

    /// Each sweep's link to its parent in the hierarchy (§5), in the order of
    /// [`Rig::sweeps`]; `None` for a root.
    pub fn links(&self) -> &[Option<Link>] {
        &self.links
    }

    /// The index of the sweep named `name`.
    pub fn sweep_index(&self, name: &str) -> Option<usize> {
        self.sweeps.iter().position(|sweep| sweep.name == name)
    }

    /// The rest sweep surfaces, in the order of [`Rig::sweeps`].
    pub fn rest(&self) -> &[Sweep] {
        &self.rest
    }

    /// The rig as a file document.
    pub fn to_document(&self) -> RigDocument {
        self.document_with(|i| &self.sweeps[i].keys)
    }

    /// A pose file document for this rig with `keys[i]` as the keys of sweep i.
    pub fn pose_document(&self, keys: &[Vec<Key>]) -> RigDocument {
        self.document_with(|i| &keys[i])
    }

    fn document_with<'a>(&'a self, keys: impl Fn(usize) -> &'a Vec<Key>) -> RigDocument {
        RigDocument {
            format: FORMAT.to_string(),
            version: VERSION,
            rotation_interpolation: None,
            sweeps: self
                .sweeps
                .iter()
                .enumerate()
                .map(|(i, sweep)| SweepDocument {
                    name: sweep.name.clone(),
                    vertices: sweep.vertices.clone(),
                    keys: keys(i).iter().map(KeyDocument::from).collect(),
                    knots: sweep.knots.clone(),
                    parent: sweep.parent.clone(),
                    falloff: (sweep.falloff > 0.0).then_some(sweep.falloff),
                    rotation_interpolation: (sweep.rotation != RotationInterpolation::Linear).then_some(sweep.rotation),
                })
                .collect(),
        }
    }

    /// Each sweep's falloff width W ([`RigSweep::falloff`]), in the order of [`Rig::sweeps`].
    pub fn falloffs(&self) -> Vec<f64> {
        self.sweeps.iter().map(|sweep| sweep.falloff).collect()
    }

    /// The posed sweep surfaces for `keys[i]` on sweep i (rest knots), checked against the rest
    /// rig: same number of sweeps, keys and radii.
    /// A frame loop poses into storage made once instead: [`Rig::pose_into`], bit for bit the
    /// same sweeps without allocating.
    pub fn pose(&self, keys: &[Vec<Key>]) -> Result<Vec<Sweep>, RigError> {
        self.pose_named(keys.iter().zip(&self.sweeps).map(|(k, s)| (s.name.as_str(), k.as_slice())), None)
    }

    #[cfg(feature = "json")]
    /// Reads a pose file and returns the posed sweep surfaces in rig order. Errors name the
    /// pose file, sweep and key at fault.
    pub fn load_pose(&self, path: &Path) -> Result<Vec<Sweep>, RigError> {
        let document = read_document(path)?;
        self.pose_from_document(&document, Some(path.to_path_buf()))
    }

    /// The posed sweep surfaces of a parsed pose file; `file` is named in errors.
    pub fn pose_from_document(&self, document: &RigDocument, file: Option<PathBuf>) -> Result<Vec<Sweep>, RigError> {
        check_header(document, &file)?;
        let keys: Vec<(&str, Vec<Key>)> = document
            .sweeps
            .iter()
            .map(|sweep| (sweep.name.as_str(), sweep.keys.iter().map(Key::from).collect()))
            .collect();
        self.pose_named(keys.iter().map(|(name, keys)| (*name, keys.as_slice())), file)
    }

    fn pose_named<'a>(
        &self,
        posed: impl Iterator<Item = (&'a str, &'a [Key])> + Clone,
        file: Option<PathBuf>,
    ) -> Result<Vec<Sweep>, RigError> {
        let fail = |kind| RigError::new(file.clone(), kind);
        for (name, _) in posed.clone() {
            if !self.sweeps.iter().any(|sweep| sweep.name == name) {
                return Err(fail(RigErrorKind::PoseUnknownSweep { sweep: name.to_string() }));
            }
        }
        self.sweeps
            .iter()
            .zip(&self.rest)
            .enumerate()
            .map(|(index, (sweep, rest))| {
                let Some((_, keys)) = posed.clone().find(|(n, _)| *n == sweep.name) else {
                    return Err(fail(RigErrorKind::PoseMissingSweep { sweep: sweep.name.clone() }));
                };
                self.check_pose_structure(index, keys).map_err(fail)?;
                rest.try_posed(keys).map_err(|source| fail(RigErrorKind::Sweep { sweep: sweep.name.clone(), source }))
            })
            .collect()
    }

    /// Fails unless `keys` have sweep `index`'s rest structure: as many keys, each with the
    /// rest radius count M.
    fn check_pose_structure(&self, index: usize, keys: &[Key]) -> Result<(), RigErrorKind> {
        let (sweep, rest) = (&self.sweeps[index], &self.rest[index]);
        if keys.len() != sweep.keys.len() {
            let (expected, found) = (sweep.keys.len(), keys.len());
            return Err(RigErrorKind::PoseKeyCount { sweep: sweep.name.clone(), expected, found });
        }
        let expected = rest.radius_samples();
        if let Some((key, k)) = keys.iter().enumerate().find(|(_, k)| k.radii.len() != expected) {
            let found = k.radii.len();
            return Err(RigErrorKind::PoseRadiusCount { sweep: sweep.name.clone(), key, expected, found });
        }
        Ok(())
    }
}

#[cfg(feature = "json")]
impl RigDocument {
    /// Reads and parses a rig or pose file without validating it (see [`Rig::from_document`]);
    /// errors name the file.
    pub fn load(path: &Path) -> Result<RigDocument, RigError> {
        read_document(path)
    }
}

#[cfg(feature = "json")]
fn read_document(path: &Path) -> Result<RigDocument, RigError> {
    let file = Some(path.to_path_buf());
    let text = crate::limits::read_input_text(path).map_err(|e| RigError::new(file.clone(), RigErrorKind::Io(e)))?;
    RigDocument::parse(&text).map_err(|e| RigError::new(file, RigErrorKind::Json(e)))
}

/// At most [`MAX_SWEEPS`](crate::limits::MAX_SWEEPS) sweeps and
/// [`MAX_RADII_PER_RIG`](crate::limits::MAX_RADII_PER_RIG) radii in all, before any surface is
/// built (each sweep's keys and radii are bounded by [`Sweep::try_new`]).
fn check_sizes(sweeps: &[RigSweep]) -> Result<(), RigErrorKind> {
    if sweeps.len() > crate::limits::MAX_SWEEPS {
        return Err(RigErrorKind::TooManySweeps { count: sweeps.len() });
    }
    let mut total = 0usize;
    for sweep in sweeps {
        total = sweep.keys.iter().fold(total, |sum, key| sum.saturating_add(key.radii.len()));
        if total > crate::limits::MAX_RADII_PER_RIG {
            return Err(RigErrorKind::TooManyRadii { sweep: sweep.name.clone() });
        }
    }
    Ok(())
}

/// A falloff must be finite and not negative, and only a sweep that owns vertices can have one.
fn check_falloff(sweep: &RigSweep) -> Result<(), RigErrorKind> {
    let falloff = sweep.falloff;
    if !falloff.is_finite() || falloff < 0.0 {
        return Err(RigErrorKind::BadFalloff { sweep: sweep.name.clone(), falloff });
    }
    if falloff > 0.0 && sweep.vertices.is_none() {
        return Err(RigErrorKind::VirtualFalloff { sweep: sweep.name.clone() });
    }
    Ok(())
}

fn check_header(document: &RigDocument, file: &Option<PathBuf>) -> Result<(), RigError> {
    if document.format != FORMAT {
        return Err(RigError::new(file.clone(), RigErrorKind::Format { found: document.format.clone() }));
    }
    if document.version != VERSION {
        return Err(RigError::new(file.clone(), RigErrorKind::Version { found: document.version }));
    }
    Ok(())
}

#[cfg(test)]
mod tests;
