//! Reading a large OBJ file on every core: the file is cut into pieces of whole logical lines
//! ([`cut`]), each piece is read into a [`Part`] on its own ([`read_part`]), and the parts are
//! joined in file order ([`join`]).
//!
//! A piece ends just after a line feed whose physical line does not end in `\` (before the
//! line ending), so that no logical line spans two pieces. Pieces are about [`PIECE_BYTES`]
//! long: small enough that the parts read past a limit crossed elsewhere stay small (every
//! part adds its counts to a shared tally, and once a limit is crossed or a part finds a fault
//! no new piece is read), large enough that the join costs little.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use super::as_read::AsRead;
use super::join::{join, joinable};
use super::part::Part;
use super::read::read_part;
use crate::mesh::{Limited, Mesh};
use crate::parallel::prelude::*;

/// The length a piece is cut at (it then runs to the end of its logical line).
pub(crate) const PIECE_BYTES: usize = 1 << 20;

/// The mesh and the file's data as read ([`AsRead`]), read in pieces on every core,
/// or `None` when the file is to be read as one part: without the feature `parallel` or with
/// one thread, for a file of one piece, or when a piece finds a fault or the counts cross a
/// limit (reading it whole then finds the first fault and its line).
pub(crate) fn read_in_pieces(bytes: &[u8]) -> Option<(Mesh, AsRead)> {
    #[cfg(feature = "parallel")]
    let threads = rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    let threads = 1;
    if threads < 2 {
        return None;
    }
    read_pieces(bytes, PIECE_BYTES)
}

/// [`read_in_pieces`] with pieces cut at `piece_bytes`.
pub(crate) fn read_pieces(bytes: &[u8], piece_bytes: usize) -> Option<(Mesh, AsRead)> {
    let pieces = cut(bytes, piece_bytes);
    if pieces.len() < 2 {
        return None;
    }
    let tally = Tally::default();
    let parts: Vec<Option<Part>> = pieces
        .par_iter()
        .map(|piece| {
            if tally.stopped.load(Ordering::Relaxed) {
                return None;
            }
            let part = read_part(&bytes[piece.clone()], piece.start, piece.start == 0).ok();
            tally.add(part)
        })
        .collect();
    let parts: Vec<Part> = parts.into_iter().collect::<Option<_>>()?;
    joinable(&parts).then(|| join(parts))
}

/// Counts of the parts read so far, across threads.
#[derive(Default)]
struct Tally {
    vertices: AtomicUsize,
    faces: AtomicUsize,
    indices: AtomicUsize,
    /// A part found a fault or a count crossed its limit: read no more pieces.
    stopped: AtomicBool,
}

impl Tally {
    /// Adds `part`'s counts (`None`: a fault) and passes it on, or `None` once stopped.
    fn add(&self, part: Option<Part>) -> Option<Part> {
        let Some(part) = part else {
            self.stopped.store(true, Ordering::Relaxed);
            return None;
        };
        let vertices = self.vertices.fetch_add(part.positions.len(), Ordering::Relaxed) + part.positions.len();
        let faces = self.faces.fetch_add(part.faces.len(), Ordering::Relaxed) + part.faces.len();
        let indices = self.indices.fetch_add(part.faces.indices.len(), Ordering::Relaxed) + part.faces.indices.len();
        let within = Limited::Vertices.check(vertices as u64).is_ok()
            && Limited::Faces.check(faces as u64).is_ok()
            && Limited::Triangles.check(indices.saturating_sub(2 * faces) as u64).is_ok();
        if !within {
            self.stopped.store(true, Ordering::Relaxed);
            return None;
        }
        Some(part)
    }
}

/// Cuts `bytes` into pieces of whole logical lines, each from about `piece_bytes` on to the
/// end of its logical line; together they cover `bytes` in order.
pub(crate) fn cut(bytes: &[u8], piece_bytes: usize) -> Vec<Range<usize>> {
    let mut pieces = Vec::with_capacity(bytes.len() / piece_bytes.max(1) + 1);
    let mut start = 0;
    while start < bytes.len() {
        let end = end_of_logical_line(bytes, (start + piece_bytes.max(1)).min(bytes.len()));
        pieces.push(start..end);
        start = end;
    }
    pieces
}

/// The offset just past the first line feed at or after `from - 1` that ends a logical line
/// (its physical line does not end in `\`), or the end of `bytes`.
fn end_of_logical_line(bytes: &[u8], from: usize) -> usize {
    let mut at = from.saturating_sub(1);
    while let Some(i) = memchr::memchr(b'\n', &bytes[at..]) {
        let lf = at + i;
        let content_end = if lf > 0 && bytes[lf - 1] == b'\r' { lf - 1 } else { lf };
        if content_end == 0 || bytes[content_end - 1] != b'\\' {
            return lf + 1;
        }
        at = lf + 1;
    }
    bytes.len()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::formats::obj::read::read_whole;
    use crate::formats::obj::scan::Scanner;

    /// The OBJ files of the fuzzing corpus and its regressions, and the shared test meshes
    /// that are present.
    fn files() -> Vec<Vec<u8>> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut files = Vec::new();
        for dir in [root.join("fuzz/corpus/obj"), root.join("fuzz/regressions/obj"), root.join("../shared/meshes")] {
            let Ok(entries) = std::fs::read_dir(&dir) else { continue };
            let mut paths: Vec<_> = entries.flatten().map(|e| e.path()).collect();
            paths.sort();
            files.extend(
                paths.iter().filter(|p| p.extension().is_some_and(|e| e == "obj")).map(|p| std::fs::read(p).unwrap()),
            );
        }
        files
    }

    /// A random OBJ text of the statements the reader treats apart: vertices (some with w or
    /// colour, some continued over lines), faces with positive and negative indices and
    /// slashes, groups, objects, comments, CRLF endings, and now and then a fault.
    fn random_obj(state: &mut u64, lines: usize, faults: bool) -> Vec<u8> {
        let mut next = |n: u64| {
            *state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (*state >> 33) % n
        };
        let mut text = Vec::new();
        let mut vertices = 0u64;
        for _ in 0..lines {
            let ending: &[u8] = if next(5) == 0 { b"\r\n" } else { b"\n" };
            match next(12) {
                0..=3 => {
                    vertices += 1;
                    let x = next(2000) as f64 / 7.0 - 100.0;
                    let line = match next(6) {
                        0 => format!("v {x} \\{}  1e-3 {}", String::from_utf8_lossy(ending), next(9)),
                        1 => format!("v {x} 0.5 -2 1.0 # w"),
                        2 => format!("  v\t{x:e} {} {} 0.1 0.2 0.3", next(100), x * 3.0),
                        _ => format!("v {x} {} {x}", x / 3.0),
                    };
                    text.extend_from_slice(line.as_bytes());
                }
                4..=7 if vertices > 0 => {
                    let corners = 3 + next(3);
                    text.extend_from_slice(if next(8) == 0 { b"fo" } else { b"f" });
                    for c in 0..corners {
                        let v = 1 + next(vertices);
                        let index = if next(3) == 0 { -(v as i64) } else { v as i64 };
                        let slash = ["", "/1", "//2", "/1/1"][next(4) as usize];
                        text.extend_from_slice(format!(" {index}{slash}").as_bytes());
                        if c == 1 && next(20) == 0 {
                            text.extend_from_slice(b" \\");
                            text.extend_from_slice(ending);
                        }
                    }
                }
                8 => text.extend_from_slice(["g", "g a", "g a b", "g b a b", "g  c"][next(5) as usize].as_bytes()),
                9 => text.extend_from_slice(["o", "o a", "o thing", "o c"][next(4) as usize].as_bytes()),
                10 => text.extend_from_slice(
                    ["# comment", "", "vt 0.5 0.5", "vn 0 0 1", "usemtl m"][next(5) as usize].as_bytes(),
                ),
                _ if faults => text.extend_from_slice(
                    ["f 0 1 2", "v 1 2", "f 1 2", "v 1 inf 2", "f -99999 1 2", "f 1 2 99999", "vt nan", "v a b c"]
                        [next(8) as usize]
                        .as_bytes(),
                ),
                _ => text.extend_from_slice(b"s 1"),
            }
            text.extend_from_slice(ending);
        }
        text
    }

    /// Checks that reading `bytes` in pieces of `piece_bytes` gives exactly what reading it
    /// whole gives, or declines (`None`) where reading it whole finds a fault. Returns whether
    /// the pieces were read.
    fn check_pieces(bytes: &[u8], piece_bytes: usize) -> bool {
        let whole = read_whole(Path::new("m.obj"), bytes);
        let Some((mesh, read)) = read_pieces(bytes, piece_bytes) else { return false };
        let (expected, expected_read) = whole.unwrap_or_else(|e| panic!("pieces read what is an error whole: {e}"));
        let bits = |m: &Mesh| m.positions.iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&mesh), bits(&expected), "positions, pieces of {piece_bytes}");
        assert_eq!(mesh.faces, expected.faces, "faces, pieces of {piece_bytes}");
        assert_eq!(mesh.groups, expected.groups, "groups, pieces of {piece_bytes}");
        let lines = |read: &AsRead| (0..read.vertex_count()).map(|v| read.line(v)).collect::<Vec<_>>();
        assert_eq!(lines(&read), lines(&expected_read), "vertex lines, pieces of {piece_bytes}");
        let as_read = |read: &AsRead| read.vertices(0..read.vertex_count()).collect::<Vec<_>>();
        assert_eq!(as_read(&read), as_read(&expected_read), "vertices as read, pieces of {piece_bytes}");
        assert!(read.has_faces(&mesh.faces) && expected_read.has_faces(&mesh.faces), "faces as read");
        true
    }

    #[test]
    fn pieces_end_where_logical_lines_end() {
        let mut state = 11;
        for _ in 0..50 {
            let text = random_obj(&mut state, 200, false);
            let starts: Vec<usize> = Scanner::new(&text).map(|l| l.start).collect();
            for piece_bytes in [1, 2, 5, 17, 100, 1 << 20] {
                let pieces = cut(&text, piece_bytes);
                assert_eq!(pieces.first().map(|p| p.start), Some(0));
                assert_eq!(pieces.last().map(|p| p.end), Some(text.len()));
                for pair in pieces.windows(2) {
                    assert_eq!(pair[0].end, pair[1].start);
                    assert!(starts.binary_search(&pair[1].start).is_ok(), "a piece starts inside a logical line");
                }
            }
        }
        assert_eq!(cut(b"v 1 2 3\\\n4\\\r\n5\n", 1), vec![0..15]);
        assert_eq!(cut(b"", 4), vec![]);
    }

    #[test]
    fn pieces_and_whole_read_the_same_random_files() {
        let mut state = 5;
        let mut read = 0;
        for round in 0..300 {
            let text = random_obj(&mut state, 150, round % 3 == 0);
            for piece_bytes in [1, 7, 64, 500] {
                read += usize::from(check_pieces(&text, piece_bytes));
            }
        }
        assert!(read > 400, "only {read} random files were read in pieces");
    }

    #[test]
    fn pieces_and_whole_read_the_same_corpus_and_shared_meshes() {
        for bytes in files() {
            for piece_bytes in [3, 1000, 1 << 16] {
                let pieces = check_pieces(&bytes, piece_bytes);
                let whole = read_whole(Path::new("m.obj"), &bytes).is_ok();
                assert_eq!(pieces, whole && cut(&bytes, piece_bytes).len() > 1, "pieces of {piece_bytes}");
            }
        }
    }

    #[test]
    fn a_fault_or_a_crossed_limit_reads_the_file_whole() {
        // A face refers to a vertex of a later piece: fine. One refers to no vertex at all,
        // or before the first: the whole reading names the line.
        let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -3 -2 -1\nv 0 0 1\nf 4 -2 -3\n";
        assert!(check_pieces(text, 1));
        assert!(read_pieces(b"v 0 0 0\nf -1 -1 -2\n", 1).is_none());
        assert!(read_pieces(b"v 0 0 0\nf 1 1 2\n", 1).is_none());
        assert!(read_pieces(b"v 0 0 0\nv 1 nan 0\n", 1).is_none());
        // Ten vertices per piece of about 80 bytes: no piece crosses the vertex limit alone.
        let tally = Tally::default();
        tally.vertices.store(crate::limits::MAX_VERTICES - 5, Ordering::Relaxed);
        let part = read_part(&b"v 0 0 0\n".repeat(10), 0, true).unwrap();
        assert!(tally.add(Some(part)).is_none());
        assert!(tally.stopped.load(Ordering::Relaxed));
    }
}
