//! Checks of a PLY header made before `ply-rs-bw` parses the file.
//!
//! `ply-rs-bw` keeps elements and properties in maps, so a repeated `element` or `property`
//! line silently replaces the earlier one (and every value after it is misread), and it reads
//! as many entries as a header declares, which for an element without properties costs no byte
//! of a binary file. So the header's `element` and `property` lines are checked here first:
//! no name twice, no element of entries without properties, and every count within
//! [`crate::limits`] (`vertex` ≤ `MAX_VERTICES`, `face` ≤ `MAX_FACES`, any other element ≤
//! `MAX_PLY_ENTRIES`). Lines this check does not understand are left to the parser, which
//! rejects them.

use std::collections::HashSet;

use super::error::PlyHeaderError;
use crate::mesh::Limited;

/// The element being declared.
struct Element {
    name: String,
    count: u64,
    /// The header line of its `element` line.
    line: usize,
    properties: HashSet<String>,
}

/// Checks the header at the start of `bytes`; `Err` with the 1-based header line at fault.
pub(crate) fn check(bytes: &[u8]) -> Result<(), (usize, PlyHeaderError)> {
    let mut names = HashSet::new();
    let mut current: Option<Element> = None;
    for (index, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let number = index + 1;
        let mut words = line.split(|b| b.is_ascii_whitespace()).filter(|w| !w.is_empty());
        match words.next() {
            Some(b"end_header") => break,
            Some(b"element") => {
                if let Some(done) = current.take() {
                    finish(done)?;
                }
                let name = String::from_utf8_lossy(words.next().unwrap_or_default()).into_owned();
                let count = words.next().and_then(|w| std::str::from_utf8(w).ok()?.parse().ok()).unwrap_or(0);
                if !names.insert(name.clone()) {
                    return Err((number, PlyHeaderError::DuplicateElement { element: name }));
                }
                let limited = match name.as_str() {
                    "vertex" => Limited::Vertices,
                    "face" => Limited::Faces,
                    _ => Limited::PlyEntries,
                };
                if let Err(limit) = limited.check(count) {
                    return Err((number, PlyHeaderError::Limit { element: name, limit }));
                }
                current = Some(Element { name, count, line: number, properties: HashSet::new() });
            }
            Some(b"property") => {
                let Some(element) = current.as_mut() else { continue };
                let mut words: Vec<&[u8]> = words.collect();
                let Some(name) = words.pop() else { continue };
                let name = String::from_utf8_lossy(name).into_owned();
                if !element.properties.insert(name.clone()) {
                    let element = element.name.clone();
                    return Err((number, PlyHeaderError::DuplicateProperty { element, property: name }));
                }
            }
            _ => {}
        }
    }
    current.map_or(Ok(()), finish)
}

/// The checks of an element that need all its properties.
fn finish(element: Element) -> Result<(), (usize, PlyHeaderError)> {
    if element.count > 0 && element.properties.is_empty() {
        let problem = PlyHeaderError::NoProperties { element: element.name, count: element.count };
        return Err((element.line, problem));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn problem(header: &str) -> (usize, String) {
        let (line, problem) = check(header.as_bytes()).unwrap_err();
        (line, problem.to_string())
    }

    const XYZ: &str = "property float x\nproperty float y\nproperty float z\n";

    #[test]
    fn a_plain_header_passes() {
        let header = format!(
            "ply\nformat ascii 1.0\nelement vertex 3\n{XYZ}element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        );
        assert_eq!(check(header.as_bytes()), Ok(()));
    }

    #[test]
    fn a_repeated_property_names_itself() {
        let header = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty double x\nend_header\n";
        assert_eq!(problem(header), (6, "element \"vertex\" declares property \"x\" twice".into()));
    }

    #[test]
    fn a_repeated_element_names_itself() {
        let header = format!("ply\nformat ascii 1.0\nelement vertex 1\n{XYZ}element vertex 2\n{XYZ}end_header\n");
        assert_eq!(problem(&header), (7, "element \"vertex\" is declared twice".into()));
    }

    #[test]
    fn counts_over_the_limits_name_the_limit() {
        let header =
            format!("ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n{XYZ}end_header\n");
        assert_eq!(
            problem(&header),
            (
                3,
                "element \"vertex\": 18446744073709551615 vertices, over the limit of 33554432 (limits::MAX_VERTICES)"
                    .into()
            )
        );
        let header =
            "ply\nformat ascii 1.0\nelement face 67108865\nproperty list uchar int vertex_indices\nend_header\n";
        assert_eq!(
            problem(header),
            (3, "element \"face\": 67108865 faces, over the limit of 67108864 (limits::MAX_FACES)".into())
        );
        let header = "ply\nformat ascii 1.0\nelement extra 99999999999\nproperty uchar a\nend_header\n";
        assert_eq!(
            problem(header),
            (3, "element \"extra\": 99999999999 entries, over the limit of 67108864 (limits::MAX_PLY_ENTRIES)".into())
        );
    }

    #[test]
    fn entries_without_properties_are_refused_at_their_element_line() {
        let header =
            format!("ply\nformat binary_little_endian 1.0\nelement vertex 1\n{XYZ}element nothing 1000\nend_header\n");
        assert_eq!(problem(&header), (7, "element \"nothing\" has 1000 entries but no property".into()));
        let header = format!("ply\nformat ascii 1.0\nelement nothing 0\nelement vertex 1\n{XYZ}end_header\n");
        assert_eq!(check(header.as_bytes()), Ok(()));
    }

    #[test]
    fn data_after_end_header_is_not_read() {
        let header = format!("ply\nformat ascii 1.0\nelement vertex 1\n{XYZ}end_header\nelement vertex 3\n");
        assert_eq!(check(header.as_bytes()), Ok(()));
    }
}
