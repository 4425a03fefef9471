//! Writing a PLY file read straight from its bytes ([`super::direct`]) with new positions:
//! the bytes are copied and only the moved vertices' coordinates are patched.

use std::io::{self, Write};
use std::ops::Range;

use glam::DVec3;

use super::direct::{Layout, PlyBytes, Scalar};
use crate::formats::decimal::push_display;

/// Whether two positions are equal bit for bit.
fn same_bits(a: DVec3, b: DVec3) -> bool {
    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)
}

/// Writes `file` with the coordinates of the vertices whose position changed (any coordinate
/// differs bit for bit from `original`) replaced, each in its declared type: in a binary file
/// the bytes of `x`, `y` and `z` are overwritten (f32 for `float`, f64 for `double`); in an
/// ASCII file the three numbers are rewritten in shortest round-trip digits of their type
/// (`format!("{}")`), the rest of the line kept. Every other byte is copied, so with unchanged
/// positions the output is the input.
pub(crate) fn write_faithful(
    out: &mut impl Write,
    file: &PlyBytes,
    original: &[DVec3],
    positions: &[DVec3],
) -> io::Result<()> {
    let moved = |i: usize| matches!((original.get(i), positions.get(i)), (Some(a), Some(b)) if !same_bits(*a, *b));
    let bytes = &file.bytes[..];
    match &file.layout {
        Layout::Binary { big_endian, start, stride, offsets } => {
            let count = original.len().min(positions.len());
            let end = start + count * stride;
            out.write_all(&bytes[..*start])?;
            let mut block = Vec::new();
            for first in (0..count).step_by(BLOCK) {
                let vertices = first..(first + BLOCK).min(count);
                let span = start + vertices.start * stride..start + vertices.end * stride;
                if !vertices.clone().any(moved) {
                    out.write_all(&bytes[span])?;
                    continue;
                }
                block.clear();
                block.extend_from_slice(&bytes[span.clone()]);
                for i in vertices.filter(|&i| moved(i)) {
                    let record = (i - first) * stride;
                    let p = positions[i].to_array();
                    for (k, (offset, (_, t))) in offsets.iter().zip(file.xyz).enumerate() {
                        patch(&mut block[record + offset..], p[k], t, *big_endian);
                    }
                }
                out.write_all(&block)?;
            }
            out.write_all(&bytes[end..])?;
        }
        Layout::Ascii { lines } => {
            let mut copied = 0;
            let mut line = Vec::new();
            for (i, &start) in lines.iter().enumerate().filter(|&(i, _)| moved(i)) {
                let end = memchr::memchr(b'\n', &bytes[start..]).map_or(bytes.len(), |n| start + n + 1);
                out.write_all(&bytes[copied..start])?;
                line.clear();
                rewrite_line(&mut line, &bytes[start..end], positions[i], file.xyz);
                out.write_all(&line)?;
                copied = end;
            }
            out.write_all(&bytes[copied..])?;
        }
    }
    out.flush()
}

/// Vertices per block of a binary faithful write.
const BLOCK: usize = 1 << 16;

/// Overwrites the first bytes of `at` with `value` in type `t` (float or double).
fn patch(at: &mut [u8], value: f64, t: Scalar, big_endian: bool) {
    match (t, big_endian) {
        (Scalar::Float, false) => at[..4].copy_from_slice(&(value as f32).to_le_bytes()),
        (Scalar::Float, true) => at[..4].copy_from_slice(&(value as f32).to_be_bytes()),
        (_, false) => at[..8].copy_from_slice(&value.to_le_bytes()),
        (_, true) => at[..8].copy_from_slice(&value.to_be_bytes()),
    }
}

/// Appends the ASCII vertex `line` with its numbers at the places of `xyz` replaced by `p`.
fn rewrite_line(out: &mut Vec<u8>, line: &[u8], p: DVec3, xyz: [(usize, Scalar); 3]) {
    let mut copied = 0;
    let p = p.to_array();
    for (place, word) in words(line).enumerate() {
        if let Some(k) = xyz.iter().position(|&(c, _)| c == place) {
            out.extend_from_slice(&line[copied..word.start]);
            match xyz[k].1 {
                Scalar::Float => push_display(out, p[k] as f32),
                _ => push_display(out, p[k]),
            }
            copied = word.end;
        }
    }
    out.extend_from_slice(&line[copied..]);
}

/// The byte ranges of the numbers of an ASCII data line.
fn words(line: &[u8]) -> impl Iterator<Item = Range<usize>> + '_ {
    let separator = |b: &u8| matches!(b, b' ' | b'\t' | b'\r' | b'\n');
    let mut pos = 0;
    std::iter::from_fn(move || {
        let start = pos + line[pos..].iter().position(|b| !separator(b))?;
        let len = line[start..].iter().position(separator).unwrap_or(line.len() - start);
        pos = start + len;
        Some(start..pos)
    })
}
