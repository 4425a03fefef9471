//! The texture coordinates of an OBJ file's face corners (`vt u v` lines, and the `v/vt` of
//! each `f` corner), for writers that carry them into formats with per-vertex texture
//! coordinates (the glTF animation export). The mesh reader keeps positions and faces only; this
//! reads the same file's faces again for their `vt` references, and gives up (`None`) wherever
//! they do not line up with the mesh's faces corner for corner.

use crate::mesh::Faces;

/// Texture coordinates per face corner: `coords[corners[i]]` is corner i's (u, v), corners in
/// the order of the mesh's faces.
#[derive(Clone, Debug, PartialEq)]
pub struct CornerTexcoords {
    /// The file's `vt` coordinates (u, v), in file order.
    pub coords: Vec<[f32; 2]>,
    /// Per face corner, the index of its coordinates in `coords`.
    pub corners: Vec<u32>,
}

/// The texture coordinates of `bytes`' face corners, where every face corner has one and the
/// file's faces are `faces` corner for corner (the reader dropped none); `None` otherwise, or
/// where the file has no `vt`. Lines continued with `\` are not followed (such a file gets
/// `None` where the faces then differ).
pub fn corner_texcoords(bytes: &[u8], faces: &Faces) -> Option<CornerTexcoords> {
    let text = std::str::from_utf8(bytes).ok()?;
    let mut coords: Vec<[f32; 2]> = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    let mut face = 0;
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vt") => {
                let u: f32 = words.next()?.parse().ok()?;
                let v: f32 = words.next().map_or(Some(0.0), |w| w.parse().ok())?;
                coords.push([u, v]);
            }
            Some("f") => {
                if face >= faces.len() {
                    return None;
                }
                let expected = faces.face(face);
                let mut count = 0;
                for word in words {
                    let vt = word.split('/').nth(1).filter(|vt| !vt.is_empty())?;
                    let vt: i64 = vt.parse().ok()?;
                    let index = if vt < 0 { coords.len() as i64 + vt } else { vt - 1 };
                    corners.push(u32::try_from(index).ok().filter(|&i| (i as usize) < coords.len())?);
                    count += 1;
                }
                if count != expected.len() {
                    return None;
                }
                face += 1;
            }
            _ => {}
        }
    }
    (face == faces.len() && !coords.is_empty()).then_some(CornerTexcoords { coords, corners })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn faces(list: &[&[u32]]) -> Faces {
        let mut faces = Faces::new();
        for face in list {
            faces.push(face);
        }
        faces
    }

    #[test]
    fn corners_take_their_vt_relative_or_absolute() {
        let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 3/-1/1 2/-2/1 1/-3/1\n";
        let read = corner_texcoords(text, &faces(&[&[0, 1, 2], &[2, 1, 0]])).unwrap();
        assert_eq!(read.coords, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(read.corners, vec![0, 1, 2, 2, 1, 0]);
    }

    #[test]
    fn a_corner_without_vt_or_faces_that_differ_give_none() {
        let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3/1\n";
        assert_eq!(corner_texcoords(text, &faces(&[&[0, 1, 2]])), None, "corner 2 has no vt");
        let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n";
        assert_eq!(corner_texcoords(text, &faces(&[&[0, 1, 2], &[0, 2, 1]])), None, "a face fewer");
        assert_eq!(corner_texcoords(text, &faces(&[&[0, 1, 2, 0]])), None, "another corner count");
        assert_eq!(corner_texcoords(b"v 0 0 0\nf 1 1 1\n", &faces(&[&[0, 0, 0]])), None, "no vt");
        assert_eq!(corner_texcoords(b"vt 0 0\nf 1/7 1/1 1/1\n", &faces(&[&[0, 0, 0]])), None, "vt out of range");
    }
}
