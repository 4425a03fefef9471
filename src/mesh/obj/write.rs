//! Writing OBJ files: faithfully over the file a mesh was read from, or generically.

use std::io::{self, Write};

use glam::DVec3;

use super::scan::{self, Keyword, Scanner};
use crate::mesh::{FaceGroup, Faces};

/// A coordinate in the shortest decimal form that reads back to the same f64: plain digits,
/// or exponent notation for magnitudes below 1e-5 or from 1e16 on (so round-off such as
/// 6.1e-17 stays short). Every OBJ reader parses both forms.
pub(crate) struct Coordinate(pub f64);

impl std::fmt::Display for Coordinate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let magnitude = self.0.abs();
        if magnitude != 0.0 && !(1e-5..1e16).contains(&magnitude) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// Writes the OBJ file `bytes` with new vertex positions.
///
/// Every byte is copied as it is except the `v` statements of vertices whose position changed
/// (any coordinate differs bit for bit from `original`, the positions read from `bytes`).
/// Such a statement is written `v x y z` (shortest round-trip digits, see [`Coordinate`]), then
/// its original text after the third number (w or colour, a comment), then its original line
/// ending; a `\`-continued statement becomes one line. With unchanged positions the output is
/// byte-identical to `bytes`.
pub(crate) fn write_faithful(
    out: &mut impl Write,
    bytes: &[u8],
    original: &[DVec3],
    positions: &[DVec3],
) -> io::Result<()> {
    let mut copied = 0;
    let mut vertex = 0;
    for line in Scanner::new(bytes) {
        let code = scan::code(&line.body);
        let (keyword, args) = scan::keyword(code);
        if keyword != Keyword::Vertex {
            continue;
        }
        let i = vertex;
        vertex += 1;
        let (Some(old), Some(new)) = (original.get(i), positions.get(i)) else {
            continue;
        };
        if same_bits(*old, *new) {
            continue;
        }
        let Ok((_, tail)) = scan::vertex(code, args) else {
            continue;
        };
        out.write_all(&bytes[copied..line.start])?;
        write!(out, "v {} {} {}", Coordinate(new.x), Coordinate(new.y), Coordinate(new.z))?;
        out.write_all(&line.body[tail..])?;
        out.write_all(line.ending)?;
        copied = line.start + line.raw.len();
    }
    out.write_all(&bytes[copied..])
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
    writeln!(out, "# written by sweepffd")?;
    for p in positions {
        writeln!(out, "v {} {} {}", Coordinate(p.x), Coordinate(p.y), Coordinate(p.z))?;
    }
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
    for (face, _) in faces.iter().zip(owner).filter(|(_, o)| **o == group) {
        out.write_all(b"f")?;
        for &v in face {
            write!(out, " {}", u64::from(v) + 1)?;
        }
        out.write_all(b"\n")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::mesh::obj::read::read;

    const MIXED: &[u8] = b"# exported\r\nmtllib m.mtl\r\no thing\r\n  v 0 0 0 1.0\r\nv 1.0 0.0 0.0 # right\r\nv 0 \\\r\n 1 0\r\nv 0 0 1 0.5 0.25 0.125\nvt 0 0\r\nvn 0 0 1\r\ng a b\r\nusemtl red\r\nf 1/1/1 2/1/1 3/1/1\r\nf 1//1 \\\n 3//1 4//1\r\n\r\n# end";

    fn faithful(text: &[u8], positions: &[DVec3]) -> Vec<u8> {
        let mesh = read(Path::new("m.obj"), text.to_vec()).unwrap();
        let mut out = Vec::new();
        write_faithful(&mut out, text, &mesh.positions, positions).unwrap();
        out
    }

    #[test]
    fn unchanged_positions_give_identical_bytes() {
        let mesh = read(Path::new("m.obj"), MIXED.to_vec()).unwrap();
        assert_eq!(faithful(MIXED, &mesh.positions), MIXED);
    }

    #[test]
    fn moved_vertex_rewrites_only_its_line_keeping_tail_and_ending() {
        let mesh = read(Path::new("m.obj"), MIXED.to_vec()).unwrap();
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
        let mesh = read(Path::new("m.obj"), MIXED.to_vec()).unwrap();
        let mut moved = mesh.positions.clone();
        moved[2].x = -3.5;
        let out = faithful(MIXED, &moved);
        let expected = String::from_utf8_lossy(MIXED).replace("v 0 \\\r\n 1 0\r\n", "v -3.5 1 0\r\n");
        assert_eq!(String::from_utf8(out).unwrap(), expected);
        let reread = read(Path::new("m.obj"), expected.into_bytes()).unwrap();
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
        let back = read(Path::new("m.obj"), text.into_bytes()).unwrap();
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
        let back = read(Path::new("m.obj"), out).unwrap();
        for (a, b) in back.positions.iter().zip(&positions) {
            assert!(same_bits(*a, *b), "{a} vs {b}");
        }
    }
}
