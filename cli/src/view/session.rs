//! The pose being edited in the viewer. One pointer gesture is one [`Edit`]: while it lasts it
//! is re-applied, on every pointer move, to the keys committed before it (so the result depends
//! only on where the pointer is, and replaying the same edit with `sweepffd pose` gives the
//! same keys); releasing commits it. Committed edits can be undone and redone, and the list of
//! them saved as an edits file.

use sweepffd::edit::{BoundMesh, DragMode, Edit, EditError, KeyMode, Posing, VolumeRule};
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;

/// A bend drag's span at first: a fifth of the sweep.
pub const DEFAULT_BEND_SPAN: f64 = 0.2;

/// How edits are made, as the panel and the keyboard set it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// What a point drag applies (§4, Fig. 9, 14).
    pub drag_mode: DragMode,
    /// Keys a point drag edits below the point.
    pub drag_keys: usize,
    /// Whether a key move carries the keys after it.
    pub key_mode: KeyMode,
    /// The volume rule applied after each edit (§5, Fig. 13).
    pub volume: VolumeRule,
    /// Whether edits propagate through the hierarchy (§5).
    pub hierarchy: bool,
    /// Whether each edit keeps its sweep's length (the chords between its keys).
    pub keep_length: bool,
    /// Whether a drag on the mesh bends its sweep (a `bend` edit over `bend_span`) instead of
    /// dragging the point.
    pub bend: bool,
    /// The width in t of a bend drag's span, centred where the mesh was grabbed.
    pub bend_span: f64,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            drag_mode: DragMode::Both,
            drag_keys: sweepffd::edit::DEFAULT_DRAG_KEYS,
            key_mode: KeyMode::Local,
            volume: VolumeRule::None,
            hierarchy: true,
            keep_length: false,
            bend: false,
            bend_span: DEFAULT_BEND_SPAN,
        }
    }
}

/// One committed edit and the keys after it.
#[derive(Clone, Debug)]
struct Step {
    edit: Edit,
    keys: Vec<Vec<Key>>,
}

/// Committed keys, the gesture in progress, undo and redo.
#[derive(Clone, Debug)]
pub struct Session {
    start: Vec<Vec<Key>>,
    done: Vec<Step>,
    undone: Vec<Step>,
    preview: Option<Step>,
}

impl Session {
    /// A session starting from `keys` (the rest keys, or a loaded pose).
    pub fn new(keys: Vec<Vec<Key>>) -> Session {
        Session { start: keys, done: Vec::new(), undone: Vec::new(), preview: None }
    }

    /// The keys committed so far (without the gesture in progress).
    pub fn committed(&self) -> &[Vec<Key>] {
        self.done.last().map_or(&self.start, |step| &step.keys)
    }

    /// The keys to show: the gesture's if one is in progress.
    pub fn keys(&self) -> &[Vec<Key>] {
        self.preview.as_ref().map_or_else(|| self.committed(), |step| &step.keys)
    }

    /// Applies `edit` (with `settings`' hierarchy and volume rule) to the committed keys as the
    /// gesture in progress, replacing the previous one. On error the previous preview stays.
    pub fn preview(
        &mut self,
        rig: &Rig,
        edit: Edit,
        settings: &Settings,
        mesh: Option<BoundMesh>,
    ) -> Result<usize, EditError> {
        let mut posing = Posing::new(rig).with_keys(self.committed().to_vec())?;
        posing.hierarchy = settings.hierarchy;
        posing.volume = settings.volume;
        posing.keep_length = settings.keep_length;
        if let Some(mesh) = mesh {
            posing = posing.with_mesh(mesh);
        }
        let rounds = posing.apply(&edit)?;
        self.preview = Some(Step { edit, keys: posing.keys().to_vec() });
        Ok(rounds)
    }

    /// Whether a gesture is in progress.
    pub fn in_gesture(&self) -> bool {
        self.preview.is_some()
    }

    /// Commits the gesture in progress; returns whether there was one. Clears the redo list.
    pub fn commit(&mut self) -> bool {
        let Some(step) = self.preview.take() else { return false };
        self.done.push(step);
        self.undone.clear();
        true
    }

    /// Drops the gesture in progress.
    pub fn cancel(&mut self) {
        self.preview = None;
    }

    /// Undoes the last committed edit; returns whether there was one.
    pub fn undo(&mut self) -> bool {
        self.preview = None;
        move_last(&mut self.done, &mut self.undone)
    }

    /// Redoes the last undone edit; returns whether there was one.
    pub fn redo(&mut self) -> bool {
        self.preview = None;
        move_last(&mut self.undone, &mut self.done)
    }

    /// Number of committed edits and of undone ones that can be redone.
    pub fn history(&self) -> (usize, usize) {
        (self.done.len(), self.undone.len())
    }

    /// The committed edits in order: an edits file that `sweepffd pose` applies to the keys
    /// the session started from.
    pub fn edits(&self) -> Vec<Edit> {
        self.done.iter().map(|step| step.edit.clone()).collect()
    }
}

/// Moves the last step of `from` onto `to`; returns whether there was one.
fn move_last(from: &mut Vec<Step>, to: &mut Vec<Step>) -> bool {
    from.pop().map(|step| to.push(step)).is_some()
}

#[cfg(test)]
mod tests {
    use super::*;
    use sweepffd::synthetic::{Tube, tube_rig};

    fn rig() -> Rig {
        tube_rig(&Tube { rings: 8, around: 8, length: 2.0, radius: 0.5 }, 4, 8)
    }

    fn drag(to: [f64; 3]) -> Edit {
        Edit::DragPoint {
            sweep: rig().sweeps()[0].name.clone(),
            theta: 0.0,
            t: 0.9,
            d: 0.0,
            h: 0.0,
            to,
            mode: DragMode::Both,
            keys: 2,
        }
    }

    #[test]
    fn gesture_is_one_edit_from_the_keys_before_it() {
        let rig = rig();
        let settings = Settings::default();
        let mut session = Session::new(rig.sweeps().iter().map(|s| s.keys.clone()).collect());
        let rest = session.keys().to_vec();
        // Pointer moves: each preview starts again from the rest keys.
        session.preview(&rig, drag([0.3, 0.0, 1.8]), &settings, None).unwrap();
        session.preview(&rig, drag([0.6, 0.1, 1.7]), &settings, None).unwrap();
        assert_eq!(session.committed(), &rest[..]);
        assert!(session.commit());
        assert_eq!(session.edits(), vec![drag([0.6, 0.1, 1.7])]);
        // The same edit applied once to the rest keys gives the same pose.
        let mut posing = Posing::new(&rig);
        posing.apply(&drag([0.6, 0.1, 1.7])).unwrap();
        assert_eq!(session.keys(), posing.keys());
    }

    #[test]
    fn undo_and_redo_walk_the_history() {
        let rig = rig();
        let settings = Settings::default();
        let mut session = Session::new(rig.sweeps().iter().map(|s| s.keys.clone()).collect());
        let rest = session.keys().to_vec();
        session.preview(&rig, drag([0.3, 0.0, 1.8]), &settings, None).unwrap();
        session.commit();
        let first = session.keys().to_vec();
        session.preview(&rig, drag([0.0, 0.4, 1.8]), &settings, None).unwrap();
        session.commit();
        assert!(session.undo());
        assert_eq!(session.keys(), &first[..]);
        assert!(session.undo());
        assert_eq!(session.keys(), &rest[..]);
        assert!(!session.undo());
        assert!(session.redo());
        assert_eq!(session.keys(), &first[..]);
        assert_eq!(session.history(), (1, 1));
        // A new edit forgets what could be redone.
        session.preview(&rig, drag([0.1, 0.1, 1.9]), &settings, None).unwrap();
        session.commit();
        assert_eq!(session.history(), (2, 0));
        assert!(!session.redo());
    }

    #[test]
    fn failed_preview_keeps_the_last_good_one() {
        let rig = rig();
        let mut session = Session::new(rig.sweeps().iter().map(|s| s.keys.clone()).collect());
        session.preview(&rig, drag([0.3, 0.0, 1.8]), &Settings::default(), None).unwrap();
        let good = session.keys().to_vec();
        let bad = drag([f64::NAN, 0.0, 0.0]);
        assert!(session.preview(&rig, bad, &Settings::default(), None).is_err());
        assert_eq!(session.keys(), &good[..]);
    }
}
