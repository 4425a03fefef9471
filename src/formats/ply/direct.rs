//! Reading a PLY file's data straight from its bytes, without building `ply-rs-bw`'s map of
//! named values per vertex and face (which costs most of the time of a large file); it is
//! written back by patching the bytes of the moved vertices ([`super::patch`]).
//!
//! The header is still parsed by `ply-rs-bw` (the same grammar as before); the data are then
//! walked element by element, every value read in its declared type with `ply-rs-bw`'s rules:
//! binary scalars of fixed size and lists with a count of the declared type (a negative count
//! refused); ASCII one entry per line, the line made of numbers `[-+]?d+(.d+)?([eE][-+]?d+)?`
//! separated by spaces or tabs (`ply-rs-bw`'s grammar), each value parsed with `str::parse` of
//! its type, list counts as `usize`, extra numbers at the end of a line ignored. Bytes after
//! the last element are ignored.
//!
//! This reader only accepts: a file it cannot read completely and without fault — anything
//! `ply-rs-bw` or the mesh checks of [`super::read`] would refuse, or a `vertex` element with a
//! list property, whose vertices are not of one size — gives `None`, and the file is then read
//! through `ply-rs-bw` as before, which names the fault. What it accepts it reads to the same
//! positions and faces (`tests` compare both on the fuzzing corpus and on damaged copies).

use glam::DVec3;
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{DefaultElement, ElementDef, Encoding, Header, PropertyType, ScalarType};

use super::index_list::index_list;
use crate::mesh::Faces;

/// A PLY file read by this reader, for the faithful writer.
#[derive(Debug)]
pub(crate) struct PlyBytes {
    /// The file.
    pub bytes: Vec<u8>,
    /// Its header as `ply-rs-bw` parses it.
    pub header: Header,
    /// Where the vertices' coordinates lie.
    pub layout: Layout,
    /// The declared type and the place among its vertex's values of `x`, `y` and `z`.
    pub xyz: [(usize, Scalar); 3],
}

/// Where the vertices lie in a [`PlyBytes`] file.
#[derive(Debug)]
pub(crate) enum Layout {
    /// Binary: vertex i's values start at `start + i * stride`; `offsets[k]` is the byte
    /// offset of `xyz[k]` within them.
    Binary { big_endian: bool, start: usize, stride: usize, offsets: [usize; 3] },
    /// ASCII: `lines[i]` is the offset of vertex i's line.
    Ascii { lines: Vec<usize> },
}

/// What [`read`] gives: the positions, the faces and the file's layout.
pub(crate) type Direct = (Vec<DVec3>, Faces, Header, Layout, [(usize, Scalar); 3]);

/// A PLY scalar type (`ply-rs-bw`'s `ScalarType`, which is not `Copy`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    Char,
    UChar,
    Short,
    UShort,
    Int,
    UInt,
    Float,
    Double,
}

impl From<&ScalarType> for Scalar {
    fn from(t: &ScalarType) -> Scalar {
        match t {
            ScalarType::Char => Scalar::Char,
            ScalarType::UChar => Scalar::UChar,
            ScalarType::Short => Scalar::Short,
            ScalarType::UShort => Scalar::UShort,
            ScalarType::Int => Scalar::Int,
            ScalarType::UInt => Scalar::UInt,
            ScalarType::Float => Scalar::Float,
            ScalarType::Double => Scalar::Double,
        }
    }
}

/// A property's type: a scalar, or a list with the type of its count and of its values.
#[derive(Clone, Copy)]
enum Kind {
    Scalar(Scalar),
    List(Scalar, Scalar),
}

impl From<&PropertyType> for Kind {
    fn from(t: &PropertyType) -> Kind {
        match t {
            PropertyType::Scalar(t) => Kind::Scalar(t.into()),
            PropertyType::List(count, t) => Kind::List(count.into(), t.into()),
        }
    }
}

/// The kinds of an element's properties, in order.
fn kinds(element: &ElementDef) -> Vec<Kind> {
    element.properties.values().map(|p| Kind::from(&p.data_type)).collect()
}

/// Reads `bytes` as a PLY file; `None` whenever anything is not as [`super::read`] accepts.
pub(crate) fn read(bytes: &[u8]) -> Option<Direct> {
    let mut reader = Reader::new(bytes);
    let header = Parser::<DefaultElement>::new().read_header(&mut reader).ok()?;
    let mut at = bytes.len() - reader.get_ref().len();
    let vertex = header.elements.get("vertex")?;
    let xyz = coordinates(vertex)?;
    if vertex.count == 0 || vertex.properties.values().any(|p| matches!(p.data_type, PropertyType::List(..))) {
        return None;
    }
    let face_list = match header.elements.get("face") {
        Some(face) => Some(index_list(face)?),
        None => None,
    };
    let mut data = Data { count: vertex.count, positions: Vec::new(), faces: Faces::new(), layout: None, xyz };
    for (name, element) in &header.elements {
        let list = if name == "face" { face_list } else { None };
        at = match header.encoding {
            Encoding::Ascii => data.ascii_element(bytes, at, element, name == "vertex", list)?,
            encoding => data.binary_element(bytes, at, element, encoding, name == "vertex", list)?,
        };
    }
    Some((data.positions, data.faces, header, data.layout?, xyz))
}

/// The place and type of `x`, `y` and `z` among a vertex's values, if all three are float or
/// double.
fn coordinates(vertex: &ElementDef) -> Option<[(usize, Scalar); 3]> {
    let find = |name: &str| {
        let (place, _, def) = vertex.properties.get_full(name)?;
        match Kind::from(&def.data_type) {
            Kind::Scalar(t @ (Scalar::Float | Scalar::Double)) => Some((place, t)),
            _ => None,
        }
    };
    Some([find("x")?, find("y")?, find("z")?])
}

/// The bytes of one binary value of type `t`.
fn size(t: Scalar) -> usize {
    match t {
        Scalar::Char | Scalar::UChar => 1,
        Scalar::Short | Scalar::UShort => 2,
        Scalar::Int | Scalar::UInt | Scalar::Float => 4,
        Scalar::Double => 8,
    }
}

/// A binary value of type `t` from its bytes: integers as `Ok`, floats as `Err`.
fn binary_value(raw: &[u8], t: Scalar, big_endian: bool) -> Result<i64, f64> {
    macro_rules! get {
        ($ty:ty) => {{
            let raw = raw.try_into().expect("the caller takes size(t) bytes");
            if big_endian { <$ty>::from_be_bytes(raw) } else { <$ty>::from_le_bytes(raw) }
        }};
    }
    match t {
        Scalar::Char => Ok(i64::from(get!(i8))),
        Scalar::UChar => Ok(i64::from(get!(u8))),
        Scalar::Short => Ok(i64::from(get!(i16))),
        Scalar::UShort => Ok(i64::from(get!(u16))),
        Scalar::Int => Ok(i64::from(get!(i32))),
        Scalar::UInt => Ok(i64::from(get!(u32))),
        Scalar::Float => Err(f64::from(get!(f32))),
        Scalar::Double => Err(get!(f64)),
    }
}

/// An ASCII value of type `t` parsed as `ply-rs-bw` does (`str::parse` of the type): integers as
/// `Ok`, floats as `Err`, `None` if it does not parse.
fn ascii_value(word: &str, t: Scalar) -> Option<Result<i64, f64>> {
    Some(match t {
        Scalar::Char => Ok(i64::from(word.parse::<i8>().ok()?)),
        Scalar::UChar => Ok(i64::from(word.parse::<u8>().ok()?)),
        Scalar::Short => Ok(i64::from(word.parse::<i16>().ok()?)),
        Scalar::UShort => Ok(i64::from(word.parse::<u16>().ok()?)),
        Scalar::Int => Ok(i64::from(word.parse::<i32>().ok()?)),
        Scalar::UInt => Ok(i64::from(word.parse::<u32>().ok()?)),
        Scalar::Float => Err(f64::from(word.parse::<f32>().ok()?)),
        Scalar::Double => Err(word.parse::<f64>().ok()?),
    })
}

/// The mesh data read so far.
struct Data {
    /// The vertex count.
    count: usize,
    positions: Vec<DVec3>,
    faces: Faces,
    layout: Option<Layout>,
    xyz: [(usize, Scalar); 3],
}

impl Data {
    /// Reads the binary entries of `element` from `at`; the offset after them.
    fn binary_element(
        &mut self,
        bytes: &[u8],
        at: usize,
        element: &ElementDef,
        encoding: Encoding,
        vertex: bool,
        list: Option<usize>,
    ) -> Option<usize> {
        let big_endian = encoding == Encoding::BinaryBigEndian;
        if vertex {
            return self.binary_vertices(bytes, at, element, big_endian);
        }
        // Counts come from the header: reserve only what the rest of the file can hold.
        let mut at = at;
        let mut face = Vec::new();
        let kinds = kinds(element);
        for _ in 0..element.count {
            for (place, &kind) in kinds.iter().enumerate() {
                match kind {
                    Kind::Scalar(t) => {
                        let raw = bytes.get(at..at + size(t))?;
                        at += size(t);
                        if binary_value(raw, t, big_endian).is_err_and(|v| !v.is_finite()) {
                            return None;
                        }
                    }
                    Kind::List(count_type, t) => {
                        let raw = bytes.get(at..at + size(count_type))?;
                        at += size(count_type);
                        let n = usize::try_from(binary_value(raw, count_type, big_endian).ok()?).ok()?;
                        let values = bytes.get(at..at.checked_add(n.checked_mul(size(t))?)?)?;
                        at += values.len();
                        let values = values.chunks_exact(size(t)).map(|raw| binary_value(raw, t, big_endian));
                        if list == Some(place) {
                            face.clear();
                            for value in values {
                                face.push(self.vertex_index(value.ok()?)?);
                            }
                            self.push_face(&face)?;
                        } else if values.into_iter().any(|v| v.is_err_and(|v| !v.is_finite())) {
                            return None;
                        }
                    }
                }
            }
        }
        Some(at)
    }

    /// Reads the vertices, all of one size, from `at`; the offset after them.
    fn binary_vertices(&mut self, bytes: &[u8], start: usize, element: &ElementDef, big_endian: bool) -> Option<usize> {
        let mut offsets = Vec::with_capacity(element.properties.len());
        let mut stride = 0;
        for kind in kinds(element) {
            let Kind::Scalar(t) = kind else { return None };
            offsets.push((stride, t));
            stride += size(t);
        }
        let end = start.checked_add(element.count.checked_mul(stride)?)?;
        let records = bytes.get(start..end)?;
        let floats: Vec<(usize, Scalar)> =
            offsets.iter().copied().filter(|(_, t)| matches!(t, Scalar::Float | Scalar::Double)).collect();
        let xyz = self.xyz.map(|(place, t)| (offsets[place].0, t));
        self.positions.reserve_exact(element.count);
        for record in records.chunks_exact(stride) {
            let value = |(offset, t): (usize, Scalar)| binary_value(&record[offset..offset + size(t)], t, big_endian);
            if floats.iter().any(|&f| value(f).is_err_and(|v| !v.is_finite())) {
                return None;
            }
            let [x, y, z] = xyz.map(|c| value(c).err().unwrap_or(f64::NAN));
            self.positions.push(DVec3::new(x, y, z));
        }
        self.layout = Some(Layout::Binary { big_endian, start, stride, offsets: xyz.map(|(offset, _)| offset) });
        Some(end)
    }

    /// Reads the ASCII entries of `element`, one per line from `at`; the offset after them.
    fn ascii_element(
        &mut self,
        bytes: &[u8],
        mut at: usize,
        element: &ElementDef,
        vertex: bool,
        list: Option<usize>,
    ) -> Option<usize> {
        let mut lines = Vec::new();
        let mut words: Vec<&str> = Vec::new();
        let mut face = Vec::new();
        let kinds = kinds(element);
        if vertex {
            // At least two bytes per vertex line remain, so this reserves no more than the
            // file can hold.
            let capacity = element.count.min(bytes.len().saturating_sub(at) / 2);
            lines.reserve_exact(capacity);
            self.positions.reserve_exact(capacity);
        }
        for _ in 0..element.count {
            if at >= bytes.len() {
                return None;
            }
            let end = memchr::memchr(b'\n', &bytes[at..]).map_or(bytes.len(), |i| at + i + 1);
            data_line(&bytes[at..end], &mut words)?;
            let mut next = words.iter();
            let mut xyz = [0.0; 3];
            for (place, &kind) in kinds.iter().enumerate() {
                match kind {
                    Kind::Scalar(t) => match ascii_value(next.next()?, t)? {
                        Err(v) if !v.is_finite() => return None,
                        Err(v) => {
                            if let Some(k) = self.xyz.iter().position(|&(p, _)| p == place).filter(|_| vertex) {
                                xyz[k] = v;
                            }
                        }
                        Ok(_) => {}
                    },
                    Kind::List(_, t) => {
                        let n: usize = next.next()?.parse().ok()?;
                        face.clear();
                        for _ in 0..n {
                            match ascii_value(next.next()?, t)? {
                                Ok(index) if list == Some(place) => face.push(self.vertex_index(index)?),
                                Err(v) if !v.is_finite() => return None,
                                _ => {}
                            }
                        }
                        if list == Some(place) {
                            self.push_face(&face)?;
                        }
                    }
                }
            }
            if vertex {
                self.positions.push(DVec3::from_array(xyz));
                lines.push(at);
            }
            at = end;
        }
        if vertex {
            self.layout = Some(Layout::Ascii { lines });
        }
        Some(at)
    }

    /// A face's vertex index, if it names a vertex.
    fn vertex_index(&self, index: i64) -> Option<u32> {
        u32::try_from(index).ok().filter(|&v| (v as usize) < self.count)
    }

    /// Adds a face of at least three vertices, within the limits.
    fn push_face(&mut self, face: &[u32]) -> Option<()> {
        (face.len() >= 3).then_some(())?;
        self.faces.push_within_limits(face).ok()
    }
}

/// Splits an ASCII data line (its bytes up to and including the line feed, if any) into its
/// numbers, if it matches `ply-rs-bw`'s grammar: `[ \t]*` numbers separated by `[ \t]+`, then
/// `[ \t]*`, then at most one `\r\n`, `\n` or `\r`.
fn data_line<'a>(line: &'a [u8], words: &mut Vec<&'a str>) -> Option<()> {
    words.clear();
    let line = match line.strip_suffix(b"\n") {
        Some(line) => line.strip_suffix(b"\r").unwrap_or(line),
        None => line.strip_suffix(b"\r").unwrap_or(line),
    };
    for word in line.split(|&b| b == b' ' || b == b'\t').filter(|w| !w.is_empty()) {
        if !is_number(word) {
            return None;
        }
        // ASCII digits, signs, points and exponents only.
        words.push(std::str::from_utf8(word).ok()?);
    }
    Some(())
}

/// Whether `word` is `[-+]?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?`.
fn is_number(word: &[u8]) -> bool {
    fn digits(word: &[u8]) -> (usize, &[u8]) {
        let n = word.iter().take_while(|b| b.is_ascii_digit()).count();
        (n, &word[n..])
    }
    let word = word.strip_prefix(b"-").or_else(|| word.strip_prefix(b"+")).unwrap_or(word);
    let (n, mut rest) = digits(word);
    if n == 0 {
        return false;
    }
    if let Some(fraction) = rest.strip_prefix(b".") {
        let (n, after) = digits(fraction);
        if n == 0 {
            return false;
        }
        rest = after;
    }
    if let Some(exponent) = rest.strip_prefix(b"e").or_else(|| rest.strip_prefix(b"E")) {
        let exponent = exponent.strip_prefix(b"-").or_else(|| exponent.strip_prefix(b"+")).unwrap_or(exponent);
        let (n, after) = digits(exponent);
        if n == 0 {
            return false;
        }
        rest = after;
    }
    rest.is_empty()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use ply_rs_bw::ply::{Ply, Property};
    use ply_rs_bw::writer::Writer;

    use super::*;
    use crate::formats::loaded::{LoadedMesh, Source};
    use crate::formats::ply::header;
    use crate::formats::ply::patch::write_faithful;
    use crate::formats::ply::read::read_parsed;

    fn parse(bytes: &[u8]) -> Ply<DefaultElement> {
        Parser::<DefaultElement>::new().read_ply(&mut &bytes[..]).unwrap()
    }

    /// `ply` written again in `encoding` by `ply-rs-bw`.
    fn encoded(ply: &Ply<DefaultElement>, encoding: Encoding) -> Vec<u8> {
        let mut ply = ply.clone();
        ply.header.encoding = encoding;
        let mut out = Vec::new();
        Writer::new().write_ply(&mut out, &mut ply).unwrap();
        out
    }

    /// The PLY files of the fuzzing corpus and its regressions and the shared bunny, each also
    /// in the two other encodings when it parses, and files with every kind of property.
    fn files() -> Vec<Vec<u8>> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut files = vec![MIXED.as_bytes().to_vec()];
        for dir in [root.join("fuzz/corpus/ply"), root.join("fuzz/regressions/ply"), root.join("../shared/meshes")] {
            let Ok(entries) = std::fs::read_dir(&dir) else { continue };
            let mut paths: Vec<_> = entries.flatten().map(|e| e.path()).collect();
            paths.sort();
            files.extend(
                paths.iter().filter(|p| p.extension().is_some_and(|e| e == "ply")).map(|p| std::fs::read(p).unwrap()),
            );
        }
        let mut all = Vec::new();
        for bytes in files {
            // The header check keeps the parser from reading entries that take no byte.
            let ply = header::check(&bytes)
                .ok()
                .and_then(|()| Parser::<DefaultElement>::new().read_ply(&mut &bytes[..]).ok());
            if let Some(ply) = ply {
                for encoding in [Encoding::Ascii, Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
                    all.push(encoded(&ply, encoding));
                }
            }
            all.push(bytes);
        }
        all
    }

    /// Every scalar type, lists of floats and of indices, an element before the vertices and
    /// one after the faces.
    const MIXED: &str = "ply\nformat ascii 1.0\ncomment mixed\nelement camera 1\nproperty double view\nproperty list uchar float grid\nelement vertex 4\nproperty char a\nproperty float x\nproperty uchar b\nproperty double y\nproperty short c\nproperty ushort d\nproperty float z\nproperty int e\nproperty uint f\nelement face 2\nproperty float quality\nproperty list ushort uint vertex_indices\nproperty list int char flags\nelement extra 1\nproperty list uint double w\nend_header\n0.5 2 1.5 -2.25\n-1 0 255 0.1 -300 6000 1e-3 -7 8\n1 1 0 0.2 1 2 -1.5 3 4\n-128 0.3 7 -0.0 32767 65535 2 2147483647 4294967295\n0 1 2 3 4 5 6 7 8\n0.25 3 0 1 2 2 -1 1\n0.75 4 3 2 1 0 0\n2 1e300 -1e-300\n";

    /// Checks that the direct reader reads `bytes` as `ply-rs-bw` does, or refuses what it
    /// refuses. Returns whether the direct reader read it.
    fn check(bytes: &[u8]) -> bool {
        let parsed = read_parsed(Path::new("m.ply"), bytes);
        let direct = if header::check(bytes).is_ok() { read(bytes) } else { None };
        let Some((positions, faces, ..)) = direct else { return false };
        let expected = parsed.unwrap_or_else(|e| panic!("the direct reader read a file that is an error: {e}"));
        let bits = |p: &[DVec3]| p.iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&positions), bits(&expected.mesh.positions));
        assert_eq!(faces, expected.mesh.faces);
        true
    }

    #[test]
    fn direct_and_parsed_read_the_same_files() {
        for bytes in files() {
            let parsed = read_parsed(Path::new("m.ply"), &bytes).is_ok();
            assert_eq!(check(&bytes), parsed, "{}", String::from_utf8_lossy(&bytes[..bytes.len().min(200)]));
        }
    }

    #[test]
    fn direct_and_parsed_agree_on_damaged_files() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for bytes in files().into_iter().filter(|b| b.len() < 200_000) {
            for round in 0..150 {
                let mut damaged = bytes.clone();
                match round % 3 {
                    0 => damaged.truncate((next() % bytes.len() as u64) as usize),
                    _ => {
                        for _ in 0..1 + round % 4 {
                            let at = (next() % damaged.len() as u64) as usize;
                            damaged[at] =
                                [b' ', b'\t', b'\r', b'\n', b'-', b'.', b'e', b'9', 0, 255, (next() >> 40) as u8]
                                    [(next() % 11) as usize];
                        }
                    }
                }
                check(&damaged);
            }
        }
    }

    #[test]
    fn ascii_lines_follow_the_parser_grammar() {
        let head = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        let lines = [
            "1 2 3\n",
            "1 2 3\r\n",
            "1 2 3 \t\n",
            " \t1\t2  3\n",
            "1 2 3",
            "1 2 3\r",
            "1 2 3 4 5\n",
            "+1 -2 3e+2\n",
            "1E5 2.5e-3 0\n",
            "1 2 3\r\r\n",
            "1 2 3\r \n",
            "1. 2 3\n",
            ".5 2 3\n",
            "1e 2 3\n",
            "1 2\n",
            "nan 1 2\n",
            "1e39 0 0\n",
            "0x1 2 3\n",
            "1 2 3\x0c\n",
            "1 2 3 a\n",
            "1,2 3 4\n",
            "\n1 2 3\n",
            "1 2 3\n\n",
            "",
        ];
        let mut read = 0;
        for line in lines {
            read += usize::from(check(format!("{head}{line}").as_bytes()));
        }
        assert_eq!(read, 10);
    }

    #[test]
    fn a_vertex_with_a_list_is_left_to_the_parser() {
        let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty list uchar int n\nend_header\n1 2 3 2 4 5\n";
        assert!(read(text.as_bytes()).is_none());
        let mesh = crate::formats::ply::read::read(Path::new("m.ply"), text.as_bytes().to_vec()).unwrap();
        assert_eq!(mesh.mesh.positions, vec![DVec3::new(1.0, 2.0, 3.0)]);
    }

    fn load(bytes: &[u8]) -> LoadedMesh {
        let mesh = crate::formats::ply::read::read(Path::new("m.ply"), bytes.to_vec()).unwrap();
        assert!(matches!(&mesh.source, Source::Ply(p) if matches!(p.file, crate::formats::ply::PlyFile::Bytes(_))));
        mesh
    }

    fn faithful(mesh: &LoadedMesh, positions: &[DVec3]) -> Vec<u8> {
        let Source::Ply(original) = &mesh.source else { unreachable!() };
        let crate::formats::ply::PlyFile::Bytes(file) = &original.file else { unreachable!() };
        let mut out = Vec::new();
        write_faithful(&mut out, file, &original.positions, positions).unwrap();
        out
    }

    #[test]
    fn unchanged_positions_give_the_input_bytes() {
        for bytes in files() {
            if header::check(&bytes).is_ok() && read(&bytes).is_some() {
                let mesh = load(&bytes);
                assert_eq!(faithful(&mesh, &mesh.mesh.positions), bytes);
            }
        }
    }

    #[test]
    fn moved_vertices_change_only_their_coordinates_in_their_types() {
        let source = parse(MIXED.as_bytes());
        for encoding in [Encoding::Ascii, Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
            let bytes = encoded(&source, encoding);
            let mesh = load(&bytes);
            let mut moved = mesh.mesh.positions.clone();
            moved[1] = DVec3::new(0.1, -0.2, 1e-7);
            moved[3] = DVec3::new(-0.0, 1e300, 123_456.789);
            let out = faithful(&mesh, &moved);
            let mut expected = parse(&bytes);
            for (i, p) in [(1, moved[1]), (3, moved[3])] {
                let v = &mut expected.payload["vertex"][i];
                v.insert("x".into(), Property::Float(p.x as f32));
                v.insert("y".into(), Property::Double(p.y));
                v.insert("z".into(), Property::Float(p.z as f32));
            }
            assert_eq!(parse(&out), expected, "{encoding:?}");
            if encoding == Encoding::Ascii {
                let text = String::from_utf8(out).unwrap();
                assert!(text.contains("\n1 0.1 0 -0.2 1 2 0.0000001 3 4\n"), "{text}");
            } else {
                assert_eq!(out.len(), bytes.len());
                let differing = out.iter().zip(&bytes).filter(|(a, b)| a != b).count();
                assert!(differing <= 2 * (4 + 8 + 4), "{differing} bytes differ");
            }
        }
    }
}
