//! What an OBJ file gave when it was read, kept for the faithful writer in the runs it was
//! read in: the positions, the faces and the byte offset of each vertex's logical line of every
//! part of the file ([`super::read`]), indexed as one list.
//!
//! The mesh gets its own joined copy of the positions and faces, which the application may
//! change; the parts, read into arrays of their own before the join, are that copy's original
//! and are kept as they are rather than copied once more.

use std::ops::Range;

use glam::DVec3;

use crate::mesh::Faces;
use crate::parallel::prelude::*;

/// The data of one part of the file, as read.
#[derive(Debug, Default)]
pub(crate) struct Run {
    /// The positions of its `v` statements.
    pub positions: Vec<DVec3>,
    /// The byte offset in the file of each of those statements' logical line.
    pub lines: Vec<usize>,
    /// Its faces: offsets from the run's first face index, indices into the file's vertices.
    pub faces: Faces,
}

/// The runs of a file in file order, with where each starts in the joined lists.
#[derive(Debug)]
pub(crate) struct AsRead {
    runs: Vec<Run>,
    /// `first_vertex[k]`: the vertices of the runs before run `k`; one entry more, the total.
    first_vertex: Vec<usize>,
    /// The same for faces.
    first_face: Vec<usize>,
    /// The same for face indices.
    first_index: Vec<usize>,
}

impl AsRead {
    /// The runs `runs`, in file order.
    pub fn new(runs: Vec<Run>) -> Self {
        let starts = |count: fn(&Run) -> usize| {
            let mut starts = Vec::with_capacity(runs.len() + 1);
            starts.push(0);
            for run in &runs {
                starts.push(starts[starts.len() - 1] + count(run));
            }
            starts
        };
        let first_vertex = starts(|run| run.positions.len());
        let first_face = starts(|run| run.faces.len());
        let first_index = starts(|run| run.faces.indices.len());
        Self { runs, first_vertex, first_face, first_index }
    }

    /// The number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.first_vertex.last().copied().unwrap_or(0)
    }

    /// The run that holds vertex `vertex`: the last whose first vertex is at most `vertex`
    /// (runs without vertices share their first vertex with the next run).
    fn run_of(&self, vertex: usize) -> usize {
        self.first_vertex[..self.runs.len()].partition_point(|&first| first <= vertex).saturating_sub(1)
    }

    /// The byte offset of vertex `vertex`'s logical line.
    ///
    /// # Panics
    ///
    /// If `vertex >= self.vertex_count()`, like slice indexing.
    pub fn line(&self, vertex: usize) -> usize {
        let k = self.run_of(vertex);
        self.runs[k].lines[vertex - self.first_vertex[k]]
    }

    /// The logical line's offset and the position of each vertex of `vertices` (within
    /// [`Self::vertex_count`]), in order.
    pub fn vertices(&self, vertices: Range<usize>) -> impl Iterator<Item = (usize, DVec3)> + '_ {
        let k = self.run_of(vertices.start);
        self.runs[k..]
            .iter()
            .zip(&self.first_vertex[k..])
            .take_while(move |&(_, &first)| first < vertices.end)
            .flat_map(move |(run, &first)| {
                let count = run.positions.len();
                let (from, to) = (vertices.start.saturating_sub(first).min(count), (vertices.end - first).min(count));
                run.lines[from..to].iter().copied().zip(run.positions[from..to].iter().copied())
            })
    }

    /// Whether `faces` are the faces as read, index for index.
    pub fn has_faces(&self, faces: &Faces) -> bool {
        let (face_count, index_count) = (self.first_face[self.runs.len()], self.first_index[self.runs.len()]);
        if faces.offsets.len() != face_count + 1 || faces.offsets[0] != 0 || faces.indices.len() != index_count {
            return false;
        }
        (0..self.runs.len()).into_par_iter().all(|k| {
            let (run, first_face, first_index) = (&self.runs[k], self.first_face[k], self.first_index[k]);
            let ends = run.faces.offsets.get(1..).unwrap_or_default();
            let joined_ends = &faces.offsets[first_face + 1..first_face + 1 + ends.len()];
            let indices = &faces.indices[first_index..first_index + run.faces.indices.len()];
            indices == &run.faces.indices[..]
                && joined_ends.iter().zip(ends).all(|(&joined, &end)| joined as usize == end as usize + first_index)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs of 2, 0 and 3 vertices, the second with a face only, the third with two faces.
    fn three_runs() -> AsRead {
        let position = |i: usize| DVec3::splat(i as f64);
        let faces = |list: &[&[u32]]| {
            let mut faces = Faces::new();
            for face in list {
                faces.push(face);
            }
            faces
        };
        AsRead::new(vec![
            Run { positions: vec![position(0), position(1)], lines: vec![0, 10], faces: Faces::new() },
            Run { positions: Vec::new(), lines: Vec::new(), faces: faces(&[&[0, 1, 0]]) },
            Run {
                positions: vec![position(2), position(3), position(4)],
                lines: vec![30, 40, 50],
                faces: faces(&[&[1, 2, 3, 4], &[4, 3, 2]]),
            },
        ])
    }

    fn joined_faces() -> Faces {
        Faces { offsets: vec![0, 3, 7, 10], indices: vec![0, 1, 0, 1, 2, 3, 4, 4, 3, 2] }
    }

    #[test]
    fn vertices_and_lines_across_runs_and_an_empty_run() {
        let read = three_runs();
        assert_eq!(read.vertex_count(), 5);
        assert_eq!((0..5).map(|v| read.line(v)).collect::<Vec<_>>(), vec![0, 10, 30, 40, 50]);
        let all: Vec<(usize, f64)> = read.vertices(0..5).map(|(line, p)| (line, p.x)).collect();
        assert_eq!(all, vec![(0, 0.0), (10, 1.0), (30, 2.0), (40, 3.0), (50, 4.0)]);
        let middle: Vec<usize> = read.vertices(1..4).map(|(line, _)| line).collect();
        assert_eq!(middle, vec![10, 30, 40]);
        assert_eq!(read.vertices(2..2).count(), 0);
        assert_eq!(read.vertices(4..5).map(|(line, _)| line).collect::<Vec<_>>(), vec![50]);
    }

    #[test]
    fn faces_as_read_match_only_the_same_faces() {
        let read = three_runs();
        assert!(read.has_faces(&joined_faces()));
        let mut other = joined_faces();
        other.indices[5] = 0;
        assert!(!read.has_faces(&other));
        let mut other = joined_faces();
        other.offsets[2] = 6;
        assert!(!read.has_faces(&other));
        let mut fewer = joined_faces();
        fewer.offsets.pop();
        fewer.indices.truncate(7);
        assert!(!read.has_faces(&fewer));
        assert!(!read.has_faces(&Faces::default()));
        assert!(!read.has_faces(&Faces::new()));
    }

    #[test]
    fn no_faces_as_read_match_empty_faces_only() {
        let read = AsRead::new(vec![Run { positions: vec![DVec3::ZERO], lines: vec![0], faces: Faces::new() }]);
        assert!(read.has_faces(&Faces::new()));
        assert!(!read.has_faces(&Faces::default()));
        assert!(!read.has_faces(&joined_faces()));
    }
}
