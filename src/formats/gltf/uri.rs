//! The files a `.gltf` may read: relative URIs that resolve, symbolic links followed, to a
//! regular file inside the folder of the `.gltf` file.
//!
//! A URI with a scheme (`http:`, `file:`, `C:`, …), an absolute path, a NUL byte, a
//! malformed percent escape, or a path that leaves the folder (`..`, or a link leading out)
//! is refused before anything is opened; so are FIFOs, devices and folders. The file is read
//! through a bounded read of at most the buffer's `byteLength` bytes.

use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The first `length` bytes of the file that the relative URI `uri` names in `folder` (all
/// of them when shorter).
///
/// # Errors
///
/// A one-line reason naming `uri`.
pub(super) fn read_relative(folder: &Path, uri: &str, length: usize) -> Result<Vec<u8>, String> {
    let path = resolve(folder, uri)?;
    let cannot = |e: std::io::Error| format!("cannot read uri {uri:?}: {e}");
    let file = File::open(&path).map_err(cannot)?;
    let meta = file.metadata().map_err(cannot)?;
    if !meta.is_file() {
        return Err(format!("uri {uri:?} does not name a regular file"));
    }
    let mut data = Vec::new();
    let reserve = usize::try_from(meta.len()).unwrap_or(usize::MAX).min(length);
    data.try_reserve_exact(reserve)
        .map_err(|_| format!("uri {uri:?}: {reserve} bytes do not fit in the memory left"))?;
    file.take(length as u64).read_to_end(&mut data).map_err(cannot)?;
    Ok(data)
}

/// The canonical path of the regular file `uri` names in `folder`, checked to lie inside the
/// canonical `folder`.
fn resolve(folder: &Path, uri: &str) -> Result<PathBuf, String> {
    if let Some(scheme) = scheme(uri) {
        return Err(format!(
            "uri {uri:?} has the scheme {scheme:?}; only data URIs and relative paths inside the file's folder are read"
        ));
    }
    let relative = percent_decode(uri).map_err(|reason| format!("uri {uri:?}: {reason}"))?;
    if relative.contains('\0') {
        return Err(format!("uri {uri:?} contains a NUL byte"));
    }
    if relative.starts_with('/') || relative.starts_with('\\') || Path::new(&relative).has_root() {
        return Err(format!("uri {uri:?} is an absolute path; only paths relative to the file's folder are read"));
    }
    let cannot = |e: std::io::Error| format!("cannot read uri {uri:?}: {e}");
    let base = if folder.as_os_str().is_empty() { Path::new(".") } else { folder };
    let base = base.canonicalize().map_err(cannot)?;
    let path = base.join(&relative).canonicalize().map_err(cannot)?;
    if !path.starts_with(&base) {
        return Err(format!("uri {uri:?} leads outside the folder of the glTF file"));
    }
    let meta = path.metadata().map_err(cannot)?;
    if !meta.is_file() {
        return Err(format!("uri {uri:?} does not name a regular file"));
    }
    Ok(path)
}

/// The scheme of `uri` (`http`, `file`, a drive letter…) if it has one: letters, digits,
/// `+`, `-` or `.` after a first letter, then a colon.
fn scheme(uri: &str) -> Option<&str> {
    let (head, _) = uri.split_once(':')?;
    let mut chars = head.chars();
    let first = chars.next()?;
    (first.is_ascii_alphabetic() && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))).then_some(head)
}

/// `uri` with its `%XX` escapes decoded, as UTF-8.
fn percent_decode(uri: &str) -> Result<String, String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes.get(i + 1..i + 3).and_then(|h| std::str::from_utf8(h).ok());
            let value = hex.and_then(|h| u8::from_str_radix(h, 16).ok()).ok_or("a malformed percent escape")?;
            out.push(value);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "percent escapes that do not decode to UTF-8".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schemes_are_found_and_relative_paths_have_none() {
        assert_eq!(scheme("http://x/y.bin"), Some("http"));
        assert_eq!(scheme("file:///etc/passwd"), Some("file"));
        assert_eq!(scheme("C:\\a.bin"), Some("C"));
        assert_eq!(scheme("a b.bin"), None);
        assert_eq!(scheme("sub/x:y.bin"), None);
        assert_eq!(scheme(":x"), None);
    }

    #[test]
    fn percent_escapes_decode_and_bad_ones_are_errors() {
        assert_eq!(percent_decode("a%20b%2Fc.bin").unwrap(), "a b/c.bin");
        assert_eq!(percent_decode("%2e%2e/x").unwrap(), "../x");
        assert_eq!(percent_decode("%4").unwrap_err(), "a malformed percent escape");
        assert_eq!(percent_decode("%zz").unwrap_err(), "a malformed percent escape");
        assert_eq!(percent_decode("%ff").unwrap_err(), "percent escapes that do not decode to UTF-8");
    }
}
