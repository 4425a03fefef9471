//! The data of a glTF file's buffers: the GLB BIN chunk, base64 data URIs, or files beside it
//! (see [`uri`](super::uri) for which files may be read).

use std::path::Path;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;

use super::{GltfDataError, uri};

/// The data of every buffer of `document`, each cut to its `byteLength`. `blob` is the GLB
/// BIN chunk, if any; relative URIs are resolved against `path`'s folder. No buffer reads
/// more than its `byteLength` from a file.
///
/// # Errors
///
/// [`GltfDataError::Buffer`] for a buffer whose data are missing, shorter than its
/// `byteLength`, or not allowed (a URI other than a data URI or a relative path inside the
/// folder).
pub(super) fn resolve(
    path: &Path,
    document: &::gltf::Document,
    blob: Option<&[u8]>,
) -> Result<Vec<Vec<u8>>, GltfDataError> {
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let error = |reason: String| GltfDataError::Buffer { buffer: buffer.index(), reason };
        let length = buffer.length();
        let mut data = match buffer.source() {
            ::gltf::buffer::Source::Bin => {
                let bin = blob.ok_or_else(|| error("the file has no GLB BIN chunk".to_string()))?;
                bin[..length.min(bin.len())].to_vec()
            }
            ::gltf::buffer::Source::Uri(uri) => match uri.strip_prefix("data:") {
                Some(rest) => decode_data_uri(rest).map_err(error)?,
                None => uri::read_relative(folder, uri, length).map_err(error)?,
            },
        };
        if data.len() < length {
            return Err(error(format!("has {} bytes but its byteLength is {length}", data.len())));
        }
        data.truncate(length);
        buffers.push(data);
    }
    Ok(buffers)
}

/// The bytes of a data URI without its `data:` prefix: `<media type>;base64,<payload>`.
fn decode_data_uri(rest: &str) -> Result<Vec<u8>, String> {
    let Some((header, payload)) = rest.split_once(',') else {
        return Err("malformed data URI (no comma)".to_string());
    };
    if !header.ends_with(";base64") {
        return Err("only base64 data URIs are supported".to_string());
    }
    STANDARD.decode(payload).map_err(|e| format!("bad base64 in data URI: {e}"))
}

/// `data` as a base64 data URI of type `application/octet-stream`.
pub(super) fn data_uri(data: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", STANDARD.encode(data))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_uris_round_trip_and_bad_ones_are_errors() {
        let uri = data_uri(&[1, 2, 3, 250]);
        assert_eq!(decode_data_uri(uri.strip_prefix("data:").unwrap()).unwrap(), [1, 2, 3, 250]);
        assert!(decode_data_uri("text/plain,abc").unwrap_err().contains("only base64"));
        assert!(decode_data_uri("application/octet-stream;base64,@@@").unwrap_err().contains("bad base64"));
        assert!(decode_data_uri("nothing").unwrap_err().contains("no comma"));
    }
}
