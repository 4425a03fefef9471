//! Scripted sessions (`--script FILE`): a JSON array of steps replayed as input events, frame by
//! frame, with screenshots at named steps; the viewer exits after the last step.
//!
//! ```json
//! [{"wait": 0.5},
//!  {"screenshot": "before"},
//!  {"drag": {"from": [400, 300], "to": [560, 300], "seconds": 2}},
//!  {"key": "ctrl+z"}, {"key": "ctrl+shift+z"},
//!  {"click": {"at": [120, 80]}},
//!  {"scroll": 2},
//!  {"key": "k"}, {"falloff": {"sweep": "arm", "width": 0.5}},
//!  {"save_pose": "pose.json"}, {"save_edits": "edits.json"},
//!  {"screenshot": "after"}]
//! ```
//!
//! Positions are window pixels from the top left. Relative paths (screenshots, which get
//! `.png` when they have no extension, and saved files) are taken from the script's folder.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glam::Vec2;
use serde::Deserialize;

use super::input::{Button, Command, Input};

/// One step of a script.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Step {
    /// Render frames for this many seconds.
    Wait(f64),
    /// Write the next frame to this picture.
    Screenshot(PathBuf),
    /// Move the pointer (over `seconds`, one position per frame).
    Move {
        to: [f32; 2],
        #[serde(default)]
        seconds: f64,
    },
    /// Press a button at a position.
    Press {
        at: [f32; 2],
        #[serde(default)]
        button: Button,
    },
    /// Release a button.
    Release {
        #[serde(default)]
        button: Button,
    },
    /// Press and release a button at a position.
    Click {
        at: [f32; 2],
        #[serde(default)]
        button: Button,
    },
    /// Press at `from`, move to `to` over `seconds` (one position per frame), release.
    Drag {
        from: [f32; 2],
        to: [f32; 2],
        #[serde(default)]
        seconds: f64,
        #[serde(default)]
        button: Button,
    },
    /// Turn the wheel by this many lines.
    Scroll(f32),
    /// Press a key: "w", "ctrl+z", "escape" (see the controls).
    Key(String),
    /// Save the pose to this file.
    SavePose(PathBuf),
    /// Save the committed edits to this file.
    SaveEdits(PathBuf),
    /// Load a pose file.
    LoadPose(PathBuf),
    /// Save the rig (with fitted sweeps) to this file.
    SaveRig(PathBuf),
    /// Set a sweep's falloff width W (mesh units), as its slider in the panel does.
    Falloff { sweep: String, width: f64 },
}

/// What a script asks of one frame, besides input.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Feed this input.
    Input(Input),
    /// Capture the frame into this file.
    Screenshot(PathBuf),
    /// Save the pose.
    SavePose(PathBuf),
    /// Save the edits.
    SaveEdits(PathBuf),
    /// Load a pose.
    LoadPose(PathBuf),
    /// Save the rig.
    SaveRig(PathBuf),
    /// Set a sweep's falloff width.
    Falloff { sweep: String, width: f64 },
}

/// The longest a timed step (wait, move, drag) may last, in seconds: one hour.
pub const MAX_STEP_SECONDS: f64 = 3600.0;

/// The largest pointer coordinate, in pixels, and the most lines one scroll step may turn.
pub const MAX_PIXELS: f32 = 65536.0;

/// Reads a script file; errors name the file.
pub fn load(path: &Path) -> Result<Vec<Step>, String> {
    let text = sweepffd::limits::read_input_text(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    parse(&text, path)
}

/// Parses and checks the text of the script file `path`; errors name the file and the step.
pub fn parse(text: &str, path: &Path) -> Result<Vec<Step>, String> {
    let steps: Vec<Step> =
        serde_json::from_str(text).map_err(|e| format!("{}: not a viewer script: {e}", path.display()))?;
    for (i, step) in steps.iter().enumerate() {
        check(step).map_err(|problem| format!("{}: step {i}: {problem}", path.display()))?;
    }
    Ok(steps)
}

/// What is wrong with one step, if anything: an unbound key, a falloff width that is not a
/// number ≥ 0, seconds outside [0, [`MAX_STEP_SECONDS`]], a position or scroll that is not
/// finite or is beyond [`MAX_PIXELS`].
fn check(step: &Step) -> Result<(), String> {
    if let Step::Key(key) = step
        && Command::parse(key).is_none()
    {
        return Err(format!("no command is bound to the key {key:?}"));
    }
    if let Step::Falloff { width, .. } = step
        && !(width.is_finite() && *width >= 0.0)
    {
        return Err(format!("a falloff width is a number ≥ 0, found {width}"));
    }
    let seconds = match step {
        Step::Wait(s) | Step::Move { seconds: s, .. } | Step::Drag { seconds: s, .. } => *s,
        _ => 0.0,
    };
    if !(seconds.is_finite() && (0.0..=MAX_STEP_SECONDS).contains(&seconds)) {
        return Err(format!("seconds must be a number from 0 to {MAX_STEP_SECONDS}, found {seconds:?}"));
    }
    let values: &[f32] = match step {
        Step::Move { to, .. } => to,
        Step::Press { at, .. } | Step::Click { at, .. } => at,
        Step::Drag { from, to, .. } => &[from[0], from[1], to[0], to[1]],
        Step::Scroll(lines) => std::slice::from_ref(lines),
        _ => &[],
    };
    match values.iter().find(|v| !(v.is_finite() && v.abs() <= MAX_PIXELS)) {
        Some(v) => Err(format!("positions and scrolls are numbers from -{MAX_PIXELS} to {MAX_PIXELS}, found {v:?}")),
        None => Ok(()),
    }
}

/// Plays a script frame by frame.
#[derive(Debug)]
pub struct Player {
    steps: Vec<Step>,
    folder: PathBuf,
    next: usize,
    /// When the current timed step began, and where the pointer was then.
    began: Option<(Instant, Vec2)>,
    pointer: Vec2,
}

impl Player {
    /// A player of `steps`, resolving relative paths against `folder`.
    pub fn new(steps: Vec<Step>, folder: PathBuf) -> Player {
        Player { steps, folder, next: 0, began: None, pointer: Vec2::ZERO }
    }

    /// Whether every step has been played.
    pub fn finished(&self) -> bool {
        self.next >= self.steps.len()
    }

    /// Whether the step being played is a drag (its frames are the ones a drag measurement
    /// counts).
    pub fn dragging(&self) -> bool {
        matches!(self.steps.get(self.next), Some(Step::Drag { .. })) && self.began.is_some()
    }

    /// The actions of the frame starting `now`: instant steps run until a timed step or a
    /// screenshot (which ends the frame's actions, so it shows everything before it).
    pub fn frame(&mut self, now: Instant) -> Vec<Action> {
        let mut actions = Vec::new();
        while let Some(step) = self.steps.get(self.next).cloned() {
            let done = self.play(&step, now, &mut actions);
            if !done {
                break;
            }
            self.next += 1;
            self.began = None;
            if matches!(step, Step::Screenshot(_)) {
                break;
            }
        }
        actions
    }

    /// Plays (part of) `step`; returns whether it is finished.
    fn play(&mut self, step: &Step, now: Instant, actions: &mut Vec<Action>) -> bool {
        let start = self.pointer;
        let mut pointer = |actions: &mut Vec<Action>, to: Vec2| {
            self.pointer = to;
            actions.push(Action::Input(Input::Pointer(to)));
        };
        match step {
            Step::Wait(seconds) => {
                let (began, _) = *self.began.get_or_insert((now, start));
                now.duration_since(began) >= Duration::from_secs_f64(*seconds)
            }
            Step::Screenshot(path) => {
                actions.push(Action::Screenshot(self.picture_path(path)));
                true
            }
            Step::Move { to, seconds } => {
                let (began, from) = *self.began.get_or_insert((now, start));
                let (at, done) = along(from, Vec2::from_array(*to), began, now, *seconds);
                pointer(actions, at);
                done
            }
            Step::Press { at, button } => {
                pointer(actions, Vec2::from_array(*at));
                actions.push(Action::Input(Input::Button { button: *button, pressed: true }));
                true
            }
            Step::Release { button } => {
                actions.push(Action::Input(Input::Button { button: *button, pressed: false }));
                true
            }
            Step::Click { at, button } => {
                pointer(actions, Vec2::from_array(*at));
                actions.push(Action::Input(Input::Button { button: *button, pressed: true }));
                actions.push(Action::Input(Input::Button { button: *button, pressed: false }));
                true
            }
            Step::Drag { from, to, seconds, button } => {
                let from = Vec2::from_array(*from);
                if self.began.is_none() {
                    self.began = Some((now, from));
                    pointer(actions, from);
                    actions.push(Action::Input(Input::Button { button: *button, pressed: true }));
                    if *seconds > 0.0 {
                        return false;
                    }
                }
                let (began, _) = self.began.expect("set above");
                let (at, done) = along(from, Vec2::from_array(*to), began, now, *seconds);
                pointer(actions, at);
                if done {
                    actions.push(Action::Input(Input::Button { button: *button, pressed: false }));
                }
                done
            }
            Step::Scroll(lines) => {
                actions.push(Action::Input(Input::Scroll(*lines)));
                true
            }
            Step::Key(key) => {
                let command = Command::parse(key).expect("checked when the script was loaded");
                actions.push(Action::Input(Input::Command(command)));
                true
            }
            Step::Falloff { sweep, width } => {
                actions.push(Action::Falloff { sweep: sweep.clone(), width: *width });
                true
            }
            Step::SavePose(path) | Step::SaveEdits(path) | Step::LoadPose(path) | Step::SaveRig(path) => {
                let path = self.folder.join(path);
                actions.push(match step {
                    Step::SavePose(_) => Action::SavePose(path),
                    Step::SaveEdits(_) => Action::SaveEdits(path),
                    Step::LoadPose(_) => Action::LoadPose(path),
                    _ => Action::SaveRig(path),
                });
                true
            }
        }
    }

    fn picture_path(&self, path: &Path) -> PathBuf {
        let path = self.folder.join(path);
        if path.extension().is_some() { path } else { path.with_extension("png") }
    }
}

/// The point `from → to` reached at `now` of a motion taking `seconds` from `began`, and
/// whether the motion is over.
fn along(from: Vec2, to: Vec2, began: Instant, now: Instant, seconds: f64) -> (Vec2, bool) {
    if seconds <= 0.0 {
        return (to, true);
    }
    let fraction = (now.duration_since(began).as_secs_f64() / seconds).min(1.0);
    (from.lerp(to, fraction as f32), fraction >= 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs(actions: &[Action]) -> Vec<Input> {
        actions.iter().filter_map(|a| if let Action::Input(i) = a { Some(*i) } else { None }).collect()
    }

    #[test]
    fn script_parses_every_step() {
        let text = r#"[{"wait": 0.5}, {"screenshot": "a"}, {"move": {"to": [1, 2]}},
            {"press": {"at": [1, 2], "button": "right"}}, {"release": {}}, {"click": {"at": [3, 4]}},
            {"drag": {"from": [0, 0], "to": [10, 0], "seconds": 1}}, {"scroll": -2}, {"key": "ctrl+z"},
            {"save_pose": "p.json"}, {"save_edits": "e.json"}, {"load_pose": "p.json"}, {"save_rig": "r.json"},
            {"falloff": {"sweep": "arm", "width": 0.5}}]"#;
        let steps: Vec<Step> = serde_json::from_str(text).unwrap();
        assert_eq!(steps.len(), 14);
        assert_eq!(steps[3], Step::Press { at: [1.0, 2.0], button: Button::Right });
        assert_eq!(steps[13], Step::Falloff { sweep: "arm".into(), width: 0.5 });
    }

    #[test]
    fn drag_presses_moves_over_frames_and_releases() {
        let start = Instant::now();
        let steps = vec![Step::Drag { from: [0.0, 0.0], to: [100.0, 0.0], seconds: 1.0, button: Button::Left }];
        let mut player = Player::new(steps, PathBuf::from("."));
        let first = inputs(&player.frame(start));
        assert_eq!(first, vec![Input::Pointer(Vec2::ZERO), Input::Button { button: Button::Left, pressed: true }]);
        assert!(player.dragging());
        let middle = inputs(&player.frame(start + Duration::from_millis(500)));
        assert_eq!(middle, vec![Input::Pointer(Vec2::new(50.0, 0.0))]);
        let last = inputs(&player.frame(start + Duration::from_millis(1200)));
        assert_eq!(
            last,
            vec![Input::Pointer(Vec2::new(100.0, 0.0)), Input::Button { button: Button::Left, pressed: false }]
        );
        assert!(player.finished());
    }

    #[test]
    fn screenshot_ends_the_frame_and_gets_an_extension() {
        let steps = vec![Step::Key("w".into()), Step::Screenshot("shot".into()), Step::Key("d".into())];
        let mut player = Player::new(steps, PathBuf::from("/out"));
        let actions = player.frame(Instant::now());
        assert_eq!(
            actions,
            vec![
                Action::Input(Input::Command(Command::CycleSweeps)),
                Action::Screenshot(PathBuf::from("/out/shot.png"))
            ]
        );
        assert_eq!(player.frame(Instant::now()), vec![Action::Input(Input::Command(Command::CycleDragMode))]);
    }

    #[test]
    fn a_negative_falloff_is_an_error_naming_the_file_and_step() {
        let dir = std::env::temp_dir().join(format!("sweepffd-script-falloff-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("falloff.json");
        std::fs::write(&path, r#"[{"wait": 0}, {"falloff": {"sweep": "arm", "width": -1}}]"#).unwrap();
        let error = load(&path).unwrap_err();
        assert!(error.contains("falloff.json") && error.contains("step 1") && error.contains("-1"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn unknown_key_is_an_error_naming_the_file() {
        let dir = std::env::temp_dir().join(format!("sweepffd-script-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.json");
        std::fs::write(&path, r#"[{"key": "ctrl+q"}]"#).unwrap();
        let error = load(&path).unwrap_err();
        assert!(error.contains("bad.json") && error.contains("ctrl+q"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn hostile_numbers_are_errors_naming_the_step() {
        let path = Path::new("s.json");
        let cases = [
            // Finite but too long for a `Duration`: the player used to panic on it.
            (r#"[{"wait": 1e300}]"#, "s.json: step 0: seconds must be a number from 0 to 3600, found 1e300"),
            (
                r#"[{"wait": 0}, {"drag": {"from": [0, 0], "to": [1, 1], "seconds": 3601}}]"#,
                "s.json: step 1: seconds must be a number from 0 to 3600, found 3601.0",
            ),
            // 1e39 does not fit an f32.
            (
                r#"[{"click": {"at": [1e39, 0]}}]"#,
                "s.json: not a viewer script: number out of range at line 1 column 23",
            ),
            (
                r#"[{"move": {"to": [0, -70000]}}]"#,
                "s.json: step 0: positions and scrolls are numbers from -65536 to 65536, found -70000.0",
            ),
            (
                r#"[{"scroll": 1e6}]"#,
                "s.json: step 0: positions and scrolls are numbers from -65536 to 65536, found 1000000.0",
            ),
        ];
        for (text, expected) in cases {
            assert_eq!(parse(text, path).unwrap_err(), expected, "{text}");
        }
        let bounds = r#"[{"wait": 3600}, {"drag": {"from": [-65536, 0], "to": [65536, 0]}}, {"scroll": -3}]"#;
        assert_eq!(parse(bounds, path).unwrap().len(), 3);
    }
}
