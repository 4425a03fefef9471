//! Writing OFF files: faithfully over the file a mesh was read from, or generically.

use std::io::{self, Write};

use glam::DVec3;

use super::OffFile;
use crate::formats::obj::write::Coordinate;
use crate::mesh::Faces;

/// Writes the OFF file `file` with new vertex positions: every byte is copied as it is except
/// the `x y z` of vertices whose position changed (any coordinate differs bit for bit from
/// `original`), written in shortest round-trip digits ([`Coordinate`]). Normals, colours,
/// texture coordinates and comments are kept; with unchanged positions the output is
/// byte-identical to the input.
pub(crate) fn write_faithful(
    out: &mut impl Write,
    file: &OffFile,
    original: &[DVec3],
    positions: &[DVec3],
) -> io::Result<()> {
    let mut copied = 0;
    for ((range, old), new) in file.coordinates.iter().zip(original).zip(positions) {
        if old.to_array().map(f64::to_bits) == new.to_array().map(f64::to_bits) {
            continue;
        }
        out.write_all(&file.bytes[copied..range.start])?;
        write!(out, "{} {} {}", Coordinate(new.x), Coordinate(new.y), Coordinate(new.z))?;
        copied = range.end;
    }
    out.write_all(&file.bytes[copied..])?;
    out.flush()
}

/// Writes a mesh as a new OFF file: `OFF`, the counts `V F 0`, one `x y z` line per vertex
/// (shortest round-trip digits) and one `n i0 … i(n−1)` line per face.
pub(crate) fn write_generic(out: &mut impl Write, positions: &[DVec3], faces: &Faces) -> io::Result<()> {
    writeln!(out, "OFF\n{} {} 0", positions.len(), faces.len())?;
    for p in positions {
        writeln!(out, "{} {} {}", Coordinate(p.x), Coordinate(p.y), Coordinate(p.z))?;
    }
    for face in faces.iter() {
        write!(out, "{}", face.len())?;
        for index in face {
            write!(out, " {index}")?;
        }
        writeln!(out)?;
    }
    out.flush()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::formats::loaded::Source;
    use crate::formats::off::read::read;

    const COFF: &str =
        "COFF\n# colours\n3 1 0\n0 0 0 255 0 0 255\n1 0 0  0 255 0 128 # green\n0 1 0 0 0 255 255\n3 0 1 2 9 9 9\n";

    fn faithful(text: &str, moved: &[(usize, DVec3)]) -> String {
        let mesh = read(Path::new("m.off"), text.as_bytes().to_vec()).unwrap();
        let Source::Off(original) = &mesh.source else { panic!("not an OFF source") };
        let mut positions = mesh.mesh.positions.clone();
        for &(i, p) in moved {
            positions[i] = p;
        }
        let mut out = Vec::new();
        write_faithful(&mut out, &original.file, &mesh.mesh.positions, &positions).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn faithful_unchanged_is_byte_identical() {
        assert_eq!(faithful(COFF, &[]), COFF);
    }

    #[test]
    fn faithful_moved_vertex_keeps_its_colour_and_comment() {
        let out = faithful(COFF, &[(1, DVec3::new(0.5, -2.0, 1e-7))]);
        assert_eq!(out, COFF.replace("1 0 0  0 255 0 128 # green", "0.5 -2 1e-7  0 255 0 128 # green"));
    }

    #[test]
    fn generic_reads_back() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.1, 0.2, 0.3)];
        let mut faces = Faces::new();
        faces.push(&[0, 1, 2, 3]);
        faces.push(&[0, 2, 3]);
        let mut out = Vec::new();
        write_generic(&mut out, &positions, &faces).unwrap();
        let mesh = read(Path::new("m.off"), out).unwrap();
        assert_eq!(mesh.mesh.positions, positions);
        assert_eq!(mesh.mesh.faces, faces);
    }
}
