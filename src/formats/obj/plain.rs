//! The OBJ reader's fast path for the lines almost all of a large file is made of: a plain
//! `v x y z` or `f a b c …` on one physical line, its words separated by spaces or tabs.
//!
//! Each function here accepts only lines that the statement reader of [`super::read`] reads
//! without fault, and gives what it would give; for any other line (another keyword, leading
//! whitespace, a comment, a w or colour after the position, negative or signed indices, other
//! whitespace, a non-finite number, a fault of any kind) it declines, and the line goes to the
//! statement reader, which names the fault as before. Continued lines (`\` at the end) never
//! come here.

use super::float;

/// Whether `b` separates the words of a plain line.
fn blank(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// The position of `line` (one physical line without its ending) when it is `v`, then three
/// finite numbers (as `str::parse::<f64>` reads them), then nothing but spaces or tabs.
pub(crate) fn vertex(line: &[u8]) -> Option<[f64; 3]> {
    let rest = line.strip_prefix(b"v")?;
    if !rest.first().is_some_and(|&b| blank(b)) {
        return None;
    }
    let mut at = 0;
    let mut xyz = [0.0; 3];
    for c in &mut xyz {
        while rest.get(at).is_some_and(|&b| blank(b)) {
            at += 1;
        }
        let start = at;
        while rest.get(at).is_some_and(|&b| !blank(b)) {
            at += 1;
        }
        *c = float::parse(&rest[start..at]).filter(|c| c.is_finite())?;
    }
    rest[at..].iter().all(|&b| blank(b)).then_some(xyz)
}

/// The indices of `line` (one physical line without its ending) into `indices` when it is
/// `f`, then words each of unsigned decimal digits (at most 18) optionally followed by `/` and
/// more text without whitespace or `#` (the texture and normal indices, which the reader does
/// not use). Returns whether the line is such; `indices` is then the words' indices as
/// written (not yet checked: 0 or past the last vertex are faults the caller reports).
pub(crate) fn face(line: &[u8], indices: &mut Vec<i64>) -> bool {
    indices.clear();
    let Some(rest) = line.strip_prefix(b"f") else { return false };
    if !rest.first().is_some_and(|&b| blank(b)) {
        return false;
    }
    let mut at = 0;
    loop {
        while rest.get(at).is_some_and(|&b| blank(b)) {
            at += 1;
        }
        if at == rest.len() {
            return true;
        }
        let start = at;
        let mut index: i64 = 0;
        while let Some(&b) = rest.get(at).filter(|b| b.is_ascii_digit()) {
            index = index * 10 + i64::from(b - b'0');
            at += 1;
        }
        if at == start || at - start > 18 {
            return false;
        }
        if rest.get(at) == Some(&b'/') {
            while let Some(&b) = rest.get(at).filter(|&&b| !blank(b)) {
                if b.is_ascii_whitespace() || b == b'#' {
                    return false;
                }
                at += 1;
            }
        } else if rest.get(at).is_some_and(|&b| !blank(b)) {
            return false;
        }
        indices.push(index);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_vertices_are_read() {
        assert_eq!(vertex(b"v 1 2 3"), Some([1.0, 2.0, 3.0]));
        assert_eq!(vertex(b"v\t-0.5  2e-3\t3 \t"), Some([-0.5, 0.002, 3.0]));
        assert_eq!(vertex(b"v 0.1 0.12345678901234567 -0"), Some([0.1, 0.123_456_789_012_345_67, -0.0]));
    }

    #[test]
    fn other_vertex_lines_are_declined() {
        let lines: [&[u8]; 14] = [
            b"v 1 2",
            b"v 1 2 3 1",
            b"v 1 2 3 # c",
            b"v 1 2 3#",
            b"v 1 2 x",
            b"v 1 2 inf",
            b"v 1 2 1e999",
            b" v 1 2 3",
            b"vt 1 2 3",
            b"v1 2 3",
            b"v",
            b"v 1 2\r3",
            b"v 1 2 3\x0c",
            b"v 1 \xff 3",
        ];
        for line in lines {
            assert_eq!(vertex(line), None, "{:?}", String::from_utf8_lossy(line));
        }
    }

    #[test]
    fn plain_faces_are_read() {
        let mut indices = Vec::new();
        assert!(face(b"f 1 2 3", &mut indices));
        assert_eq!(indices, [1, 2, 3]);
        assert!(face(b"f\t10/1 20//3  30/4/5 007 0 ", &mut indices));
        assert_eq!(indices, [10, 20, 30, 7, 0]);
        assert!(!face(b"f", &mut indices));
        assert!(face(b"f 999999999999999999", &mut indices));
        assert_eq!(indices, [999_999_999_999_999_999]);
    }

    #[test]
    fn other_face_lines_are_declined() {
        let lines: [&[u8]; 11] = [
            b"f -1 2 3",
            b"f +1 2 3",
            b"f 1 2 3 # c",
            b"f 1 2/3# 4",
            b"f 1 x 3",
            b"f 1 2a 3",
            b"f 1 /2 3",
            b"fo 1 2 3",
            b" f 1 2 3",
            b"f 1 2\r3",
            b"f 1 2 1000000000000000000",
        ];
        let mut indices = Vec::new();
        for line in lines {
            assert!(!face(line, &mut indices), "{:?}", String::from_utf8_lossy(line));
        }
    }
}
