//! Joining the [`Part`]s of an OBJ file, read each on its own, into one mesh in file order:
//! vertices and faces concatenated, negative face indices resolved against the vertices of the
//! parts before, and the `g` and `o` statements replayed to give each face its groups.

use std::collections::HashMap;

use glam::DVec3;

use super::read::Part;
use crate::mesh::source::Source;
use crate::mesh::{FaceGroup, Faces, Limited, Mesh};

/// A `g` or `o` statement, kept by a part for the join to replay.
#[derive(Debug)]
pub(crate) enum GroupChange {
    /// `g a b …`: these names become the current groups (none for a bare `g`).
    Groups(Vec<String>),
    /// `o name`: the current object (none for a bare `o`).
    Object(Option<String>),
}

/// Whether `parts`, each read without fault, join into a mesh without one: some vertex, the
/// vertex, face and triangle counts within their limits, every negative index reaching a
/// vertex, every positive one within the vertex count. If not, the file is read again as one
/// part, which finds the fault and its line.
pub(crate) fn joinable(parts: &[Part]) -> bool {
    let vertices: usize = parts.iter().map(|p| p.positions.len()).sum();
    let faces: usize = parts.iter().map(|p| p.faces.len()).sum();
    let indices: usize = parts.iter().map(|p| p.faces.indices.len()).sum();
    // Each face counted and each triangle of the fans, as `Faces::push_within_limits` does
    // face by face: both grow with every face, so the totals decide.
    let triangles = indices.saturating_sub(2 * faces);
    let within = Limited::Vertices.check(vertices as u64).is_ok()
        && Limited::Faces.check(faces as u64).is_ok()
        && Limited::Triangles.check(triangles as u64).is_ok();
    if vertices == 0 || !within {
        return false;
    }
    let largest = parts.iter().filter_map(|p| p.largest).map(|(index, _)| index).max();
    if largest.is_some_and(|index| index > vertices as i64) {
        return false;
    }
    let mut before = 0i64;
    for part in parts {
        if part.relative.iter().any(|&(_, resolved)| before + resolved < 0) {
            return false;
        }
        before += part.positions.len() as i64;
    }
    true
}

/// Joins `parts` (checked by [`joinable`], or a single part that starts the file) into the
/// mesh and the byte offset of each vertex's logical line.
pub(crate) fn join(parts: Vec<Part>) -> (Mesh, Vec<usize>) {
    let vertices: usize = parts.iter().map(|p| p.positions.len()).sum();
    let (faces, indices): (usize, usize) =
        parts.iter().fold((0, 0), |(f, i), p| (f + p.faces.len(), i + p.faces.indices.len()));
    let mut positions: Vec<DVec3> = Vec::with_capacity(vertices);
    let mut lines = Vec::with_capacity(vertices);
    let mut all = Faces { offsets: Vec::with_capacity(faces + 1), indices: Vec::with_capacity(indices) };
    all.offsets.push(0);
    let mut groups = Groups::default();
    for part in parts {
        let (first_vertex, first_face, first_index) = (positions.len(), all.len(), all.indices.len());
        positions.extend_from_slice(&part.positions);
        lines.extend_from_slice(&part.lines);
        let shift = first_index as u32;
        all.offsets.extend(part.faces.offsets.iter().skip(1).map(|&o| o + shift));
        all.indices.extend_from_slice(&part.faces.indices);
        for &(at, resolved) in &part.relative {
            all.indices[first_index + at] = (first_vertex as i64 + resolved) as u32;
        }
        let mut at = 0;
        for (before, change) in part.events {
            groups.assign(first_face + at..first_face + before);
            groups.apply(change);
            at = before;
        }
        groups.assign(first_face + at..all.len());
    }
    let mut groups = groups.groups;
    groups.retain(|g| !g.faces.is_empty());
    (Mesh { positions, faces: all, groups, source: Source::Code }, lines)
}

/// The groups met so far and the current ones.
#[derive(Default)]
struct Groups {
    groups: Vec<FaceGroup>,
    ids: HashMap<String, usize>,
    /// Groups named by the last `g`.
    current: Vec<usize>,
    /// Group named by the last `o`.
    object: Option<usize>,
}

impl Groups {
    fn apply(&mut self, change: GroupChange) {
        match change {
            GroupChange::Groups(names) => self.current = names.into_iter().map(|name| self.id(name)).collect(),
            GroupChange::Object(name) => self.object = name.map(|name| self.id(name)),
        }
    }

    /// Adds the faces `faces` to every current group and the current object, once each.
    fn assign(&mut self, faces: std::ops::Range<usize>) {
        if faces.is_empty() {
            return;
        }
        let last = faces.end as u32 - 1;
        for &g in self.current.iter().chain(self.object.iter()) {
            let members = &mut self.groups[g].faces;
            // A name given twice, or an object that is also a current group, got the run.
            if members.last() != Some(&last) {
                members.extend(faces.start as u32..faces.end as u32);
            }
        }
    }

    fn id(&mut self, name: String) -> usize {
        if let Some(&id) = self.ids.get(&name) {
            return id;
        }
        let id = self.groups.len();
        self.groups.push(FaceGroup { name: name.clone(), faces: Vec::new() });
        self.ids.insert(name, id);
        id
    }
}
