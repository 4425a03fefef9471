//! Writing PLY files: faithfully over the file a mesh was read from, or generically.

use std::io::{self, Write};

use glam::DVec3;
use ply_rs_bw::ply::{
    DefaultElement, ElementDef, Encoding, Header, Ply, Property, PropertyAccess, PropertyDef, PropertyType, ScalarType,
};
use ply_rs_bw::writer::Writer;

use super::{PlyFile, patch};
use crate::mesh::Faces;

/// Writes the PLY file `file` with new vertex positions, faithfully: a file read straight from
/// its bytes by patching them ([`patch::write_faithful`]: the output is the input with only
/// the moved vertices' coordinates changed), one read through `ply-rs-bw` by writing its data
/// again ([`write_parsed`]).
pub(crate) fn write_faithful(
    out: &mut impl Write,
    file: &PlyFile,
    original: &[DVec3],
    positions: &[DVec3],
) -> io::Result<()> {
    match file {
        PlyFile::Bytes(file) => patch::write_faithful(out, file, original, positions),
        PlyFile::Parsed(ply) => write_parsed(out, ply, original, positions),
    }
}

/// Writes the PLY file `ply` with new vertex positions: the same header (format, comments,
/// elements, properties), the same encoding and every element as read, except `x`, `y`, `z`
/// of the vertices whose position changed (any coordinate differs bit for bit from
/// `original`), stored in each property's own type (f32 for `float`, f64 for `double`).
///
/// Header comments are written before `obj_info` lines and elements, as `ply-rs-bw` keeps
/// them; the data parse back identical.
pub(crate) fn write_parsed(
    out: &mut impl Write,
    ply: &Ply<DefaultElement>,
    original: &[DVec3],
    positions: &[DVec3],
) -> io::Result<()> {
    let writer = Writer::<DefaultElement>::new();
    writer.write_header(out, &ply.header)?;
    for (name, def) in &ply.header.elements {
        let elements = ply
            .payload
            .get(name)
            .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidData, format!("no data for \"{name}\"")))?;
        if name != "vertex" {
            writer.write_payload_of_element(out, elements, def, &ply.header)?;
            continue;
        }
        for (i, element) in elements.iter().enumerate() {
            match (original.get(i), positions.get(i)) {
                (Some(old), Some(&new)) if !same_bits(*old, new) => {
                    let moved = moved(element, def, new);
                    write_element(&writer, out, &moved, def, ply.header.encoding)?;
                }
                _ => {
                    write_element(&writer, out, element, def, ply.header.encoding)?;
                }
            }
        }
    }
    out.flush()
}

/// Whether [`write_faithful`] stores some coordinate of a file of `header` as f32: `x`, `y` or
/// `z` of its `vertex` element is declared `float` (the others are written as `double`).
pub(crate) fn stores_f32(header: &Header) -> bool {
    let vertex = header.elements.get("vertex");
    ["x", "y", "z"].iter().any(|name| {
        matches!(
            vertex.and_then(|v| v.properties.get(*name)).map(|p| &p.data_type),
            Some(PropertyType::Scalar(ScalarType::Float))
        )
    })
}

/// Whether two positions are equal bit for bit.
fn same_bits(a: DVec3, b: DVec3) -> bool {
    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)
}

/// A copy of the vertex `element` at position `p`, each coordinate in its declared type.
fn moved(element: &DefaultElement, def: &ElementDef, p: DVec3) -> DefaultElement {
    let mut element = element.clone();
    for (name, value) in [("x", p.x), ("y", p.y), ("z", p.z)] {
        let property = match def.properties.get(name).map(|d| &d.data_type) {
            Some(PropertyType::Scalar(ScalarType::Float)) => Property::Float(value as f32),
            _ => Property::Double(value),
        };
        element.insert(name.to_string(), property);
    }
    element
}

fn write_element<E: PropertyAccess>(
    writer: &Writer<E>,
    out: &mut impl Write,
    element: &E,
    def: &ElementDef,
    encoding: Encoding,
) -> io::Result<usize> {
    match encoding {
        Encoding::Ascii => writer.write_ascii_element(out, element, def),
        Encoding::BinaryBigEndian => writer.write_big_endian_element(out, element, def),
        Encoding::BinaryLittleEndian => writer.write_little_endian_element(out, element, def),
    }
}

/// Writes a mesh as a new PLY file: `binary_little_endian`, a comment naming sweepffd,
/// `element vertex` with `property float x`, `y`, `z` (positions rounded to f32) and
/// `element face` with `property list uchar int vertex_indices` — `uint` instead of `uchar`
/// for the count when a face has more than 255 vertices, and `uint` instead of `int` for the
/// indices when there are more than `i32::MAX` vertices.
pub(crate) fn write_generic(out: &mut impl Write, positions: &[DVec3], faces: &Faces) -> io::Result<()> {
    let header = generic_header(positions.len(), faces);
    Writer::<DefaultElement>::new().write_header(out, &header)?;
    // The payload as `ply-rs-bw` writes it for this header: little-endian f32 x, y, z per
    // vertex, then per face the count (u8 or u32) and the indices (i32 or u32, the same bits).
    let wide_count = matches!(
        header.elements["face"].properties["vertex_indices"].data_type,
        PropertyType::List(ScalarType::UInt, _)
    );
    let mut block = Vec::with_capacity(BLOCK * 12);
    for chunk in positions.chunks(BLOCK) {
        block.clear();
        for p in chunk {
            for c in p.as_vec3().to_array() {
                block.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.write_all(&block)?;
    }
    for first in (0..faces.len()).step_by(BLOCK) {
        block.clear();
        for f in first..(first + BLOCK).min(faces.len()) {
            let face = faces.face(f);
            if wide_count {
                block.extend_from_slice(&(face.len() as u32).to_le_bytes());
            } else {
                block.push(face.len() as u8);
            }
            for &v in face {
                block.extend_from_slice(&v.to_le_bytes());
            }
        }
        out.write_all(&block)?;
    }
    out.flush()
}

/// Vertices or faces per block of a generic write.
const BLOCK: usize = 1 << 16;

fn generic_header(vertex_count: usize, faces: &Faces) -> Header {
    let mut header = Header::new();
    header.encoding = Encoding::BinaryLittleEndian;
    header.comments.push("written by sweepffd".to_string());
    let mut vertex = ElementDef::new("vertex".to_string());
    vertex.count = vertex_count;
    for name in ["x", "y", "z"] {
        let def = PropertyDef::new(name.to_string(), PropertyType::Scalar(ScalarType::Float));
        vertex.properties.insert(name.to_string(), def);
    }
    let mut face = ElementDef::new("face".to_string());
    face.count = faces.len();
    let count_type =
        if faces.iter().all(|f| f.len() <= usize::from(u8::MAX)) { ScalarType::UChar } else { ScalarType::UInt };
    let index_type = if vertex_count <= i32::MAX as usize { ScalarType::Int } else { ScalarType::UInt };
    let list = PropertyType::List(count_type, index_type);
    let def = PropertyDef::new("vertex_indices".to_string(), list);
    face.properties.insert(def.name.clone(), def);
    header.elements.insert(vertex.name.clone(), vertex);
    header.elements.insert(face.name.clone(), face);
    header
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::formats::ply::read::read;

    const ASCII: &str = "ply\nformat ascii 1.0\ncomment keep me\nelement vertex 3\nproperty float x\nproperty double y\nproperty float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\nproperty float quality\nelement extra 1\nproperty int stuff\nend_header\n0 0 0 10\n1 0.1 0 20\n0 1 0.5 30\n3 0 1 2 0.75\n42\n";

    fn parse(bytes: &[u8]) -> Ply<DefaultElement> {
        ply_rs_bw::parser::Parser::<DefaultElement>::new().read_ply(&mut &bytes[..]).unwrap()
    }

    #[test]
    fn faithful_unchanged_parses_to_the_same_data() {
        let mesh = read(Path::new("m.ply"), ASCII.as_bytes().to_vec()).unwrap();
        let original = parse(ASCII.as_bytes());
        let mut out = Vec::new();
        write_parsed(&mut out, &original, &mesh.mesh.positions, &mesh.mesh.positions).unwrap();
        assert_eq!(parse(&out), original);
    }

    #[test]
    fn faithful_moved_vertex_changes_only_its_coordinates_in_their_types() {
        let mesh = read(Path::new("m.ply"), ASCII.as_bytes().to_vec()).unwrap();
        let original = parse(ASCII.as_bytes());
        let mut moved = mesh.mesh.positions.clone();
        moved[1] = DVec3::new(0.1, 0.2, 0.3);
        for encoding in [Encoding::Ascii, Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
            let mut source = original.clone();
            source.header.encoding = encoding;
            let mut out = Vec::new();
            write_parsed(&mut out, &source, &mesh.mesh.positions, &moved).unwrap();
            let back = parse(&out);
            assert_eq!(back.header, source.header);
            let mut expected = source.clone();
            let v = &mut expected.payload["vertex"][1];
            v.insert("x".into(), Property::Float(0.1));
            v.insert("y".into(), Property::Double(0.2));
            v.insert("z".into(), Property::Float(0.3));
            assert_eq!(back, expected, "{encoding:?}");
        }
    }

    #[test]
    fn generic_is_binary_little_endian_float_with_uchar_int_lists() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::new(0.1, 0.2, 0.3)];
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2]);
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &faces).unwrap();
        let back = parse(&out);
        assert_eq!(back.header.encoding, Encoding::BinaryLittleEndian);
        assert_eq!(
            back.header.elements["face"].properties["vertex_indices"].data_type,
            PropertyType::List(ScalarType::UChar, ScalarType::Int)
        );
        assert_eq!(back.payload["vertex"][2]["y"], Property::Float(0.2));
        assert_eq!(back.payload["face"][0]["vertex_indices"], Property::ListInt(vec![0, 1, 2]));
    }

    #[test]
    fn generic_face_of_more_than_255_vertices_uses_a_uint_count() {
        let n = 300;
        let positions: Vec<DVec3> = (0..n)
            .map(|i| {
                let a = i as f64 / n as f64 * std::f64::consts::TAU;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let mut faces = Faces::new();
        faces.push(&(0..n).collect::<Vec<u32>>());
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &faces).unwrap();
        let mesh = read(Path::new("m.ply"), out.clone()).unwrap();
        assert_eq!(mesh.mesh.faces, faces);
        let back = parse(&out);
        assert_eq!(
            back.header.elements["face"].properties["vertex_indices"].data_type,
            PropertyType::List(ScalarType::UInt, ScalarType::Int)
        );
    }

    /// The generic file as `ply-rs-bw` writes it from the same header, element by element.
    fn written_by_ply_rs(positions: &[DVec3], faces: &Faces) -> Vec<u8> {
        let header = generic_header(positions.len(), faces);
        let index_type = match &header.elements["face"].properties["vertex_indices"].data_type {
            PropertyType::List(_, t) => t.clone(),
            PropertyType::Scalar(_) => unreachable!(),
        };
        let mut ply = Ply::<DefaultElement>::new();
        ply.header = header;
        let vertices = positions
            .iter()
            .map(|p| {
                let mut e = DefaultElement::new();
                for (name, c) in ["x", "y", "z"].into_iter().zip(p.as_vec3().to_array()) {
                    e.insert(name.into(), Property::Float(c));
                }
                e
            })
            .collect();
        let faces = faces
            .iter()
            .map(|f| {
                let mut e = DefaultElement::new();
                let list = match index_type {
                    ScalarType::Int => Property::ListInt(f.iter().map(|&v| v as i32).collect()),
                    _ => Property::ListUInt(f.to_vec()),
                };
                e.insert("vertex_indices".into(), list);
                e
            })
            .collect();
        ply.payload.insert("vertex".into(), vertices);
        ply.payload.insert("face".into(), faces);
        let mut out = Vec::new();
        Writer::new().write_ply(&mut out, &mut ply).unwrap();
        out
    }

    #[test]
    fn generic_payload_is_what_ply_rs_writes() {
        let n = 3 * BLOCK as u32 + 7;
        let positions: Vec<DVec3> = (0..n).map(|i| DVec3::new(f64::from(i) * 0.1, -f64::from(i), 1e-3)).collect();
        let mut faces = Faces::new();
        for f in 0..n - 3 {
            faces.push(&[f, f + 1, f + 2]);
        }
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &faces).unwrap();
        assert!(out == written_by_ply_rs(&positions, &faces), "small faces differ");
        faces.push(&(0..300).collect::<Vec<u32>>());
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &faces).unwrap();
        assert!(out == written_by_ply_rs(&positions, &faces), "a face of 300 vertices differs");
    }
}
