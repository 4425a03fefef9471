//! Reading a PLY file into a [`Mesh`].

use std::path::Path;

use glam::DVec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, ElementDef, Ply, Property, PropertyType, ScalarType};

use super::direct::{self, PlyBytes};
use super::index_list::index_list;
use super::{PlyFile, header};
use crate::formats::MeshError;
use crate::formats::loaded::{LoadedMesh, Original, Source};
use crate::mesh::{Faces, Mesh, MeshDataError};

/// Reads the PLY file `bytes` (read from `path`, which errors name): straight from the bytes
/// ([`direct`]) when that reader accepts the file, else through `ply-rs-bw`, which names the
/// fault (or reads what the direct reader leaves to it, a `vertex` element with a list).
pub(crate) fn read(path: &Path, bytes: Vec<u8>) -> Result<LoadedMesh, MeshError> {
    header::check(&bytes).map_err(|(line, problem)| MeshError::PlyHeader {
        path: path.to_path_buf(),
        line,
        problem,
    })?;
    if let Some((positions, faces, header, layout, xyz)) = direct::read(&bytes) {
        let mesh = Mesh { positions, faces, groups: Vec::new() };
        let file = PlyFile::Bytes(PlyBytes { bytes, header, layout, xyz });
        return Ok(LoadedMesh { source: Source::Ply(Original::new(file, &mesh)), mesh });
    }
    read_parsed(path, &bytes)
}

/// Reads the PLY file `bytes` through `ply-rs-bw`.
pub(crate) fn read_parsed(path: &Path, bytes: &[u8]) -> Result<LoadedMesh, MeshError> {
    header::check(bytes).map_err(|(line, problem)| MeshError::PlyHeader { path: path.to_path_buf(), line, problem })?;
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut &bytes[..])
        .map_err(|e| MeshError::InvalidPly { path: path.to_path_buf(), reason: one_line(&e.to_string()) })?;
    let positions = positions(path, &ply)?;
    let faces = faces(path, &ply, positions.len())?;
    check_finite(path, &ply)?;
    let mesh = Mesh { positions, faces, groups: Vec::new() };
    Ok(LoadedMesh { source: Source::Ply(Original::new(PlyFile::Parsed(ply), &mesh)), mesh })
}

/// The longest parser message shown, in characters: the parser quotes the offending line,
/// which may be the whole file.
const MAX_REASON_CHARS: usize = 300;

/// The parser's multi-line message on one line, without the parser's internal state (a debug
/// dump that follows `Error:`), cut to [`MAX_REASON_CHARS`].
fn one_line(message: &str) -> String {
    let message = message.split("; Error:").next().unwrap_or(message);
    let line =
        message.replace("\n'", "'").lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join("; ");
    match line.char_indices().nth(MAX_REASON_CHARS) {
        Some((cut, _)) => format!("{}…", &line[..cut]),
        None => line,
    }
}

/// Whether the `vertex` element declares float or double `x`, `y` and `z`.
fn has_coordinates(vertex: &ElementDef) -> bool {
    ["x", "y", "z"].iter().all(|name| {
        matches!(
            vertex.properties.get(*name).map(|p| &p.data_type),
            Some(PropertyType::Scalar(ScalarType::Float | ScalarType::Double))
        )
    })
}

fn positions(path: &Path, ply: &Ply<DefaultElement>) -> Result<Vec<DVec3>, MeshError> {
    let no_vertices = || MeshError::NoPlyVertices { path: path.to_path_buf() };
    let def = ply.header.elements.get("vertex").ok_or_else(no_vertices)?;
    if !has_coordinates(def) {
        return Err(no_vertices());
    }
    let vertices = ply.payload.get("vertex").map_or(&[][..], Vec::as_slice);
    if vertices.is_empty() {
        return Err(MeshError::Empty { path: path.to_path_buf() });
    }
    // The header check bounds the count by limits::MAX_VERTICES, and the parser has read them.
    let mut positions = Vec::with_capacity(vertices.len());
    for (vertex, element) in vertices.iter().enumerate() {
        let coordinate = |name| match element.get(name) {
            Some(Property::Float(v)) => Some(f64::from(*v)),
            Some(Property::Double(v)) => Some(*v),
            _ => None,
        };
        let (Some(x), Some(y), Some(z)) = (coordinate("x"), coordinate("y"), coordinate("z")) else {
            return Err(no_vertices());
        };
        let p = DVec3::new(x, y, z);
        if !p.is_finite() {
            return Err(MeshError::PlyData { path: path.to_path_buf(), problem: MeshDataError::NonFinite { vertex } });
        }
        positions.push(p);
    }
    Ok(positions)
}

fn faces(path: &Path, ply: &Ply<DefaultElement>, count: usize) -> Result<Faces, MeshError> {
    let mut faces = Faces::new();
    let Some(def) = ply.header.elements.get("face") else {
        return Ok(faces);
    };
    let name = index_list(def).and_then(|place| def.properties.get_index(place)).map(|(name, _)| name.as_str());
    let name = name.ok_or_else(|| MeshError::NoPlyFaceIndices { path: path.to_path_buf() })?;
    let data_error = |problem| MeshError::PlyData { path: path.to_path_buf(), problem };
    let mut face = Vec::new();
    for (f, element) in ply.payload.get("face").into_iter().flatten().enumerate() {
        face.clear();
        let list = element.get(name).map(integers).unwrap_or_default();
        for index in list {
            let vertex = u32::try_from(index).ok().filter(|&v| (v as usize) < count);
            let vertex = vertex.ok_or_else(|| data_error(MeshDataError::IndexOutOfRange { face: f, index, count }))?;
            face.push(vertex);
        }
        if face.len() < 3 {
            let count = face.len();
            return Err(data_error(MeshDataError::ShortFace { face: f, count }));
        }
        faces.push_within_limits(&face).map_err(|problem| MeshError::Limit { path: path.to_path_buf(), problem })?;
    }
    Ok(faces)
}

/// Checks that every `float` and `double` value of every element, scalar or in a list, is
/// finite: the faithful writer copies them all.
fn check_finite(path: &Path, ply: &Ply<DefaultElement>) -> Result<(), MeshError> {
    for (name, entries) in &ply.payload {
        for (entry, element) in entries.iter().enumerate() {
            for (property, value) in element {
                let bad = match value {
                    Property::Float(v) => (!v.is_finite()).then_some(f64::from(*v)),
                    Property::Double(v) => (!v.is_finite()).then_some(*v),
                    Property::ListFloat(v) => v.iter().find(|v| !v.is_finite()).map(|&v| f64::from(v)),
                    Property::ListDouble(v) => v.iter().find(|v| !v.is_finite()).copied(),
                    _ => None,
                };
                if let Some(value) = bad {
                    let (element, property) = (name.clone(), property.clone());
                    return Err(MeshError::PlyNonFinite { path: path.to_path_buf(), element, entry, property, value });
                }
            }
        }
    }
    Ok(())
}

/// The values of an integer list property, widened to i64 (empty for anything else).
fn integers(property: &Property) -> Vec<i64> {
    fn widen<T: Copy + Into<i64>>(values: &[T]) -> Vec<i64> {
        values.iter().map(|&v| v.into()).collect()
    }
    match property {
        Property::ListChar(v) => widen(v),
        Property::ListUChar(v) => widen(v),
        Property::ListShort(v) => widen(v),
        Property::ListUShort(v) => widen(v),
        Property::ListInt(v) => widen(v),
        Property::ListUInt(v) => widen(v),
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &[u8]) -> Result<LoadedMesh, MeshError> {
        read(Path::new("m.ply"), text.to_vec())
    }

    fn error(text: &str) -> String {
        load(text.as_bytes()).unwrap_err().to_string()
    }

    fn ply(vertex_props: &str, face_prop: &str, body: &str) -> String {
        format!(
            "ply\nformat ascii 1.0\ncomment test\nelement vertex 4\n{vertex_props}element face 2\n{face_prop}end_header\n{body}"
        )
    }

    const XYZ: &str = "property float x\nproperty float y\nproperty double z\nproperty uchar red\n";
    const SQUARE: &str = "0 0 0 9\n1 0 0 9\n1 1 0.5 9\n0 1 0 9\n";

    #[test]
    fn reads_float_and_double_coordinates_and_index_lists() {
        let text = ply(XYZ, "property list uchar uint vertex_indices\n", &format!("{SQUARE}3 0 1 2\n4 0 1 2 3\n"));
        let mesh = load(text.as_bytes()).unwrap();
        assert_eq!(mesh.mesh.positions[2], DVec3::new(1.0, 1.0, 0.5));
        assert_eq!(mesh.mesh.faces.face(1), &[0, 1, 2, 3]);
        assert!(mesh.mesh.groups.is_empty());
    }

    #[test]
    fn vertex_index_name_and_signed_short_lists_are_accepted() {
        let text = ply(XYZ, "property list int short vertex_index\n", &format!("{SQUARE}3 0 1 2\n3 2 3 0\n"));
        let mesh = load(text.as_bytes()).unwrap();
        assert_eq!(mesh.mesh.faces.face(1), &[2, 3, 0]);
    }

    #[test]
    fn index_out_of_range_names_the_face() {
        let text = ply(XYZ, "property list uchar int vertex_indices\n", &format!("{SQUARE}3 0 1 2\n3 0 4 2\n"));
        assert_eq!(error(&text), "m.ply: face 1 refers to vertex 4 but the mesh has 4 vertices");
        let text = ply(XYZ, "property list uchar int vertex_indices\n", &format!("{SQUARE}3 0 -1 2\n3 0 1 2\n"));
        assert_eq!(error(&text), "m.ply: face 0 refers to vertex -1 but the mesh has 4 vertices");
    }

    #[test]
    fn short_face_is_an_error() {
        let text = ply(XYZ, "property list uchar int vertex_indices\n", &format!("{SQUARE}3 0 1 2\n2 0 1\n"));
        assert_eq!(error(&text), "m.ply: face 1 has 2 vertices; a face needs at least 3");
    }

    #[test]
    fn integer_or_missing_coordinates_are_no_vertex_element() {
        let ints = "property int x\nproperty int y\nproperty int z\n";
        let text =
            ply(ints, "property list uchar int vertex_indices\n", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n");
        assert_eq!(error(&text), "m.ply: no \"vertex\" element with x, y, z properties");
        let text = "ply\nformat ascii 1.0\nelement point 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
        assert_eq!(error(text), "m.ply: no \"vertex\" element with x, y, z properties");
    }

    #[test]
    fn face_without_index_list_is_an_error() {
        let text = ply(XYZ, "property list uchar float vertex_indices\n", &format!("{SQUARE}3 0 1 2\n3 0 1 2\n"));
        assert!(error(&text).contains("no integer list property vertex_indices"), "{}", error(&text));
    }

    #[test]
    fn point_cloud_is_allowed_and_no_vertices_is_empty() {
        let text = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 2 3\n";
        let mesh = load(text.as_bytes()).unwrap();
        assert_eq!(mesh.mesh.positions.len(), 2);
        assert!(mesh.mesh.faces.is_empty());
        let text = "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        assert_eq!(error(text), "m.ply: the mesh has no vertices");
    }

    #[test]
    fn non_finite_coordinate_is_an_error() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n".to_vec();
        for v in [0.0, 0.0, 0.0, 1.0, f32::NAN, 3.0_f32] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let message = load(&bytes).unwrap_err().to_string();
        assert_eq!(message, "m.ply: vertex 1 has a non-finite coordinate");
    }

    #[test]
    fn parser_failures_are_invalid_ply_on_one_line() {
        for text in
            ["", "not a ply\n", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n1\nabc\n"]
        {
            let message = error(text);
            assert!(message.starts_with("m.ply: not a valid PLY file: "), "{message}");
            assert!(!message.contains('\n'), "{message}");
        }
    }

    #[test]
    fn truncated_binary_and_garbage_do_not_panic() {
        let header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
        let mut bytes = header.as_bytes().to_vec();
        bytes.extend_from_slice(&[0u8; 30]);
        assert!(load(&bytes).is_err());
        bytes.extend_from_slice(&[0u8; 6]);
        bytes.extend_from_slice(&[255, 1, 0, 0, 0]);
        assert!(load(&bytes).is_err());
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..200 {
            let mut noisy = bytes.clone();
            for _ in 0..4 {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let at = (state % noisy.len() as u64) as usize;
                noisy[at] = (state >> 40) as u8;
            }
            let _ = load(&noisy);
        }
    }
}
