//! Joining the [`Part`]s of an OBJ file, read each on its own, into one mesh in file order:
//! vertices and faces concatenated, negative face indices resolved against the vertices of the
//! parts before, and the `g` and `o` statements replayed to give each face its groups.

use std::collections::HashMap;

use glam::DVec3;

use super::as_read::{AsRead, Run};
use super::part::{GroupChange, Part};
use crate::mesh::{FaceGroup, Faces, Limited, Mesh};
use crate::parallel::prelude::*;

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
/// mesh and the file's data as read.
///
/// A single part is moved into the mesh as it is and copied (the positions and the faces at
/// once on two cores, with the feature `parallel`) to be kept as read. Otherwise the vertices
/// and faces are copied into arrays allocated once at their final size (zeroed pages, which the
/// copies touch first), one part to a task on every core, and the parts are kept as read; the
/// groups are replayed in order on the calling thread.
pub(crate) fn join(mut parts: Vec<Part>) -> (Mesh, AsRead) {
    if parts.len() == 1 {
        let part = parts.pop().unwrap_or_default();
        let mut groups = Groups::default();
        groups.replay(&part.events, 0, part.faces.len());
        let (positions, faces) = crate::parallel::join(|| part.positions.clone(), || part.faces.clone());
        let run = Run { positions, lines: part.lines, faces };
        let mesh = Mesh { positions: part.positions, faces: part.faces, groups: groups.finish() };
        return (mesh, AsRead::new(vec![run]));
    }
    let vertices: usize = parts.iter().map(|p| p.positions.len()).sum();
    let faces: usize = parts.iter().map(|p| p.faces.len()).sum();
    let indices: usize = parts.iter().map(|p| p.faces.indices.len()).sum();
    let mut positions: Vec<DVec3> = bytemuck::zeroed_vec(vertices);
    let mut all = Faces { offsets: vec![0u32; faces + 1], indices: vec![0u32; indices] };
    let mut slots = Vec::with_capacity(parts.len());
    let mut p = &mut positions[..];
    let (mut o, mut ix) = (&mut all.offsets[1..], &mut all.indices[..]);
    let (mut first_vertex, mut first_index) = (0, 0);
    for part in &mut parts {
        let (positions, rest) = std::mem::take(&mut p).split_at_mut(part.positions.len());
        p = rest;
        let (offsets, rest) = std::mem::take(&mut o).split_at_mut(part.faces.len());
        o = rest;
        let (indices, rest) = std::mem::take(&mut ix).split_at_mut(part.faces.indices.len());
        ix = rest;
        let (vertices, face_indices) = (part.positions.len(), part.faces.indices.len());
        slots.push(Slot { part, positions, offsets, indices, first_vertex, first_index });
        first_vertex += vertices;
        first_index += face_indices;
    }
    slots.par_iter_mut().for_each(Slot::fill);
    drop(slots);
    let mut groups = Groups::default();
    let mut first_face = 0;
    for part in &parts {
        groups.replay(&part.events, first_face, first_face + part.faces.len());
        first_face += part.faces.len();
    }
    let runs = parts.into_iter().map(|part| Run { positions: part.positions, lines: part.lines, faces: part.faces });
    let mesh = Mesh { positions, faces: all, groups: groups.finish() };
    (mesh, AsRead::new(runs.collect()))
}

/// A part and where its data go in the joined arrays.
struct Slot<'a> {
    part: &'a mut Part,
    positions: &'a mut [DVec3],
    /// Its faces' end offsets (the joined `offsets` less the leading 0).
    offsets: &'a mut [u32],
    indices: &'a mut [u32],
    /// The number of vertices and of face indices of the parts before it.
    first_vertex: usize,
    first_index: usize,
}

impl Slot<'_> {
    /// Resolves the part's negative indices against the earlier parts' vertices, in the part
    /// (which is kept as read) and in the joined indices, and copies the part's data, its face
    /// offsets shifted past the earlier parts' indices.
    fn fill(&mut self) {
        let part = &mut *self.part;
        for &(at, resolved) in &part.relative {
            part.faces.indices[at] = (self.first_vertex as i64 + resolved) as u32;
        }
        self.positions.copy_from_slice(&part.positions);
        let shift = self.first_index as u32;
        for (joined, &end) in self.offsets.iter_mut().zip(part.faces.offsets.iter().skip(1)) {
            *joined = end + shift;
        }
        self.indices.copy_from_slice(&part.faces.indices);
    }
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
    /// Replays a part's `g` and `o` statements, `events`, over its faces, which are the faces
    /// `first..end` of the file.
    fn replay(&mut self, events: &[(usize, GroupChange)], first: usize, end: usize) {
        let mut at = first;
        for (before, change) in events {
            self.assign(at..first + before);
            self.apply(change);
            at = first + before;
        }
        self.assign(at..end);
    }

    /// The groups that have faces, in order of first appearance.
    fn finish(self) -> Vec<FaceGroup> {
        let mut groups = self.groups;
        groups.retain(|g| !g.faces.is_empty());
        groups
    }

    fn apply(&mut self, change: &GroupChange) {
        match change {
            GroupChange::Groups(names) => self.current = names.iter().map(|name| self.id(name)).collect(),
            GroupChange::Object(name) => self.object = name.as_ref().map(|name| self.id(name)),
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

    fn id(&mut self, name: &str) -> usize {
        if let Some(&id) = self.ids.get(name) {
            return id;
        }
        let id = self.groups.len();
        self.groups.push(FaceGroup { name: name.to_owned(), faces: Vec::new() });
        self.ids.insert(name.to_owned(), id);
        id
    }
}
