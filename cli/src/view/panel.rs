//! The side panel (egui): timings, the device, volumes, the edit settings, each sweep's falloff
//! width and the weight paint, history, files, fitting and the controls.

use sweepffd::edit::{DragMode, KeyMode, VolumeRule};

use super::gesture::KeyTool;
use super::input::{CONTROLS, Command};
use super::session::Settings;
use super::stats::FrameTimes;

/// Width of the panel in points; the scene is drawn in the rest of the window.
pub const PANEL_WIDTH: f32 = 290.0;

/// How the sweeps are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SweepDisplay {
    /// Key rings and the translucent surface.
    #[default]
    RingsAndSurface,
    /// Key rings only.
    Rings,
    /// Nothing.
    Hidden,
}

impl SweepDisplay {
    /// The next display in the cycle of the W key.
    pub fn next(self) -> SweepDisplay {
        match self {
            SweepDisplay::RingsAndSurface => SweepDisplay::Rings,
            SweepDisplay::Rings => SweepDisplay::Hidden,
            SweepDisplay::Hidden => SweepDisplay::RingsAndSurface,
        }
    }
}

/// What the panel shows and lets the user change besides the settings.
#[derive(Clone, Debug)]
pub struct PanelState {
    /// Sweep display.
    pub sweeps: SweepDisplay,
    /// Key ring tool.
    pub tool: KeyTool,
    /// Select parts by face group (when the mesh has groups) rather than by radius.
    pub by_group: bool,
    /// Selection radius, fraction of the bounding-box diagonal.
    pub radius: f64,
    /// Files.
    pub pose_path: String,
    /// See `pose_path`.
    pub edits_path: String,
    /// See `pose_path`.
    pub rig_path: String,
    /// The last message (an error or what was saved).
    pub status: String,
    /// Colour the mesh by each vertex's falloff weight (K).
    pub paint_weights: bool,
}

/// Read-only facts the panel shows.
#[derive(Clone, Debug, Default)]
pub struct PanelFacts {
    /// Adapter and backend.
    pub adapter: String,
    /// Mesh vertices and triangles.
    pub vertices: usize,
    /// See `vertices`.
    pub triangles: usize,
    /// Recent median timings.
    pub times: FrameTimes,
    /// Each sweep's name, volume now and at rest (Eq. 1).
    pub sweep_volumes: Vec<(String, f64, f64)>,
    /// Where the pose folds its sweeps (drawn in red rings).
    pub folds: Vec<String>,
    /// The mesh's enclosed volume after the last committed edit and at rest, if it is closed.
    pub mesh_volume: Option<(f64, f64)>,
    /// Committed and redoable edits.
    pub history: (usize, usize),
    /// Whether there is a rig.
    pub has_rig: bool,
    /// Whether the mesh has face groups.
    pub has_groups: bool,
    /// The selected key, as text.
    pub selected_key: Option<String>,
    /// The part selected for fitting, as text.
    pub part: Option<String>,
    /// (index, name, falloff width W) of each sweep that owns vertices.
    pub falloffs: Vec<(usize, String, f64)>,
    /// The mesh's bounding box diagonal: the widest falloff.
    pub diagonal: f64,
}

/// What the user asked for in the panel.
#[derive(Clone, Debug, PartialEq)]
pub enum PanelAction {
    /// Same as a key.
    Command(Command),
    /// Save the rig (with fitted sweeps).
    SaveRig,
    /// Set sweep `sweep`'s falloff width to `width` (mesh units).
    SetFalloff { sweep: usize, width: f64 },
}

/// Draws the panel; returns the actions asked for.
pub fn panel(
    ui: &mut egui::Ui,
    facts: &PanelFacts,
    state: &mut PanelState,
    settings: &mut Settings,
) -> Vec<PanelAction> {
    let mut actions = Vec::new();
    egui::Panel::right("sweepffd panel").exact_size(PANEL_WIDTH).resizable(false).show(ui, |ui| {
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.heading("sweepffd");
            let t = &facts.times;
            ui.label(format!("render {:.1} ms, deform {:.1} ms, edit {:.1} ms", t.render, t.deform, t.edit));
            ui.label(format!("{:.1} ms between frames", t.frame));
            ui.label(format!("{} vertices, {} triangles", facts.vertices, facts.triangles));
            ui.label(&facts.adapter);
            ui.separator();
            folds(ui, facts);
            volumes(ui, facts);
            ui.separator();
            if facts.has_rig {
                edit_settings(ui, state, settings, facts.mesh_volume.is_some());
                falloffs(ui, facts, state, &mut actions);
                ui.horizontal_wrapped(|ui| {
                    let (done, undone) = facts.history;
                    if ui.add_enabled(done > 0, egui::Button::new(format!("Undo ({done})"))).clicked() {
                        actions.push(PanelAction::Command(Command::Undo));
                    }
                    if ui.add_enabled(undone > 0, egui::Button::new(format!("Redo ({undone})"))).clicked() {
                        actions.push(PanelAction::Command(Command::Redo));
                    }
                });
                if let Some(key) = &facts.selected_key {
                    ui.label(format!("selected: {key}"));
                }
                file_row(
                    ui,
                    "pose",
                    &mut state.pose_path,
                    &mut actions,
                    &[("Save", Command::SavePose), ("Load", Command::LoadPose)],
                );
                file_row(ui, "edits", &mut state.edits_path, &mut actions, &[("Save", Command::SaveEdits)]);
                ui.separator();
            }
            fitting(ui, facts, state, &mut actions);
            if !state.status.is_empty() {
                ui.separator();
                ui.label(egui::RichText::new(&state.status).strong());
            }
            ui.separator();
            egui::CollapsingHeader::new("controls").default_open(!facts.has_rig).show(ui, |ui| {
                egui::Grid::new("controls").striped(true).show(ui, |ui| {
                    for (keys, what) in CONTROLS {
                        ui.label(*keys);
                        ui.label(*what);
                        ui.end_row();
                    }
                });
            });
        });
    });
    actions
}

fn folds(ui: &mut egui::Ui, facts: &PanelFacts) {
    for fold in &facts.folds {
        ui.colored_label(egui::Color32::from_rgb(220, 30, 30), format!("warning: {fold}"));
    }
}

fn volumes(ui: &mut egui::Ui, facts: &PanelFacts) {
    ui.label("volumes (Eq. 1), now / rest");
    for (name, now, rest) in &facts.sweep_volumes {
        ui.label(format!("  {name}: {now:.5e} / {rest:.5e} ({:+.2}%)", 100.0 * (now / rest - 1.0)));
    }
    match facts.mesh_volume {
        Some((now, rest)) => {
            ui.label(format!("  mesh: {now:.5e} / {rest:.5e} ({:+.2}%)", 100.0 * (now / rest - 1.0)));
        }
        None => {
            ui.label("  mesh: open, encloses no volume");
        }
    }
}

fn edit_settings(ui: &mut egui::Ui, state: &mut PanelState, settings: &mut Settings, closed: bool) {
    ui.horizontal_wrapped(|ui| {
        ui.label("point drag (D)");
        ui.selectable_value(&mut settings.drag_mode, DragMode::Both, "both");
        ui.selectable_value(&mut settings.drag_mode, DragMode::Translate, "translate");
        ui.selectable_value(&mut settings.drag_mode, DragMode::Rotate, "rotate");
    });
    ui.add(egui::Slider::new(&mut settings.drag_keys, 1..=6).text("keys a drag edits"));
    ui.horizontal_wrapped(|ui| {
        ui.label("key ring");
        ui.selectable_value(&mut state.tool, KeyTool::Move, "move (G)");
        ui.selectable_value(&mut state.tool, KeyTool::Rotate, "turn (R)");
        ui.selectable_value(&mut state.tool, KeyTool::Scale, "scale (S)");
    });
    ui.horizontal_wrapped(|ui| {
        ui.label("key moves (L)");
        ui.selectable_value(&mut settings.key_mode, KeyMode::Local, "local");
        ui.selectable_value(&mut settings.key_mode, KeyMode::Independent, "independent");
    });
    ui.checkbox(&mut settings.hierarchy, "hierarchy propagation (H)");
    ui.checkbox(&mut settings.keep_length, "keep length (N)");
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut settings.bend, "mesh drags bend (B), span");
        ui.add(egui::Slider::new(&mut settings.bend_span, 0.02..=1.0).fixed_decimals(2));
    });
    ui.horizontal_wrapped(|ui| {
        ui.label("volume rule (V)");
        for (rule, name) in [(VolumeRule::None, "none"), (VolumeRule::Total, "total"), (VolumeRule::Ratio, "ratio")] {
            ui.selectable_value(&mut settings.volume, rule, name);
        }
        // The mesh rule keeps the enclosed volume, which only a closed mesh has.
        let mesh = egui::Button::selectable(settings.volume == VolumeRule::Mesh, "mesh");
        if ui.add_enabled(closed, mesh).clicked() {
            settings.volume = VolumeRule::Mesh;
        }
    });
    ui.horizontal_wrapped(|ui| {
        ui.label("sweeps (W)");
        ui.selectable_value(&mut state.sweeps, SweepDisplay::RingsAndSurface, "rings + surface");
        ui.selectable_value(&mut state.sweeps, SweepDisplay::Rings, "rings");
        ui.selectable_value(&mut state.sweeps, SweepDisplay::Hidden, "hidden");
    });
}

/// A slider per sweep that owns vertices for its falloff width (0 to the mesh's diagonal), and
/// the weight paint's switch.
fn falloffs(ui: &mut egui::Ui, facts: &PanelFacts, state: &mut PanelState, actions: &mut Vec<PanelAction>) {
    ui.checkbox(&mut state.paint_weights, "paint falloff weights (K)");
    if state.paint_weights {
        ui.label("  blue: rest, yellow: halfway, red: follows its sweep");
    }
    if facts.falloffs.is_empty() {
        return;
    }
    ui.label("falloff width W (mesh units)");
    for (sweep, name, width) in &facts.falloffs {
        let mut w = *width;
        let slider = egui::Slider::new(&mut w, 0.0..=facts.diagonal).text(name);
        if ui.add(slider).changed() && w != *width {
            actions.push(PanelAction::SetFalloff { sweep: *sweep, width: w });
        }
    }
}

fn file_row(
    ui: &mut egui::Ui,
    label: &str,
    path: &mut String,
    actions: &mut Vec<PanelAction>,
    buttons: &[(&str, Command)],
) {
    ui.horizontal_wrapped(|ui| {
        ui.label(label);
        ui.add(egui::TextEdit::singleline(path).desired_width(130.0));
        for (text, command) in buttons {
            if ui.button(*text).clicked() {
                actions.push(PanelAction::Command(*command));
            }
        }
    });
}

fn fitting(ui: &mut egui::Ui, facts: &PanelFacts, state: &mut PanelState, actions: &mut Vec<PanelAction>) {
    ui.label(if facts.has_rig {
        "Fit another sweep: click a part no sweep owns (§3)."
    } else {
        "No rig: click a part of the mesh, then fit a sweep to it (§3)."
    });
    if facts.has_groups {
        ui.checkbox(&mut state.by_group, "select a whole face group");
    }
    if !(facts.has_groups && state.by_group) {
        ui.add(egui::Slider::new(&mut state.radius, 0.02..=0.6).text("selection radius"));
    }
    match &facts.part {
        Some(part) => {
            ui.label(part);
            if ui.button("Fit sweep (F)").clicked() {
                actions.push(PanelAction::Command(Command::Fit));
            }
        }
        None => {
            ui.label("nothing selected");
        }
    }
    if ui.button("Auto-rig (A)").on_hover_text("one fitted sweep per protrusion, replacing the rig").clicked() {
        actions.push(PanelAction::Command(Command::AutoRig));
    }
    ui.horizontal_wrapped(|ui| {
        ui.label("rig");
        ui.add(egui::TextEdit::singleline(&mut state.rig_path).desired_width(130.0));
        if ui.add_enabled(facts.has_rig, egui::Button::new("Save")).clicked() {
            actions.push(PanelAction::SaveRig);
        }
    });
}
