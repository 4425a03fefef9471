//! The viewer's input events, from the window or from a script: both go through the same
//! handlers, so a script exercises exactly what a user's hand does.

use glam::Vec2;
use serde::Deserialize;

/// A mouse button.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Button {
    /// Picks and drags; orbits over the background.
    #[default]
    Left,
    /// Pans.
    Right,
    /// Orbits.
    Middle,
}

/// One input event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Input {
    /// The pointer moved to this pixel (from the window's top left).
    Pointer(Vec2),
    /// A button went down or up at the pointer.
    Button { button: Button, pressed: bool },
    /// The wheel turned by this many lines (positive: away from the user, zooming in).
    Scroll(f32),
    /// A key bound to a command was pressed.
    Command(Command),
}

/// What a key does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// Ctrl+Z.
    Undo,
    /// Ctrl+Shift+Z or Ctrl+Y.
    Redo,
    /// Ctrl+S: save the pose.
    SavePose,
    /// Ctrl+O: load the pose file named in the panel.
    LoadPose,
    /// Ctrl+E: save the committed edits.
    SaveEdits,
    /// W: cycle the sweeps' display (rings and surface, rings, nothing).
    CycleSweeps,
    /// D: cycle the point drag mode (both, translate, rotate).
    CycleDragMode,
    /// L: toggle key moves between local and independent.
    ToggleKeyMode,
    /// H: toggle hierarchy propagation.
    ToggleHierarchy,
    /// B: toggle whether drags on the mesh bend its sweep.
    ToggleBend,
    /// N: toggle keep-length.
    ToggleKeepLength,
    /// V: cycle the volume rule.
    CycleVolume,
    /// K: toggle the weight paint (each vertex coloured by its falloff weight).
    ToggleWeights,
    /// G: dragging a key ring moves it.
    MoveTool,
    /// R: dragging a key ring turns it.
    RotateTool,
    /// S: dragging a key ring scales its radii.
    ScaleTool,
    /// F: fit a sweep to the selected part.
    Fit,
    /// A: rig the whole mesh, one fitted sweep per protrusion (`sweepffd autorig`).
    AutoRig,
    /// Home: frame the mesh again.
    ResetCamera,
    /// Escape: cancel the gesture, clear the selection.
    Cancel,
}

impl Command {
    /// The command of a key: `name` is a character ("z") or a key name ("escape", "home"),
    /// case-insensitive, with the Ctrl and Shift modifiers.
    pub fn for_key(name: &str, ctrl: bool, shift: bool) -> Option<Command> {
        let name = name.to_lowercase();
        let command = match (name.as_str(), ctrl, shift) {
            ("z", true, false) => Command::Undo,
            ("z", true, true) | ("y", true, _) => Command::Redo,
            ("s", true, _) => Command::SavePose,
            ("o", true, _) => Command::LoadPose,
            ("e", true, _) => Command::SaveEdits,
            (_, true, _) => return None,
            ("w", ..) => Command::CycleSweeps,
            ("d", ..) => Command::CycleDragMode,
            ("l", ..) => Command::ToggleKeyMode,
            ("h", ..) => Command::ToggleHierarchy,
            ("b", ..) => Command::ToggleBend,
            ("n", ..) => Command::ToggleKeepLength,
            ("v", ..) => Command::CycleVolume,
            ("k", ..) => Command::ToggleWeights,
            ("g", ..) => Command::MoveTool,
            ("r", ..) => Command::RotateTool,
            ("s", ..) => Command::ScaleTool,
            ("f", ..) => Command::Fit,
            ("a", ..) => Command::AutoRig,
            ("home", ..) => Command::ResetCamera,
            ("escape", ..) => Command::Cancel,
            _ => return None,
        };
        Some(command)
    }

    /// A key as a script writes it: "ctrl+shift+z", "w", "escape".
    pub fn parse(text: &str) -> Option<Command> {
        let mut parts: Vec<&str> = text.split('+').map(str::trim).collect();
        let name = parts.pop()?;
        let has = |m: &str| parts.iter().any(|p| p.eq_ignore_ascii_case(m));
        if parts.iter().any(|p| !["ctrl", "shift"].iter().any(|m| p.eq_ignore_ascii_case(m))) {
            return None;
        }
        Command::for_key(name, has("ctrl"), has("shift"))
    }
}

/// The controls, as the panel and the README list them.
pub const CONTROLS: &[(&str, &str)] = &[
    ("left drag on the mesh", "drag that point (§4 direct control)"),
    ("left drag on a key ring", "move / turn / scale the key (G / R / S)"),
    ("left drag elsewhere, middle drag", "orbit"),
    ("right drag", "pan"),
    ("wheel", "zoom"),
    ("D", "point drag mode: both, translate, rotate"),
    ("B", "drags on the mesh bend its sweep over the panel's span (orange rings) or drag the point"),
    ("N", "keep length on / off: edits keep each sweep's length"),
    ("L", "key moves: local or independent"),
    ("H", "hierarchy propagation on / off"),
    ("V", "volume rule: none, total, ratio, mesh"),
    ("W", "sweeps: rings and surface, rings, hidden"),
    ("K", "weight paint on / off: blue rest, yellow halfway, red follows its sweep"),
    ("panel falloff sliders", "each sweep's falloff width W (mesh units), applied live"),
    ("F", "fit a sweep to the selected part"),
    ("Ctrl+Z, Ctrl+Shift+Z / Ctrl+Y", "undo, redo"),
    ("Ctrl+S, Ctrl+O, Ctrl+E", "save pose, load pose, save edits"),
    ("Home, Escape", "frame the mesh, cancel"),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_parse_with_modifiers() {
        assert_eq!(Command::parse("ctrl+z"), Some(Command::Undo));
        assert_eq!(Command::parse("Ctrl+Shift+Z"), Some(Command::Redo));
        assert_eq!(Command::parse("s"), Some(Command::ScaleTool));
        assert_eq!(Command::parse("ctrl+s"), Some(Command::SavePose));
        assert_eq!(Command::parse("escape"), Some(Command::Cancel));
        assert_eq!(Command::parse("K"), Some(Command::ToggleWeights));
        assert_eq!(Command::parse("alt+s"), None);
        assert_eq!(Command::parse("ctrl+q"), None);
        assert_eq!(Command::parse("x"), None);
        assert_eq!(Command::parse("b"), Some(Command::ToggleBend));
        assert_eq!(Command::parse("N"), Some(Command::ToggleKeepLength));
    }
}
