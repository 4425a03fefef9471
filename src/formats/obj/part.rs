//! [`Part`]: what a run of whole logical lines of an OBJ file gives when read on its own, and
//! its group events ([`GroupChange`]), which [`super::join`] resolves and replays in file order.

use glam::DVec3;

use crate::mesh::Faces;

/// A `g` or `o` statement, kept by a part for the join to replay.
#[derive(Debug)]
pub(crate) enum GroupChange {
    /// `g a b …`: these names become the current groups (none for a bare `g`).
    Groups(Vec<String>),
    /// `o name`: the current object (none for a bare `o`).
    Object(Option<String>),
}

/// What a run of whole logical lines of an OBJ file gives, read on its own.
#[derive(Debug, Default)]
pub(crate) struct Part {
    /// The positions of its `v` statements.
    pub positions: Vec<DVec3>,
    /// The byte offset in the file of each of those statements' logical line.
    pub lines: Vec<usize>,
    /// Its faces. A negative index of a part that does not start the file is held in
    /// `relative` and is 0 here until joined.
    pub faces: Faces,
    /// For a part that does not start the file, each negative face index: its place in
    /// `faces.indices` and the index resolved against this part's vertices only (vertices
    /// read before it in the part plus the index; below 0 when it reaches an earlier part).
    pub relative: Vec<(usize, i64)>,
    /// Its `g` and `o` statements in order, each with the number of its faces before it.
    pub events: Vec<(usize, GroupChange)>,
    /// The largest positive face index met (as written) and its line: checked once the
    /// vertex count is known.
    pub largest: Option<(i64, usize)>,
}
