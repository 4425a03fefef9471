//! Reading an OBJ file into a [`Mesh`], keeping the file's vertex order.
//!
//! Groups: `g a b` makes `a` and `b` the current groups (`g` alone: no group); `o name` sets
//! the current object, which also acts as a group because Blender writes objects rather than
//! groups. A face belongs to every current group and to the current object. Groups are listed
//! in order of first appearance; a group that ends up with no face is dropped.
//!
//! A file is read as [`Part`]s, runs of whole logical lines, joined in file order
//! ([`super::join`]). A part read on its own does not know what comes before it: it keeps its
//! negative face indices relative to its own vertices and its `g` and `o` statements as events,
//! resolved and replayed when the parts are joined. With the feature `parallel` a large file is
//! cut into many parts read on every core ([`super::pieces`]); if any of them finds a fault, or
//! the joined counts cross a limit, the file is read again as one part, which stops at the
//! first fault in file order: errors name the same line as reading line by line would.

use std::path::Path;

use glam::DVec3;

use super::as_read::AsRead;
use super::join::join;
use super::part::{GroupChange, Part};
use super::plain;
use super::scan::{self, Keyword, Scanner, VertexIssue};
use crate::formats::{MeshError, ObjLineError};
use crate::mesh::{Faces, Limited, Mesh};

/// Reads `bytes` as one part, on the calling thread: the mesh and the file's data as read,
/// or the first fault in file order.
pub(crate) fn read_whole(path: &Path, bytes: &[u8]) -> Result<(Mesh, AsRead), MeshError> {
    let obj_error = |line, problem| MeshError::Obj { path: path.to_path_buf(), line, problem };
    let part = read_part(bytes, 0, true).map_err(|(line, problem)| obj_error(line, problem))?;
    let count = part.positions.len();
    if count == 0 {
        return Err(MeshError::Empty { path: path.to_path_buf() });
    }
    if let Some((index, line)) = part.largest.filter(|&(i, _)| i > count as i64) {
        return Err(obj_error(line, ObjLineError::IndexOutOfRange { index, count }));
    }
    Ok(join(vec![part]))
}

/// Checks that every word of `text` is a finite number (the values of `vt`, `vn`, `vp`, and
/// the w or colour after a position): the faithful writer copies them verbatim.
fn finite_numbers(text: &[u8], what: &'static str) -> Result<(), ObjLineError> {
    for range in scan::words(text) {
        let word = &text[range];
        let value =
            super::float::parse(word).ok_or_else(|| ObjLineError::NotANumber { what, token: scan::lossy(word) })?;
        if !value.is_finite() {
            return Err(ObjLineError::NonFiniteValue { what, token: scan::lossy(word) });
        }
    }
    Ok(())
}

/// Reads the logical lines of `bytes`, which lie at byte `offset` of the file; `starts_file`
/// when `offset` is 0. Stops at the first fault, with its line, counted from 1 at the start of
/// `bytes`: the file's line, vertex numbers and limits are exact only when `starts_file`.
///
/// A plain `v` or `f` line is read by the fast path ([`super::plain`]), every other logical
/// line by the statement reader, which gives the same result for plain lines.
pub(crate) fn read_part(bytes: &[u8], offset: usize, starts_file: bool) -> Result<Part, (usize, ObjLineError)> {
    let mut reader =
        Reader { part: Part::default(), starts_file, offset, line: 0, face: Vec::new(), indices: Vec::new() };
    reader.part.faces = Faces::new();
    let (mut pos, mut number) = (0, 1);
    while pos < bytes.len() {
        reader.line = number;
        let (end, next) = match memchr::memchr(b'\n', &bytes[pos..]) {
            Some(i) => (pos + i, pos + i + 1),
            None => (bytes.len(), bytes.len()),
        };
        let content = &bytes[pos..if end > pos && bytes[end - 1] == b'\r' { end - 1 } else { end }];
        if content.last() == Some(&b'\\') {
            // A continued line: the scanner joins the logical line.
            let mut scanner = Scanner::resume(bytes, pos, number);
            if let Some(line) = scanner.next() {
                reader.statement(line.start, &line.body).map_err(|problem| (line.number, problem))?;
            }
            (pos, number) = scanner.position();
            continue;
        }
        if !reader.plain(pos, content).map_err(|problem| (number, problem))? {
            reader.statement(pos, content).map_err(|problem| (number, problem))?;
        }
        (pos, number) = (next, number + 1);
    }
    Ok(reader.part)
}

/// A part being read.
struct Reader {
    part: Part,
    starts_file: bool,
    /// Where the part's bytes lie in the file.
    offset: usize,
    /// The line of the statement being read.
    line: usize,
    /// The face being read, as zero-based indices.
    face: Vec<u32>,
    /// The indices of a plain face line, as written.
    indices: Vec<i64>,
}

impl Reader {
    /// Reads the physical line `line` at byte `start` of the part if it is a plain `v` or `f`
    /// line ([`super::plain`]); returns whether it was.
    fn plain(&mut self, start: usize, line: &[u8]) -> Result<bool, ObjLineError> {
        match line.first() {
            Some(b'v') => {
                let Some([x, y, z]) = plain::vertex(line) else { return Ok(false) };
                self.push_vertex(start, DVec3::new(x, y, z))?;
            }
            Some(b'f') => {
                let mut indices = std::mem::take(&mut self.indices);
                let plain = plain::face(line, &mut indices);
                let read = if plain { self.push_face(indices.iter().copied()) } else { Ok(()) };
                self.indices = indices;
                read?;
                return Ok(plain);
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// Reads the statement `body` of the logical line at byte `start` of the part.
    fn statement(&mut self, start: usize, body: &[u8]) -> Result<(), ObjLineError> {
        let code = scan::code(body);
        let (keyword, args) = scan::keyword(code);
        let faces = self.part.faces.len();
        match keyword {
            Keyword::Vertex => self.vertex(start, code, args),
            Keyword::Face => self.face(&code[args]),
            Keyword::Group => {
                let names = scan::words(&code[args.clone()])
                    .map(|w| scan::lossy(&code[args.start + w.start..args.start + w.end]))
                    .collect();
                self.part.events.push((faces, GroupChange::Groups(names)));
                Ok(())
            }
            Keyword::Object => {
                let name = code[args].trim_ascii();
                let name = (!name.is_empty()).then(|| scan::lossy(name));
                self.part.events.push((faces, GroupChange::Object(name)));
                Ok(())
            }
            Keyword::Values(what) => finite_numbers(&code[args], what),
            Keyword::Other => Ok(()),
        }
    }

    fn vertex(&mut self, start: usize, code: &[u8], args: std::ops::Range<usize>) -> Result<(), ObjLineError> {
        let ([x, y, z], tail) = scan::vertex(code, args).map_err(|issue| match issue {
            VertexIssue::NotANumber(token) => ObjLineError::NotANumber { what: "vertex coordinate", token },
            VertexIssue::Missing(found) => ObjLineError::MissingCoordinates { found },
        })?;
        let p = DVec3::new(x, y, z);
        let positions = &mut self.part.positions;
        if !p.is_finite() {
            let vertex = positions.len() + 1;
            return Err(ObjLineError::NonFinite { vertex });
        }
        finite_numbers(&code[tail..], "vertex value")?;
        self.push_vertex(start, p)
    }

    /// Adds the vertex `p` whose logical line starts at byte `start` of the part.
    fn push_vertex(&mut self, start: usize, p: DVec3) -> Result<(), ObjLineError> {
        let positions = &mut self.part.positions;
        Limited::Vertices.check(positions.len() as u64 + 1).map_err(ObjLineError::Limit)?;
        positions.push(p);
        self.part.lines.push(self.offset + start);
        Ok(())
    }

    fn face(&mut self, args: &[u8]) -> Result<(), ObjLineError> {
        let indices = scan::words(args).map(|w| {
            let word = &args[w];
            let index = word.split(|&b| b == b'/').next().unwrap_or(word);
            scan::integer(index)
                .ok_or_else(|| ObjLineError::NotANumber { what: "face index", token: scan::lossy(word) })
        });
        self.push_face_checked(indices)
    }

    /// Adds the face of the OBJ indices `indices` (as written).
    fn push_face(&mut self, indices: impl Iterator<Item = i64>) -> Result<(), ObjLineError> {
        self.push_face_checked(indices.map(Ok))
    }

    /// Adds the face of the OBJ indices `indices`, stopping at the first that is a fault.
    fn push_face_checked(
        &mut self,
        indices: impl Iterator<Item = Result<i64, ObjLineError>>,
    ) -> Result<(), ObjLineError> {
        self.face.clear();
        for index in indices {
            let resolved = self.resolve(index?)?;
            Limited::FaceCorners.check(self.face.len() as u64 + 1).map_err(ObjLineError::Limit)?;
            self.face.push(resolved);
        }
        if self.face.len() < 3 {
            let count = self.face.len();
            return Err(ObjLineError::ShortFace { count });
        }
        self.part.faces.push_within_limits(&self.face).map_err(ObjLineError::Limit)
    }

    /// The zero-based vertex of an OBJ index: positive 1-based, negative relative to the
    /// vertices read so far. Positive indices are range-checked once the vertex count is
    /// known; a negative index of a part that does not start the file is resolved when joined.
    fn resolve(&mut self, index: i64) -> Result<u32, ObjLineError> {
        let preceding = self.part.positions.len();
        if index > 0 {
            if self.part.largest.is_none_or(|(largest, _)| index > largest) {
                self.part.largest = Some((index, self.line));
            }
            return Ok(u32::try_from(index - 1).unwrap_or(u32::MAX));
        }
        if index == 0 {
            return Err(ObjLineError::ZeroIndex);
        }
        let resolved = (preceding as i64).checked_add(index);
        if !self.starts_file {
            let resolved = resolved.ok_or(ObjLineError::RelativeIndexOutOfRange { index, preceding })?;
            self.part.relative.push((self.part.faces.indices.len() + self.face.len(), resolved));
            return Ok(0);
        }
        let resolved = resolved.filter(|&r| r >= 0);
        resolved.map(|r| r as u32).ok_or(ObjLineError::RelativeIndexOutOfRange { index, preceding })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &[u8]) -> Result<Mesh, MeshError> {
        crate::formats::obj::read(Path::new("mesh.obj"), text.to_vec()).map(|(mesh, _)| mesh)
    }

    fn error(text: &[u8]) -> String {
        load(text).unwrap_err().to_string()
    }

    fn faces(mesh: &Mesh) -> Vec<Vec<u32>> {
        mesh.faces.iter().map(<[u32]>::to_vec).collect()
    }

    const SQUARE: &[u8] = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

    #[test]
    fn reads_positions_in_file_order_with_unused_vertices() {
        let mesh = load(b"v 1 2 3\nv 4 5 6 1.0\nv 7 8 9 0.1 0.2 0.3\nv -1 -2 -3\nf 1 2 3\n").unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.positions[1], DVec3::new(4.0, 5.0, 6.0));
        assert_eq!(mesh.positions[2], DVec3::new(7.0, 8.0, 9.0));
        assert_eq!(mesh.positions[3], DVec3::new(-1.0, -2.0, -3.0));
        assert_eq!(faces(&mesh), vec![vec![0, 1, 2]]);
        assert!(mesh.groups.is_empty());
    }

    #[test]
    fn coordinates_are_read_as_f64() {
        let mesh = load(b"v 0.1 1e-300 123456789.125\n").unwrap();
        assert_eq!(mesh.positions[0].x, 0.1_f64);
        assert_eq!(mesh.positions[0].y, 1e-300);
        assert_eq!(mesh.positions[0].z, 123_456_789.125);
    }

    #[test]
    fn face_tokens_with_texture_and_normal_indices() {
        let text = [SQUARE, b"vt 0 0\nvn 0 0 1\nf 1/1 2/1 3/1\nf 1//1 3//1 4//1\nf 4/1/1 3/1/1 2/1/1 1/1/1\n"].concat();
        let mesh = load(&text).unwrap();
        assert_eq!(faces(&mesh), vec![vec![0, 1, 2], vec![0, 2, 3], vec![3, 2, 1, 0]]);
    }

    #[test]
    fn negative_indices_are_relative_to_vertices_read_so_far() {
        let text = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf -4/1 -2/1/1 -1//1\n";
        let mesh = load(text).unwrap();
        assert_eq!(faces(&mesh), vec![vec![0, 1, 2], vec![0, 2, 3]]);
    }

    #[test]
    fn negative_index_before_first_vertex_is_an_error() {
        assert_eq!(
            error(b"v 0 0 0\nv 1 0 0\nf -1 -2 -3\n"),
            "mesh.obj:3: face refers to vertex -3 but only 2 vertices precede it"
        );
    }

    #[test]
    fn zero_index_is_an_error() {
        assert_eq!(
            error(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n"),
            "mesh.obj:4: face refers to vertex 0 (OBJ indices start at 1)"
        );
    }

    #[test]
    fn index_past_the_last_vertex_is_an_error_at_its_line() {
        let text = [SQUARE, b"f 1 2 3\n# c\nf 1 2 5\nf 1 2 4\n"].concat();
        assert_eq!(error(&text), "mesh.obj:7: face refers to vertex 5 but the file has 4 vertices");
        let huge = [SQUARE, b"f 1 2 99999999999999\n"].concat();
        assert_eq!(error(&huge), "mesh.obj:5: face refers to vertex 99999999999999 but the file has 4 vertices");
    }

    #[test]
    fn forward_reference_within_the_file_is_accepted() {
        let mesh = load(b"v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(faces(&mesh), vec![vec![0, 1, 2]]);
    }

    #[test]
    fn bad_face_index_is_an_error() {
        let text = [SQUARE, b"f 1 x/2 3\n"].concat();
        assert_eq!(error(&text), "mesh.obj:5: face index \"x/2\" is not a number");
        let text = [SQUARE, b"f 1 /2 3\n"].concat();
        assert_eq!(error(&text), "mesh.obj:5: face index \"/2\" is not a number");
    }

    #[test]
    fn faces_with_fewer_than_three_vertices_are_errors() {
        let text = [SQUARE, b"f 1 2\n"].concat();
        assert_eq!(error(&text), "mesh.obj:5: face has 2 vertices; a face needs at least 3");
        let text = [SQUARE, b"f\n"].concat();
        assert_eq!(error(&text), "mesh.obj:5: face has 0 vertices; a face needs at least 3");
    }

    #[test]
    fn bad_coordinate_is_an_error() {
        let text = [b"v 1 2 3\n".to_vec(), b"# x\n".repeat(10), b"v 1 abc 3\n".to_vec()].concat();
        assert_eq!(error(&text), "mesh.obj:12: vertex coordinate \"abc\" is not a number");
    }

    #[test]
    fn missing_coordinate_is_an_error() {
        assert_eq!(error(b"v 1 2\n"), "mesh.obj:1: vertex has 2 coordinates; x, y and z are needed");
    }

    #[test]
    fn non_finite_coordinate_is_an_error_naming_the_vertex() {
        let text = [b"v 0 0 0\n".repeat(10), b"\nv 1 inf 2\n".to_vec()].concat();
        assert_eq!(error(&text), "mesh.obj:12: vertex 11 has a non-finite coordinate");
        assert_eq!(error(b"v NaN 0 0\n"), "mesh.obj:1: vertex 1 has a non-finite coordinate");
    }

    #[test]
    fn errors_in_continued_lines_name_the_first_line() {
        assert_eq!(error(b"# a\nv 1 \\\n  2 \\\n q\n"), "mesh.obj:2: vertex coordinate \"q\" is not a number");
        assert_eq!(
            error(b"v 0 0 0\nv 1 0 0\\\n\nv 0 1 0\nf 1 2 \\\n 3 \\\n 9\n"),
            "mesh.obj:5: face refers to vertex 9 but the file has 3 vertices"
        );
    }

    #[test]
    fn continuation_and_crlf_and_comments_and_leading_whitespace() {
        let text = b"# head\r\n  v 0 0 0 # origin\r\n\tv 1 \\\r\n 0 0\r\nv 0 1 0\r\n\r\nf 1 \\\n 2 3 # tri\r\n";
        let mesh = load(text).unwrap();
        assert_eq!(mesh.positions[1], DVec3::X);
        assert_eq!(mesh.positions[2], DVec3::Y);
        assert_eq!(faces(&mesh), vec![vec![0, 1, 2]]);
    }

    #[test]
    fn face_belongs_to_every_current_group_and_the_object() {
        let text = [SQUARE, b"f 1 2 3\no thing\ng a b\nf 1 2 3\ng b\nf 1 3 4\ng\nf 2 3 4\ng a\nfo 1 2 4\no\nf 1 2 3\n"]
            .concat();
        let mesh = load(&text).unwrap();
        let groups: Vec<(&str, &[u32])> = mesh.groups.iter().map(|g| (g.name.as_str(), &g.faces[..])).collect();
        assert_eq!(groups, vec![("thing", &[1, 2, 3, 4][..]), ("a", &[1, 4, 5][..]), ("b", &[1, 2][..])]);
    }

    #[test]
    fn object_and_group_of_the_same_name_are_one_group() {
        let text = [SQUARE, b"o part\ng part\nf 1 2 3\n"].concat();
        let mesh = load(&text).unwrap();
        assert_eq!(mesh.groups.len(), 1);
        assert_eq!(mesh.groups[0].faces, vec![0]);
    }

    #[test]
    fn groups_without_faces_are_dropped() {
        let text = [SQUARE, b"g default\ng used\nf 1 2 3\ng empty\n"].concat();
        let mesh = load(&text).unwrap();
        assert_eq!(mesh.groups.len(), 1);
        assert_eq!(mesh.groups[0].name, "used");
    }

    #[test]
    fn other_statements_are_ignored() {
        let text = [
            &b"mtllib a.mtl\nusemtl red\ns 1\nvt 0.5 0.5\nvn 0 0 1\nvp 0.1\nl 1 2\np 1\ncstype bezier\n"[..],
            SQUARE,
            b"f 1 2 3\n",
        ]
        .concat();
        let mesh = load(&text).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.faces.len(), 1);
    }

    #[test]
    fn point_cloud_without_faces_is_allowed() {
        let mesh = load(SQUARE).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert!(mesh.faces.is_empty());
        assert_eq!(mesh.faces.offsets, vec![0]);
    }

    #[test]
    fn file_without_vertices_is_empty() {
        for text in [&b""[..], b"# nothing\n", b"\n\n\r\n", b"vt 0 0\nf 1 2 3\n"] {
            let err = load(text).unwrap_err();
            assert!(matches!(err, MeshError::Empty { .. }), "{err}");
            assert_eq!(err.to_string(), "mesh.obj: the mesh has no vertices");
        }
    }

    #[test]
    fn binary_garbage_and_non_utf8_do_not_panic() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut garbage = Vec::new();
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            garbage.push((state >> 24) as u8);
        }
        let _ = load(&garbage);
        let _ = load(b"v \xff\xfe 1 2\n");
        let _ = load(b"f \xc3\x28 1 2\n");
        let mesh = load(b"v 1 2 3\ng \xff\xfename\nf 1 1 1\n").unwrap();
        assert_eq!(mesh.groups[0].name, "\u{fffd}\u{fffd}name");
    }

    #[test]
    fn statements_of_random_lines_do_not_panic() {
        let pieces: [&[u8]; 14] =
            [b"v", b"f", b"g", b"o", b" ", b"1", b"-1", b"0", b"/", b"\\", b"\n", b"\r\n", b"#", b"1e999"];
        let mut state = 7_u64;
        for _ in 0..2_000 {
            let mut text = Vec::new();
            for _ in 0..30 {
                state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                text.extend_from_slice(pieces[(state >> 33) as usize % pieces.len()]);
            }
            let _ = load(&text);
        }
    }
}
