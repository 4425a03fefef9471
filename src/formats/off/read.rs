//! Reading an OFF file into a [`Mesh`].

use std::path::Path;
use std::str::FromStr;

use glam::DVec3;

use super::OffFile;
use super::error::OffLineError;
use super::lines::{Line, Lines};
use crate::formats::MeshError;
use crate::formats::loaded::{LoadedMesh, Original, Source};
use crate::mesh::{Faces, Limited, Mesh};

/// What the header keyword says each vertex line holds beyond `x y z`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Header {
    /// `N`: a normal after the coordinates.
    normals: bool,
    /// `ST`: texture coordinates at the end of the line.
    texture: bool,
}

impl Header {
    /// How many numbers a vertex line holds at least (colours may add more).
    fn needed(self) -> usize {
        3 + if self.normals { 3 } else { 0 } + if self.texture { 2 } else { 0 }
    }
}

/// Reads the OFF file `bytes` (read from `path`, which errors name).
pub(crate) fn read(path: &Path, bytes: Vec<u8>) -> Result<LoadedMesh, MeshError> {
    let mut lines = Lines::new(&bytes);
    let error = |line: usize, problem| MeshError::Off { path: path.to_path_buf(), line, problem };
    let Some(first) = lines.next() else {
        return Err(MeshError::Empty { path: path.to_path_buf() });
    };
    let header = header(first.tokens[0].1).map_err(|p| error(first.number, p))?;
    let counts = if first.tokens.len() > 1 {
        Line { number: first.number, tokens: first.tokens[1..].to_vec() }
    } else {
        match lines.next() {
            Some(line) => line,
            None => return Err(error(lines.number.max(1), OffLineError::MissingCounts)),
        }
    };
    if counts.tokens.first().is_some_and(|t| t.1.eq_ignore_ascii_case(b"BINARY")) {
        return Err(error(counts.number, OffLineError::Unsupported { what: "binary OFF" }));
    }
    if counts.tokens.len() < 2 {
        return Err(error(counts.number, OffLineError::MissingCounts));
    }
    let vertex_count: usize = number(counts.tokens[0].1, "vertex count").map_err(|p| error(counts.number, p))?;
    let face_count: usize = number(counts.tokens[1].1, "face count").map_err(|p| error(counts.number, p))?;
    if let Some((_, edges)) = counts.tokens.get(2) {
        number::<usize>(edges, "edge count").map_err(|p| error(counts.number, p))?;
    }
    if vertex_count == 0 {
        return Err(MeshError::Empty { path: path.to_path_buf() });
    }
    for (limited, count) in [(Limited::Vertices, vertex_count), (Limited::Faces, face_count)] {
        limited.check(count as u64).map_err(|e| error(counts.number, OffLineError::Limit(e)))?;
    }
    // Capacities are bounded by the file size too: a vertex line takes at least 6 bytes.
    let mut positions = Vec::with_capacity(vertex_count.min(bytes.len() / 6));
    let mut coordinates = Vec::with_capacity(positions.capacity());
    for vertex in 0..vertex_count {
        let truncated = OffLineError::Truncated { what: "vertices", read: vertex, declared: vertex_count };
        let Some(line) = lines.next() else {
            return Err(error(lines.number.max(1), truncated));
        };
        let p = read_vertex(&line, vertex, header).map_err(|p| error(line.number, p))?;
        positions.push(p);
        coordinates.push(line.tokens[0].0..line.tokens[2].0 + line.tokens[2].1.len());
    }
    let mut faces = Faces::new();
    let mut face = Vec::new();
    for f in 0..face_count {
        let truncated = OffLineError::Truncated { what: "faces", read: f, declared: face_count };
        let Some(line) = lines.next() else {
            return Err(error(lines.number.max(1), truncated));
        };
        read_face(&line, f, vertex_count, &mut face).map_err(|p| error(line.number, p))?;
        faces.push_within_limits(&face).map_err(|e| error(line.number, OffLineError::Limit(e)))?;
    }
    if let Some(line) = lines.next() {
        return Err(error(line.number, OffLineError::TrailingData { faces: face_count }));
    }
    let mesh = Mesh { positions, faces, groups: Vec::new() };
    let file = OffFile { bytes, coordinates };
    Ok(LoadedMesh { source: Source::Off(Original::new(file, &mesh)), mesh })
}

/// The header keyword: `[ST][C][N]OFF`, any case.
fn header(keyword: &[u8]) -> Result<Header, OffLineError> {
    let upper = keyword.to_ascii_uppercase();
    let not_off = || OffLineError::NotOff { found: String::from_utf8_lossy(keyword).into_owned() };
    let Some(mut prefix) = upper.strip_suffix(b"OFF") else {
        return Err(not_off());
    };
    let mut take = |flag: &[u8]| match prefix.strip_prefix(flag) {
        Some(rest) => {
            prefix = rest;
            true
        }
        None => false,
    };
    let texture = take(b"ST");
    let _colors = take(b"C");
    let normals = take(b"N");
    if take(b"4") {
        return Err(OffLineError::Unsupported { what: "4D OFF (4OFF)" });
    }
    if take(b"N") {
        return Err(OffLineError::Unsupported { what: "n-dimensional OFF (nOFF)" });
    }
    if !prefix.is_empty() {
        return Err(not_off());
    }
    Ok(Header { normals, texture })
}

/// Parses `token` as a `T`, or says that the `what` is not a number.
fn number<T: FromStr>(token: &[u8], what: &'static str) -> Result<T, OffLineError> {
    std::str::from_utf8(token)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| OffLineError::NotANumber { what, token: String::from_utf8_lossy(token).into_owned() })
}

/// The position on a vertex line; every other token must be a number too.
fn read_vertex(line: &Line, vertex: usize, header: Header) -> Result<DVec3, OffLineError> {
    let needed = header.needed();
    if line.tokens.len() < needed {
        return Err(OffLineError::ShortVertex { vertex, found: line.tokens.len(), needed });
    }
    let mut xyz = [0.0; 3];
    for (value, (_, token)) in xyz.iter_mut().zip(&line.tokens) {
        *value = number(token, "vertex coordinate")?;
    }
    let p = DVec3::from_array(xyz);
    if !p.is_finite() {
        return Err(OffLineError::NonFinite { vertex });
    }
    finite_values(&line.tokens[3..], "vertex", vertex)?;
    Ok(p)
}

/// Checks that the `tokens` after the position of a vertex (normal, colour, texture
/// coordinates) or after the indices of a face (colour) are finite numbers: the faithful
/// writer copies them.
fn finite_values(tokens: &[(usize, &[u8])], what: &'static str, index: usize) -> Result<(), OffLineError> {
    for (_, token) in tokens {
        let value: f64 = number(token, if what == "vertex" { "vertex value" } else { "face colour value" })?;
        if !value.is_finite() {
            return Err(OffLineError::NonFiniteValue {
                what,
                index,
                token: String::from_utf8_lossy(token).into_owned(),
            });
        }
    }
    Ok(())
}

/// The vertex indices of a face line into `face`; the tokens after them (a colour) must be
/// finite numbers.
fn read_face(line: &Line, f: usize, count: usize, face: &mut Vec<u32>) -> Result<(), OffLineError> {
    let declared: usize = number(line.tokens[0].1, "face vertex count")?;
    if declared < 3 {
        return Err(OffLineError::ShortFace { face: f, count: declared });
    }
    Limited::FaceCorners.check(declared as u64).map_err(OffLineError::Limit)?;
    let found = line.tokens.len() - 1;
    if found < declared {
        return Err(OffLineError::MissingIndices { face: f, declared, found });
    }
    face.clear();
    for (_, token) in &line.tokens[1..=declared] {
        let index: i64 = number(token, "face index")?;
        let vertex = u32::try_from(index).ok().filter(|&v| (v as usize) < count);
        face.push(vertex.ok_or(OffLineError::IndexOutOfRange { face: f, index, count })?);
    }
    finite_values(&line.tokens[declared + 1..], "face", f)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &str) -> Result<LoadedMesh, MeshError> {
        read(Path::new("m.off"), text.as_bytes().to_vec())
    }

    fn error(text: &str) -> String {
        load(text).unwrap_err().to_string()
    }

    const SQUARE: &str =
        "OFF\n# a square and a triangle\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 2\n4 0 1 2 3\n3 0 1 4\n";

    #[test]
    fn reads_polygons_comments_and_unused_vertices() {
        let mesh = load(SQUARE).unwrap();
        assert_eq!(mesh.mesh.positions.len(), 5);
        assert_eq!(mesh.mesh.faces.face(0), &[0, 1, 2, 3]);
        assert_eq!(mesh.mesh.faces.face(1), &[0, 1, 4]);
        assert!(mesh.mesh.groups.is_empty());
    }

    #[test]
    fn header_variants_and_counts_on_the_header_line() {
        let text = "CNOFF 3 1\n0 0 0  0 0 1  255 0 0 255\n1 0 0 0 0 1 0 255 0 255\n0 1 0 0 0 1 0 0 255 255\n3 0 1 2 0.5 0.5 0.5\n";
        let mesh = load(text).unwrap();
        assert_eq!(mesh.mesh.positions[1], DVec3::X);
        let text = "stoff\n3 1 3\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 2 1 0\n";
        assert_eq!(load(text).unwrap().mesh.faces.face(0), &[2, 1, 0]);
    }

    #[test]
    fn header_errors() {
        assert_eq!(
            error("PLY\n3 1\n"),
            "m.off:1: expected an OFF header (OFF, COFF, NOFF, CNOFF, STOFF, …) but found \"PLY\""
        );
        assert_eq!(error("OFF BINARY\n"), "m.off:1: binary OFF is not supported");
        assert_eq!(error("4OFF\n1 0\n"), "m.off:1: 4D OFF (4OFF) is not supported");
        assert_eq!(error("OFF\n3\n"), "m.off:2: expected the vertex and face counts (and optionally the edge count)");
        assert_eq!(error("OFF\n"), "m.off:1: expected the vertex and face counts (and optionally the edge count)");
        assert_eq!(error("OFF\nthree 1 0\n"), "m.off:2: vertex count \"three\" is not a number");
        assert_eq!(error("OFF\n0 0 0\n"), "m.off: the mesh has no vertices");
        assert_eq!(error("# nothing\n"), "m.off: the mesh has no vertices");
    }

    #[test]
    fn truncated_files_name_the_last_line() {
        assert_eq!(
            error("OFF\n3 1 0\n0 0 0\n1 0 0\n"),
            "m.off:4: the file ends after 2 of the 3 vertices the header declares"
        );
        let text = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n";
        assert_eq!(error(text), "m.off:7: the file ends after 1 of the 2 faces the header declares");
    }

    #[test]
    fn bad_counts_leave_trailing_data() {
        let text = "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert_eq!(error(text), "m.off:6: unexpected data after the last of the 0 faces the header declares");
    }

    #[test]
    fn vertex_errors() {
        assert_eq!(error("OFF\n2 0 0\n0 0 0\n1 x 0\n"), "m.off:4: vertex coordinate \"x\" is not a number");
        assert_eq!(
            error("OFF\n2 0 0\n0 0 0\n1 0\n"),
            "m.off:4: vertex 1 has 2 numbers but the header asks for at least 3"
        );
        assert_eq!(
            error("NOFF\n1 0 0\n0 0 0 1\n"),
            "m.off:3: vertex 0 has 4 numbers but the header asks for at least 6"
        );
        assert_eq!(error("OFF\n1 0 0\n0 nan 0\n"), "m.off:3: vertex 0 has a non-finite coordinate");
        assert_eq!(error("COFF\n1 0 0\n0 0 0 red 0 0 1\n"), "m.off:3: vertex value \"red\" is not a number");
    }

    #[test]
    fn face_errors() {
        let base = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
        assert_eq!(
            error(&format!("{base}3 0 1 3\n")),
            "m.off:6: face 0 refers to vertex 3 but the file has 3 vertices (indices start at 0)"
        );
        assert_eq!(
            error(&format!("{base}3 0 -1 2\n")),
            "m.off:6: face 0 refers to vertex -1 but the file has 3 vertices (indices start at 0)"
        );
        assert_eq!(error(&format!("{base}2 0 1\n")), "m.off:6: face 0 has 2 vertices; a face needs at least 3");
        assert_eq!(error(&format!("{base}4 0 1 2\n")), "m.off:6: face 0 declares 4 vertices but lists 3");
        assert_eq!(error(&format!("{base}3 0 1.5 2\n")), "m.off:6: face index \"1.5\" is not a number");
    }

    #[test]
    fn huge_counts_do_not_allocate_or_panic() {
        assert_eq!(
            error("OFF\n99999999999 1 0\n"),
            "m.off:2: 99999999999 vertices, over the limit of 33554432 (limits::MAX_VERTICES)"
        );
        assert!(error("OFF\n9999999 1 0\n0 0 0\n").contains("the file ends after 1 of the 9999999 vertices"));
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..300 {
            let mut noisy = SQUARE.as_bytes().to_vec();
            for _ in 0..3 {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let at = (state % noisy.len() as u64) as usize;
                noisy[at] = (state >> 40) as u8;
            }
            let _ = read(Path::new("m.off"), noisy);
        }
    }
}
