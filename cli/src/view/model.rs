//! What the viewer edits, apart from the window: the mesh, the rig (from a file, or fitted
//! in the viewer), the session of edits and its settings. Loading errors name the file.

use std::path::{Path, PathBuf};

use sweepffd::bind::MeshBindings;
use sweepffd::bind::falloff::BandWeight;
use sweepffd::edit::{BoundMesh, Edit, EditError, VolumeRule};
use sweepffd::mesh::{Mesh, Subdivision};
use sweepffd::rig::{FORMAT, Rig, RigDocument, VERSION, VertexSelection};
use sweepffd::sweep::{Key, Sweep};

use super::session::{Session, Settings};
use super::{Subdivide, ViewError};

/// The mesh, its rig and the edits.
pub struct Model {
    /// The mesh at rest.
    pub mesh: Mesh,
    /// How errors name the mesh.
    pub mesh_name: String,
    /// Its triangles (fan-triangulated faces).
    pub triangles: Vec<[u32; 3]>,
    /// Whether the mesh is closed, so its enclosed volume means something.
    pub closed: bool,
    /// Its bounding box diagonal, the widest falloff a sweep may have.
    pub diagonal: f64,
    /// The rig as a document (no sweeps until one is loaded or fitted).
    pub document: RigDocument,
    /// The rig, when it has sweeps.
    pub rig: Option<Rig>,
    /// The sweep owning each vertex, or `UNOWNED`.
    pub owners: Vec<u32>,
    /// The falloff weights of the band vertices ([`Rig::band_weights`]; empty without falloff).
    pub bands: Vec<BandWeight>,
    /// The edits, when there is a rig.
    pub session: Option<Session>,
    /// How edits are made.
    pub settings: Settings,
    /// Every vertex's binding, made when the mesh volume rule first needs it.
    bindings: Option<MeshBindings>,
}

impl Model {
    /// Loads the mesh (subdivided), the rig and a pose, with the volume rule to start with.
    pub fn load(
        mesh_path: &Path,
        rig: Option<&Path>,
        pose: Option<&Path>,
        subdivide: Subdivide,
        volume: VolumeRule,
    ) -> Result<Model, ViewError> {
        let mesh = Mesh::load(mesh_path).map_err(|e| ViewError::Input(e.to_string()))?;
        let (mesh, steps) = match subdivide {
            Subdivide::No => Ok((mesh, Vec::new())),
            Subdivide::Levels(levels) => mesh.subdivided_times(levels),
            Subdivide::Vertices(vertices) => mesh.subdivided_to(vertices),
        }
        .map_err(|e| ViewError::Input(format!("{}: subdividing: {e}", mesh_path.display())))?;
        let mesh_name = mesh_path.display().to_string();
        let document = match rig {
            Some(path) => {
                carry_selections(RigDocument::load(path).map_err(|e| ViewError::Input(e.to_string()))?, &steps)
            }
            None => RigDocument {
                format: FORMAT.to_string(),
                version: VERSION,
                rotation_interpolation: None,
                sweeps: Vec::new(),
            },
        };
        let triangles = mesh.faces.triangles().collect();
        let closed = mesh.is_closed();
        let diagonal = mesh.diagonal();
        let mut model = Model {
            mesh,
            mesh_name,
            triangles,
            closed,
            diagonal,
            document: RigDocument {
                format: FORMAT.to_string(),
                version: VERSION,
                rotation_interpolation: None,
                sweeps: Vec::new(),
            },
            rig: None,
            owners: Vec::new(),
            bands: Vec::new(),
            session: None,
            settings: Settings::default(),
            bindings: None,
        };
        model.set_rig(document, rig.map(Path::to_path_buf))?;
        if volume == VolumeRule::Mesh && !model.closed {
            let file = mesh_path.display();
            return Err(ViewError::Input(format!(
                "{file}: the mesh volume rule needs a closed mesh, and {file} is open"
            )));
        }
        model.settings.volume = volume;
        if let Some(path) = pose {
            model.load_pose(path)?;
        }
        Ok(model)
    }

    /// Replaces the rig (checking that it owns the mesh's vertices without conflict) and starts
    /// a new session from its rest keys.
    pub fn set_rig(&mut self, document: RigDocument, file: Option<PathBuf>) -> Result<(), ViewError> {
        if document.sweeps.is_empty() {
            self.rig = None;
            self.owners = vec![sweepffd::bind::UNOWNED; self.mesh.positions.len()];
            self.bands = Vec::new();
            self.session = None;
        } else {
            let rig = Rig::from_document(&document, file).map_err(|e| ViewError::Input(e.to_string()))?;
            self.owners = rig.owners(&self.mesh, &self.mesh_name).map_err(|e| ViewError::Input(e.to_string()))?;
            self.bands = rig.band_weights(&self.mesh, &self.owners);
            self.session = Some(Session::new(rig.sweeps().iter().map(|s| s.keys.clone()).collect()));
            self.rig = Some(rig);
        }
        self.document = document;
        self.bindings = None;
        Ok(())
    }

    /// Sets the falloff width W of sweep `sweep` (mesh units; 0: a hard boundary) in the rig and
    /// in its document (so a saved rig carries it), keeping the session: the keys, edits and
    /// history do not depend on it. The band weights are computed again, and the CPU bindings
    /// (the mesh volume rule's) made again when next needed. Errors name the sweep: a virtual
    /// sweep, a negative or non-finite width, or one wider than the mesh. Returns the sweep's name.
    pub fn set_falloff(&mut self, sweep: usize, width: f64) -> Result<String, ViewError> {
        let Some(rig) = &self.rig else {
            return Err(ViewError::Input("there is no rig, so no falloff to set".into()));
        };
        let Some(name) = rig.sweeps().get(sweep).map(|s| s.name.clone()) else {
            return Err(ViewError::Input(format!("the rig has no sweep {sweep}")));
        };
        let mut document = self.document.clone();
        // Rig validation refuses negative and non-finite widths, naming the sweep.
        document.sweeps[sweep].falloff = if width == 0.0 { None } else { Some(width) };
        let fail = |e: sweepffd::rig::RigError| ViewError::Input(e.to_string());
        let rig = Rig::from_document(&document, rig.file().map(Path::to_path_buf)).map_err(fail)?;
        rig.check_fits_mesh(&self.mesh, &self.mesh_name).map_err(fail)?;
        self.bands = rig.band_weights(&self.mesh, &self.owners);
        self.rig = Some(rig);
        self.document = document;
        self.bindings = None;
        Ok(name)
    }

    /// Starts a new session from the pose in `path`.
    pub fn load_pose(&mut self, path: &Path) -> Result<(), ViewError> {
        let Some(rig) = &self.rig else {
            return Err(ViewError::Input(format!("{}: there is no rig to pose", path.display())));
        };
        let document = RigDocument::load(path).map_err(|e| ViewError::Input(e.to_string()))?;
        // Checked against the rig, so errors name the file, sweep and key at fault.
        rig.pose_from_document(&document, Some(path.to_path_buf())).map_err(|e| ViewError::Input(e.to_string()))?;
        let keys: Vec<Vec<Key>> = rig
            .sweeps()
            .iter()
            .map(|sweep| {
                let posed = document.sweeps.iter().find(|s| s.name == sweep.name).expect("checked against the rig");
                posed.keys.iter().map(Key::from).collect()
            })
            .collect();
        self.session = Some(Session::new(keys));
        Ok(())
    }

    /// The posed sweeps of the current keys.
    pub fn posed(&self) -> Option<Result<Vec<Sweep>, ViewError>> {
        let (rig, session) = (self.rig.as_ref()?, self.session.as_ref()?);
        Some(rig.pose(session.keys()).map_err(|e| ViewError::Input(e.to_string())))
    }

    /// Applies `edit` as the gesture in progress ([`Session::preview`]) with the settings'
    /// hierarchy and volume rule; the mesh volume rule binds every vertex the first time.
    pub fn preview(&mut self, edit: Edit) -> Result<usize, EditError> {
        let Model { rig, session, mesh, owners, bindings, settings, .. } = self;
        let (Some(rig), Some(session)) = (rig.as_ref(), session.as_mut()) else {
            return Err(EditError::Invalid("there is no rig to edit".into()));
        };
        let bound = match settings.volume {
            VolumeRule::Mesh => {
                let bindings = bindings.get_or_insert_with(|| rig.bind_mesh(mesh, owners, &|_| {}));
                Some(BoundMesh { mesh, bindings })
            }
            _ => None,
        };
        session.preview(rig, edit, settings, bound)
    }

    /// Which vertices a sweep owns.
    pub fn taken(&self) -> Vec<bool> {
        self.owners.iter().map(|&o| o != sweepffd::bind::UNOWNED).collect()
    }
}

/// A rig's index selections carried through the subdivision `steps` (group and "all"
/// selections need no change).
fn carry_selections(mut document: RigDocument, steps: &[Subdivision]) -> RigDocument {
    for sweep in &mut document.sweeps {
        if let Some(VertexSelection::Indices(indices)) = &mut sweep.vertices {
            indices.sort_unstable();
            indices.dedup();
            for step in steps {
                *indices = step.carry(indices);
                indices.sort_unstable();
            }
        }
    }
    document
}
