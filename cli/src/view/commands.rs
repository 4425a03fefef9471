//! Keyboard and panel commands: settings, undo and redo, saving and loading, fitting a sweep to
//! the selected part or rigging the whole mesh, and the volumes the panel shows.

use std::io::Write;
use std::path::Path;

use super::ViewError;
use super::app::App;
use super::draw::MeshDraw;
use super::gesture::KeyTool;
use super::input::Command;
use sweepffd::atomic_file::write_atomically;
use sweepffd::edit::{DragMode, KeyMode, VolumeRule};
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::fit::{FitOptions, fit};

impl App {
    pub(super) fn command(&mut self, command: Command) {
        let settings = &mut self.model.settings;
        match command {
            Command::Undo | Command::Redo => {
                self.gesture = None;
                let Some(session) = &mut self.model.session else { return };
                let changed = if command == Command::Undo { session.undo() } else { session.redo() };
                if changed {
                    self.pose_changed = true;
                    self.mesh_volume_stale = true;
                }
            }
            Command::SavePose => self.save_pose(Path::new(&self.panel.pose_path.clone())),
            Command::LoadPose => self.load_pose(Path::new(&self.panel.pose_path.clone())),
            Command::SaveEdits => self.save_edits(Path::new(&self.panel.edits_path.clone())),
            Command::CycleSweeps => {
                self.panel.sweeps = self.panel.sweeps.next();
                self.overlay_changed = true;
            }
            Command::CycleDragMode => {
                settings.drag_mode = match settings.drag_mode {
                    DragMode::Both => DragMode::Translate,
                    DragMode::Translate => DragMode::Rotate,
                    DragMode::Rotate => DragMode::Both,
                }
            }
            Command::ToggleKeyMode => {
                settings.key_mode = match settings.key_mode {
                    KeyMode::Local => KeyMode::Independent,
                    KeyMode::Independent => KeyMode::Local,
                }
            }
            Command::ToggleHierarchy => settings.hierarchy = !settings.hierarchy,
            Command::ToggleBend => settings.bend = !settings.bend,
            Command::ToggleKeepLength => settings.keep_length = !settings.keep_length,
            Command::ToggleWeights => self.panel.paint_weights = !self.panel.paint_weights,
            Command::CycleVolume => {
                settings.volume = match settings.volume {
                    VolumeRule::None => VolumeRule::Total,
                    VolumeRule::Total => VolumeRule::Ratio,
                    // The mesh rule keeps an enclosed volume, which only a closed mesh has.
                    VolumeRule::Ratio if self.model.closed => VolumeRule::Mesh,
                    VolumeRule::Ratio | VolumeRule::Mesh => VolumeRule::None,
                }
            }
            Command::MoveTool => self.panel.tool = KeyTool::Move,
            Command::RotateTool => self.panel.tool = KeyTool::Rotate,
            Command::ScaleTool => self.panel.tool = KeyTool::Scale,
            Command::Fit => self.fit_part(),
            Command::AutoRig => {
                let outcome = self.try_auto_rig();
                self.report(outcome.map_err(|e| e.to_string()));
            }
            Command::ResetCamera => {
                let (min, max) = self.model.mesh.bounds();
                let size = self.size();
                self.camera = super::orbit::Orbit::framing(min.as_vec3(), max.as_vec3(), size.x / size.y);
            }
            Command::Cancel => {
                if let Some(session) = &mut self.model.session
                    && session.in_gesture()
                {
                    session.cancel();
                    self.pose_changed = true;
                }
                self.gesture = None;
                self.selected_key = None;
                self.part = None;
                self.show_part();
                self.overlay_changed = true;
            }
        }
    }

    /// Reports `outcome` in the panel (and in a script's report when it failed).
    pub(super) fn report(&mut self, outcome: Result<String, String>) {
        match outcome {
            Ok(message) => self.panel.status = message,
            Err(error) => {
                self.panel.status = error.clone();
                self.errors.push(error);
            }
        }
    }

    pub(super) fn save_pose(&mut self, path: &Path) {
        let outcome = match (&self.model.rig, &self.model.session) {
            (Some(rig), Some(session)) => rig
                .pose_document(session.committed())
                .try_to_json(path)
                .map_err(|e| e.to_string())
                .and_then(|text| write_text(path, &text))
                .map(|()| format!("pose saved to {}", path.display())),
            _ => Err("there is no rig, so no pose to save".to_string()),
        };
        self.report(outcome);
    }

    pub(super) fn save_edits(&mut self, path: &Path) {
        let outcome = match &self.model.session {
            Some(session) => {
                let edits = session.edits();
                sweepffd::edit::edits_to_json(&edits)
                    .map_err(|e| format!("{}: {e}; nothing was written", path.display()))
                    .and_then(|text| write_text(path, &text))
                    .map(|()| format!("{} edits saved to {}", edits.len(), path.display()))
            }
            None => Err("there is no rig, so no edits to save".to_string()),
        };
        self.report(outcome);
    }

    pub(super) fn load_pose(&mut self, path: &Path) {
        let outcome = self.model.load_pose(path).map(|()| format!("pose loaded from {}", path.display()));
        if outcome.is_ok() {
            self.pose_changed = true;
            self.mesh_volume_stale = true;
        }
        self.report(outcome.map_err(|e| e.to_string()));
    }

    pub(super) fn save_rig(&mut self, path: &Path) {
        let outcome = if self.model.document.sweeps.is_empty() {
            Err("there is no rig to save".to_string())
        } else {
            (self.model.document.try_to_json(path).map_err(|e| e.to_string()))
                .and_then(|text| write_text(path, &text))
                .map(|()| format!("rig saved to {}", path.display()))
        };
        self.report(outcome);
    }

    /// Sets the falloff width of the sweep named `name` (a script's step).
    pub(super) fn set_falloff_of(&mut self, name: &str, width: f64) {
        match self.model.rig.as_ref().and_then(|rig| rig.sweep_index(name)) {
            Some(sweep) => self.set_falloff(sweep, width),
            None => self.report(Err(format!("falloff: the rig has no sweep named {name:?}"))),
        }
    }

    /// Sets sweep `sweep`'s falloff width W (mesh units) live: the rig (and the rig saved) takes
    /// it, and the deformer gets the new bands without binding the mesh again
    /// ([`GpuDeformer::set_bands`](sweepffd::gpu::GpuDeformer::set_bands)); the pose is deformed
    /// again and the weight paint redrawn.
    pub(super) fn set_falloff(&mut self, sweep: usize, width: f64) {
        let outcome = self.try_set_falloff(sweep, width);
        self.report(outcome.map_err(|e| e.to_string()));
    }

    fn try_set_falloff(&mut self, sweep: usize, width: f64) -> Result<String, ViewError> {
        let name = self.model.set_falloff(sweep, width)?;
        if let Some(running) = &mut self.running {
            if let Some(deformer) = running.mesh.deformer() {
                let (positions, bands) = (&self.model.mesh.positions, &self.model.bands);
                deformer
                    .set_bands(&sweepffd::gpu::rest_positions(positions), bands)
                    .map_err(|e| ViewError::Gpu(e.to_string()))?;
            }
            running.mesh.weights_changed();
        }
        self.pose_changed = true;
        self.mesh_volume_stale = true;
        Ok(format!("falloff of {name:?}: W = {width:.4} ({} band vertices)", self.model.bands.len()))
    }

    /// Fits a sweep to the selected part (§3), key 0 at its attached end and with the default
    /// falloff ([`sweepffd::fit::DEFAULT_FALLOFF_FRACTION`] of its length), and adds it to the
    /// rig; the mesh is bound anew.
    fn fit_part(&mut self) {
        let Some(part) = self.part.clone() else {
            self.report(Err("select a part first: click the mesh where no sweep owns it".into()));
            return;
        };
        let outcome = self.try_fit(&part);
        if outcome.is_ok() {
            self.part = None;
            self.show_part();
        }
        self.report(outcome.map_err(|e| e.to_string()));
    }

    fn try_fit(&mut self, part: &super::part::Part) -> Result<String, ViewError> {
        let fitted = fit(&self.model.mesh, &part.vertices, &FitOptions::default())
            .map_err(|e| ViewError::Input(format!("fitting {:?}: {e}", part.name)))?;
        let mut document = self.model.document.clone();
        let mut name = part.name.clone();
        while document.sweeps.iter().any(|s| s.name == name) {
            name.push('\'');
        }
        document.sweeps.push(fitted.sweep_document(name.clone(), part.selection.clone(), None));
        self.model.set_rig(document, None)?;
        if let Some(running) = &mut self.running {
            let model = &self.model;
            let rig = model.rig.as_ref().map(|r| (r, &model.owners[..], &model.bands[..]));
            running.mesh = MeshDraw::new(&running.gpu.context, &model.mesh, rig)?;
        }
        self.selected_key = None;
        self.pose_changed = true;
        self.measure_rest_volumes();
        let q = &fitted.quality;
        Ok(format!(
            "fitted {name:?}: {} vertices, {} keys, RMS |d| {:.1}% of the mean radius, falloff {:.4}",
            q.vertices,
            fitted.keys.len(),
            100.0 * q.rms_d,
            fitted.falloff
        ))
    }

    /// Rigs the loaded mesh as `sweepffd autorig` does with its defaults
    /// ([`sweepffd::fit::autorig::autorig`]): one fitted sweep per protrusion, replacing the rig;
    /// a mesh with none keeps its rig and says so.
    fn try_auto_rig(&mut self) -> Result<String, ViewError> {
        let rigged = autorig(&self.model.mesh, &AutorigOptions::default())
            .map_err(|e| ViewError::Input(format!("auto-rig: {e}")))?;
        match (rigged.parts.is_empty(), rigged.rejected.len()) {
            (true, 0) => return Ok("auto-rig found no protrusion; the rig is unchanged".to_string()),
            (true, left_out) => {
                return Ok(format!(
                    "auto-rig left out every protrusion it found ({left_out}: no tube fits them, their fits fold back, or they are too small); the rig is unchanged"
                ));
            }
            _ => {}
        }
        self.model.set_rig(rigged.document(), None)?;
        if let Some(running) = &mut self.running {
            let model = &self.model;
            let rig = model.rig.as_ref().map(|r| (r, &model.owners[..], &model.bands[..]));
            running.mesh = MeshDraw::new(&running.gpu.context, &model.mesh, rig)?;
        }
        self.part = None;
        self.show_part();
        self.selected_key = None;
        self.pose_changed = true;
        self.measure_rest_volumes();
        let parts: Vec<String> = rigged
            .parts
            .iter()
            .map(|p| format!("{} ({} vertices, RMS |d| {:.1}%)", p.name, p.vertices.len(), 100.0 * p.fit.quality.rms_d))
            .collect();
        Ok(format!("auto-rig: {} sweeps: {}", parts.len(), parts.join(", ")))
    }

    /// The rest volumes of the sweeps (Eq. 1) and of the mesh.
    pub(super) fn measure_rest_volumes(&mut self) {
        self.rest_volumes =
            self.model.rig.as_ref().map_or(Vec::new(), |rig| rig.rest().iter().map(|s| s.volume()).collect());
        let mesh = &self.model.mesh;
        self.rest_mesh_volume = if self.model.closed { mesh.enclosed_volume(&mesh.positions) } else { 0.0 };
        self.mesh_volume = self.rest_mesh_volume;
    }

    /// The deformed mesh's enclosed volume, read back from the GPU once a committed change has
    /// been deformed (never per frame); the positions read serve picking too.
    pub(super) fn measure_mesh_volume(&mut self) {
        if !std::mem::take(&mut self.mesh_volume_stale) || !self.model.closed {
            return;
        }
        let Some(running) = &self.running else { return };
        match running.mesh.current_positions(&self.model.mesh) {
            Ok(positions) => {
                let exact: Vec<glam::DVec3> = positions.iter().map(|p| p.as_dvec3()).collect();
                self.mesh_volume = self.model.mesh.enclosed_volume(&exact);
                self.picked_positions = Some(positions);
            }
            Err(error) => self.panel.status = error.to_string(),
        }
    }
}

/// Writes `text` to `path` atomically; the error names the file.
fn write_text(path: &Path, text: &str) -> Result<(), String> {
    write_atomically(path, |out| out.write_all(text.as_bytes()))
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}
