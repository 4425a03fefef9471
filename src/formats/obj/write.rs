//! Writing OBJ files: faithfully over the file a mesh was read from, or generically.
//!
//! Both build their text in blocks of [`BLOCK`] vertices, a window of blocks at a time on every
//! core (with the feature `parallel`), and write the blocks in order: the output is the same
//! bytes whatever the number of threads.

use std::io::{self, Write};
use std::ops::Range;

use glam::DVec3;

use super::ObjFile;
use super::scan::{self, Scanner};
use crate::formats::decimal::{push_display, push_lower_exp};
use crate::mesh::{FaceGroup, Faces};
use crate::parallel::prelude::*;

/// Vertices (or faces) per block of text built on one thread.
const BLOCK: usize = 1 << 14;

/// Blocks built at once before they are written, which bounds the text held in memory.
const WINDOW: usize = 64;

/// A coordinate in the shortest decimal form that reads back to the same f64: plain digits,
/// or exponent notation for magnitudes below 1e-5 or from 1e16 on (so round-off such as
/// 6.1e-17 stays short). Every OBJ reader parses both forms. The same text as
/// `format!("{}")`, respectively `format!("{:e}")`, of the value ([`push_coordinate`]).
pub(crate) struct Coordinate(pub f64);

impl std::fmt::Display for Coordinate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if !self.0.is_finite() {
            // As `{}` writes them, for messages about values that cannot be written.
            return write!(f, "{}", self.0);
        }
        let mut text = Vec::with_capacity(32);
        push_coordinate(&mut text, self.0);
        // The formatter writes ASCII digits, signs, points and `e` only.
        f.write_str(std::str::from_utf8(&text).map_err(|_| std::fmt::Error)?)
    }
}

/// Appends [`Coordinate`]`(value)` to `out`.
pub(crate) fn push_coordinate(out: &mut Vec<u8>, value: f64) {
    let magnitude = value.abs();
    if magnitude != 0.0 && !(1e-5..1e16).contains(&magnitude) {
        push_lower_exp(out, value);
    } else {
        push_display(out, value);
    }
}

/// Appends `x y z` (three [`Coordinate`]s).
pub(crate) fn push_position(out: &mut Vec<u8>, p: DVec3) {
    push_coordinate(out, p.x);
    out.push(b' ');
    push_coordinate(out, p.y);
    out.push(b' ');
    push_coordinate(out, p.z);
}

/// The blocks of [`BLOCK`] items that `count` items make, in order.
fn blocks(count: usize) -> Vec<Range<usize>> {
    (0..count).step_by(BLOCK).map(|s| s..(s + BLOCK).min(count)).collect()
}

/// Builds the text of each of `count` items in blocks of [`BLOCK`] (`block` gives the text of
/// a range of items), a window at a time in parallel, and writes them in order.
fn write_blocks(out: &mut impl Write, count: usize, block: impl Fn(Range<usize>) -> Vec<u8> + Sync) -> io::Result<()> {
    for window in blocks(count).chunks(WINDOW) {
        let texts: Vec<Vec<u8>> = window.par_iter().map(|range| block(range.clone())).collect();
        for text in texts {
            out.write_all(&text)?;
        }
    }
    Ok(())
}

/// The new statements of the moved vertices of a block: each one's logical line (its bytes in
/// the file) and the end of its new text in `text`.
#[derive(Default)]
struct Patch {
    lines: Vec<(Range<usize>, usize)>,
    text: Vec<u8>,
}

impl Patch {
    /// Writes the bytes of `file` from `copied` to the end of the patch's last line, each
    /// patched line replaced by its new text; returns where the copy stopped.
    fn write(&self, out: &mut impl Write, bytes: &[u8], mut copied: usize) -> io::Result<usize> {
        let mut written = 0;
        for (line, end) in &self.lines {
            out.write_all(&bytes[copied..line.start])?;
            out.write_all(&self.text[written..*end])?;
            (copied, written) = (line.end, *end);
        }
        Ok(copied)
    }

    /// The patch as one text from `from` to `to` in the file.
    fn into_text(self, bytes: &[u8], from: usize, to: usize) -> Vec<u8> {
        let mut text = Vec::with_capacity(to - from + self.text.len());
        let copied = self.write(&mut text, bytes, from).unwrap_or(to);
        text.extend_from_slice(&bytes[copied..to]);
        text
    }
}

/// A block of vertices to write: its new statements, or, when they are many, its whole text.
enum Block {
    Patch(Patch),
    Text(Vec<u8>),
}

/// A block where at least one vertex in `DENSE` moved is built as one text and written with
/// one call; sparser ones have their unchanged runs written straight from the file.
const DENSE: usize = 4;

/// Writes the OBJ file `file` with new vertex positions.
///
/// Every byte is copied as it is except the `v` statements of vertices whose position changed
/// (any coordinate differs bit for bit from the position read from the file). Such a
/// statement is written `v x y z` (shortest round-trip digits, see [`Coordinate`]), then its
/// original text after the third number (w or colour, a comment), then its original line
/// ending; a `\`-continued statement becomes one line. With unchanged positions the output is
/// byte-identical to the file.
///
/// The new statements are built in blocks of [`BLOCK`] vertices, a window of blocks at a time
/// on every core; the unchanged bytes around few moved vertices are written straight from the
/// file, not copied.
pub(crate) fn write_faithful(out: &mut impl Write, file: &ObjFile, positions: &[DVec3]) -> io::Result<()> {
    let bytes = &file.bytes[..];
    let count = file.read.vertex_count().min(positions.len());
    // Vertices first..last own the bytes from the first's statement (the file's start for
    // vertex 0) to the next vertex's statement (the file's end after the last vertex).
    let span = |vertices: &Range<usize>| {
        let start = if vertices.start == 0 { 0 } else { file.read.line(vertices.start) };
        let end = if vertices.end >= count { bytes.len() } else { file.read.line(vertices.end) };
        start..end
    };
    let block = |vertices: Range<usize>| {
        let mut patch = Patch::default();
        for ((start, original), &p) in file.read.vertices(vertices.clone()).zip(&positions[vertices.clone()]) {
            if same_bits(original, p) {
                continue;
            }
            let Some(line) = Scanner::new(&bytes[start..]).next() else { continue };
            let code = scan::code(&line.body);
            let (_, args) = scan::keyword(code);
            let Some(tail) = after_position(code, args) else { continue };
            let text = &mut patch.text;
            text.extend_from_slice(b"v ");
            push_position(text, p);
            text.extend_from_slice(&line.body[tail..]);
            text.extend_from_slice(line.ending);
            patch.lines.push((start..start + line.raw.len(), text.len()));
        }
        if patch.lines.len() * DENSE < vertices.len() {
            return Block::Patch(patch);
        }
        let span = span(&vertices);
        Block::Text(patch.into_text(bytes, span.start, span.end))
    };
    let mut copied = 0;
    for window in blocks(count).chunks(WINDOW) {
        let built: Vec<Block> = window.par_iter().map(|range| block(range.clone())).collect();
        for (range, block) in window.iter().zip(built) {
            match block {
                Block::Patch(patch) => copied = patch.write(out, bytes, copied)?,
                Block::Text(text) => {
                    let span = span(range);
                    out.write_all(&bytes[copied..span.start])?;
                    out.write_all(&text)?;
                    copied = span.end;
                }
            }
        }
    }
    out.write_all(&bytes[copied..])
}

/// The offset in `code` just past the third word of `args`, where the tail of a `v` statement
/// begins: what `scan::vertex` finds, without parsing the numbers again (the file was read
/// without fault, so the three words are its position).
fn after_position(code: &[u8], args: Range<usize>) -> Option<usize> {
    scan::words(&code[args.clone()]).nth(2).map(|word| args.start + word.end)
}

/// Whether two positions are equal bit for bit (so −0.0 differs from 0.0).
fn same_bits(a: DVec3, b: DVec3) -> bool {
    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)
}

/// Writes a mesh as a new OBJ file: a comment naming sweepffd, one `v` line per position, then
/// the faces (1-based indices).
///
/// Faces in no group come first; then each group in order, as a `g name` line followed by its
/// faces. OBJ could give a face several groups (`g a b`), but a face that belongs to several
/// groups is written once, under the first group that lists it, so it reads back as a member
/// of that group only. Whitespace in a group name is written as `_` (OBJ separates names by
/// whitespace).
pub(crate) fn write_generic(
    out: &mut impl Write,
    positions: &[DVec3],
    faces: &Faces,
    groups: &[FaceGroup],
) -> io::Result<()> {
    out.write_all(b"# written by sweepffd\n")?;
    let vertices = |range: Range<usize>| {
        let mut text = Vec::with_capacity(range.len() * 64);
        for &p in &positions[range] {
            text.extend_from_slice(b"v ");
            push_position(&mut text, p);
            text.push(b'\n');
        }
        text
    };
    write_blocks(out, positions.len(), vertices)?;
    let owner = first_groups(faces.len(), groups);
    write_faces(out, faces, &owner, None)?;
    for (g, group) in groups.iter().enumerate() {
        if !owner.contains(&Some(g)) {
            continue;
        }
        let name: String = group.name.chars().map(|c| if c.is_whitespace() { '_' } else { c }).collect();
        writeln!(out, "g {name}")?;
        write_faces(out, faces, &owner, Some(g))?;
    }
    Ok(())
}

/// For each face, the first group that lists it.
fn first_groups(face_count: usize, groups: &[FaceGroup]) -> Vec<Option<usize>> {
    let mut owner = vec![None; face_count];
    for (g, group) in groups.iter().enumerate() {
        for &f in &group.faces {
            if let Some(slot @ None) = owner.get_mut(f as usize) {
                *slot = Some(g);
            }
        }
    }
    owner
}

/// Writes the `f` lines of the faces whose first group is `group`.
fn write_faces(out: &mut impl Write, faces: &Faces, owner: &[Option<usize>], group: Option<usize>) -> io::Result<()> {
    let block = |range: Range<usize>| {
        let mut text = Vec::with_capacity(range.len() * 32);
        for f in range.filter(|&f| owner[f] == group) {
            text.push(b'f');
            for &v in faces.face(f) {
                text.push(b' ');
                push_decimal(&mut text, u64::from(v) + 1);
            }
            text.push(b'\n');
        }
        text
    };
    write_blocks(out, faces.len(), block)
}

/// Appends the decimal digits of `n`.
fn push_decimal(out: &mut Vec<u8>, mut n: u64) {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    loop {
        at -= 1;
        digits[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&digits[at..]);
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::formats::obj::as_read::AsRead;
    use crate::formats::obj::pieces::read_pieces;
    use crate::formats::obj::read;
    use crate::formats::obj::read::read_whole;
    use crate::mesh::Mesh;

    const MIXED: &[u8] = b"# exported\r\nmtllib m.mtl\r\no thing\r\n  v 0 0 0 1.0\r\nv 1.0 0.0 0.0 # right\r\nv 0 \\\r\n 1 0\r\nv 0 0 1 0.5 0.25 0.125\nvt 0 0\r\nvn 0 0 1\r\ng a b\r\nusemtl red\r\nf 1/1/1 2/1/1 3/1/1\r\nf 1//1 \\\n 3//1 4//1\r\n\r\n# end";

    /// The faithful write of `text` with `positions`, from the file read whole and, where it
    /// is more than one piece of 4 KiB, read in pieces (both must give the same bytes).
    fn faithful(text: &[u8], positions: &[DVec3]) -> Vec<u8> {
        let write = |(mesh, read): (Mesh, AsRead)| {
            let file = ObjFile { bytes: text.to_vec(), read, groups: mesh.groups };
            let mut out = Vec::new();
            write_faithful(&mut out, &file, positions).unwrap();
            out
        };
        let whole = write(read_whole(Path::new("m.obj"), text).unwrap());
        if let Some(pieces) = read_pieces(text, 4096) {
            assert!(write(pieces) == whole, "the faithful write differs between the file read whole and in pieces");
        }
        whole
    }

    #[test]
    fn unchanged_positions_give_identical_bytes() {
        let (mesh, _) = read(Path::new("m.obj"), MIXED.to_vec()).unwrap();
        assert_eq!(faithful(MIXED, &mesh.positions), MIXED);
    }

    #[test]
    fn moved_vertex_rewrites_only_its_line_keeping_tail_and_ending() {
        let (mesh, _) = read(Path::new("m.obj"), MIXED.to_vec()).unwrap();
        let mut moved = mesh.positions.clone();
        moved[0] = DVec3::new(0.5, -0.25, 1e-7);
        moved[1].y = 2.0;
        moved[3] = DVec3::new(0.1, 0.2, 0.3);
        let out = faithful(MIXED, &moved);
        let expected = String::from_utf8_lossy(MIXED)
            .replace("  v 0 0 0 1.0\r\n", "v 0.5 -0.25 1e-7 1.0\r\n")
            .replace("v 1.0 0.0 0.0 # right\r\n", "v 1 2 0 # right\r\n")
            .replace("v 0 0 1 0.5 0.25 0.125\n", "v 0.1 0.2 0.3 0.5 0.25 0.125\n");
        assert_eq!(String::from_utf8(out).unwrap(), expected);
    }

    #[test]
    fn moved_continued_vertex_becomes_one_line() {
        let (mesh, _) = read(Path::new("m.obj"), MIXED.to_vec()).unwrap();
        let mut moved = mesh.positions.clone();
        moved[2].x = -3.5;
        let out = faithful(MIXED, &moved);
        let expected = String::from_utf8_lossy(MIXED).replace("v 0 \\\r\n 1 0\r\n", "v -3.5 1 0\r\n");
        assert_eq!(String::from_utf8(out).unwrap(), expected);
        let (reread, _) = read(Path::new("m.obj"), expected.into_bytes()).unwrap();
        assert_eq!(reread.positions, moved);
        assert_eq!(reread.faces, mesh.faces);
    }

    #[test]
    fn negative_zero_counts_as_moved() {
        let text = b"v 0 0 0\n";
        let out = faithful(text, &[DVec3::new(-0.0, 0.0, 0.0)]);
        assert_eq!(out, b"v -0 0 0\n");
    }

    #[test]
    fn last_line_without_ending_stays_without_ending() {
        let text = b"v 1 2 3\nv 4 5 6";
        let out = faithful(text, &[DVec3::new(1.0, 2.0, 3.0), DVec3::new(4.0, 5.0, 7.5)]);
        assert_eq!(out, b"v 1 2 3\nv 4 5 7.5");
    }

    #[test]
    fn generic_writes_faces_in_no_group_first_then_each_under_its_first_group() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.5, 0.25, -1.0)];
        let mut faces = Faces::new();
        for face in [[0, 1, 2], [0, 2, 3], [1, 2, 3], [0, 1, 3]] {
            faces.push(&face);
        }
        let groups = vec![
            FaceGroup { name: "left side".into(), faces: vec![1, 3] },
            FaceGroup { name: "right".into(), faces: vec![0, 1] },
        ];
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &faces, &groups).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(
            text,
            "# written by sweepffd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.5 0.25 -1\n\
             f 2 3 4\ng left_side\nf 1 3 4\nf 1 2 4\ng right\nf 1 2 3\n"
        );
        let (back, _) = read(Path::new("m.obj"), text.into_bytes()).unwrap();
        assert_eq!(back.positions, positions);
        let back_faces: Vec<Vec<u32>> = back.faces.iter().map(<[u32]>::to_vec).collect();
        assert_eq!(back_faces, vec![vec![1, 2, 3], vec![0, 2, 3], vec![0, 1, 3], vec![0, 1, 2]]);
        assert_eq!(back.groups[0].name, "left_side");
        assert_eq!(back.groups[0].faces, vec![1, 2]);
        assert_eq!(back.groups[1].faces, vec![3]);
    }

    #[test]
    fn generic_positions_round_trip_exactly() {
        let positions = vec![DVec3::new(0.1, -1e-300, 1e300), DVec3::new(std::f64::consts::PI, -0.0, 123456.789)];
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &Faces::new(), &[]).unwrap();
        let (back, _) = read(Path::new("m.obj"), out).unwrap();
        for (a, b) in back.positions.iter().zip(&positions) {
            assert!(same_bits(*a, *b), "{a} vs {b}");
        }
    }

    /// The faithful writer as it was before blocks: a scan of every line, `core::fmt` digits.
    fn line_by_line(bytes: &[u8], original: &[DVec3], positions: &[DVec3]) -> Vec<u8> {
        let mut out = Vec::new();
        let (mut copied, mut vertex) = (0, 0);
        for line in Scanner::new(bytes) {
            let code = scan::code(&line.body);
            let (keyword, args) = scan::keyword(code);
            if keyword != scan::Keyword::Vertex {
                continue;
            }
            let i = vertex;
            vertex += 1;
            if same_bits(original[i], positions[i]) {
                continue;
            }
            let (_, tail) = scan::vertex(code, args).unwrap();
            let p = positions[i];
            out.extend_from_slice(&bytes[copied..line.start]);
            out.extend_from_slice(
                format!("v {} {} {}", fmt_coordinate(p.x), fmt_coordinate(p.y), fmt_coordinate(p.z)).as_bytes(),
            );
            out.extend_from_slice(&line.body[tail..]);
            out.extend_from_slice(line.ending);
            copied = line.start + line.raw.len();
        }
        out.extend_from_slice(&bytes[copied..]);
        out
    }

    /// [`Coordinate`] as it was written before `zmij`: through `core::fmt`.
    fn fmt_coordinate(value: f64) -> String {
        let magnitude = value.abs();
        if magnitude != 0.0 && !(1e-5..1e16).contains(&magnitude) { format!("{value:e}") } else { format!("{value}") }
    }

    fn next(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    /// A position of mixed magnitudes, with now and then a −0 or a tiny or huge coordinate.
    fn random_position(state: &mut u64) -> DVec3 {
        let mut c = || {
            let unit = (next(state) >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            match next(state) % 10 {
                0 => -0.0,
                1 => unit * 1e-9,
                2 => unit * 1e20,
                3 => (unit * 1000.0).round(),
                _ => unit,
            }
        };
        DVec3::new(c(), c(), c())
    }

    #[test]
    fn the_tail_starts_where_scan_vertex_finds_it() {
        for code in [&b"v 1 2 3"[..], b"  v\t1e-3  -0 4.5 1.0 ", b"v 1 2 3 0.5 0.25 0.125", b"v 0 \x0c1 2\t"] {
            let (_, args) = scan::keyword(code);
            let (_, tail) = scan::vertex(code, args.clone()).unwrap();
            assert_eq!(after_position(code, args), Some(tail));
        }
    }

    #[test]
    fn faithful_blocks_match_the_line_by_line_writer() {
        let mut state = 0x2545_f491_4f6c_dd1d;
        let mut text = b"# many\r\nmtllib m.mtl\n".to_vec();
        let count = 3 * BLOCK + 5;
        for i in 0..count {
            let line = match i % 7 {
                0 => format!("v {i} 0 1 1.0 # w\r\n"),
                1 => format!("  v {i} \\\n 0 2\n"),
                2 => format!("v {i} 0 3 0.5 0.5 0.5\nvt 0 0\n"),
                3 => format!("v {i}.5 -0 4\nf 1 2 3\n# c\n"),
                _ => format!("v {i} 1e-3 5\n"),
            };
            text.extend_from_slice(line.as_bytes());
        }
        text.extend_from_slice(b"g end\nf 1 2 3");
        let (mesh, _) = read(Path::new("m.obj"), text.clone()).unwrap();
        assert_eq!(mesh.positions.len(), count);
        let patterns: [&dyn Fn(usize) -> bool; 5] =
            [&|_| false, &|_| true, &|i| i == 0 || i == count - 1, &|i| (BLOCK..2 * BLOCK).contains(&i), &|i| {
                i % 97 == 3
            }];
        for moves in patterns {
            let positions: Vec<DVec3> = mesh
                .positions
                .iter()
                .enumerate()
                .map(|(i, &p)| if moves(i) { random_position(&mut state) } else { p })
                .collect();
            let got = faithful(&text, &positions);
            assert!(got == line_by_line(&text, &mesh.positions, &positions), "the block writer differs");
        }
    }

    #[test]
    fn generic_blocks_match_core_fmt() {
        let mut state = 7;
        let count = 2 * BLOCK + 3;
        let positions: Vec<DVec3> = (0..count).map(|_| random_position(&mut state)).collect();
        let mut faces = Faces::new();
        for f in 0..count as u32 - 3 {
            if f % 3 == 0 {
                faces.push(&[f, f + 1, f + 2, f + 3]);
            } else {
                faces.push(&[f, f + 2, f + 1]);
            }
        }
        let groups = vec![FaceGroup { name: "a b".into(), faces: (0..count as u32 / 2).step_by(3).collect() }];
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &faces, &groups).unwrap();
        let mut expected = String::from("# written by sweepffd\n");
        for p in &positions {
            expected += &format!("v {} {} {}\n", fmt_coordinate(p.x), fmt_coordinate(p.y), fmt_coordinate(p.z));
        }
        let owner = first_groups(faces.len(), &groups);
        for group in [None, Some(0)] {
            if group.is_some() {
                expected += "g a_b\n";
            }
            for (face, _) in faces.iter().zip(&owner).filter(|(_, o)| **o == group) {
                expected += "f";
                for &v in face {
                    expected += &format!(" {}", v + 1);
                }
                expected += "\n";
            }
        }
        assert!(out == expected.as_bytes(), "the generic block writer differs");
    }
}
