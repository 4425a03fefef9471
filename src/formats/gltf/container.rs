//! The GLB container, read and written, and writing a glTF document with its buffers
//! embedded: `.gltf` (JSON, every buffer a base64 data URI) or `.glb` (binary container: JSON
//! chunk, then buffer 0 as the BIN chunk; other buffers as data URIs).

use std::io::{self, Write};

use serde_json::Value;

use super::buffers::data_uri;

/// GLB chunk type of the JSON chunk (`JSON`, little-endian).
const JSON_CHUNK: u32 = 0x4E4F_534A;
/// GLB chunk type of the binary chunk (`BIN\0`, little-endian).
const BIN_CHUNK: u32 = 0x004E_4942;

/// The JSON chunk and the BIN chunk (if any) of the GLB file `bytes`: a 12-byte header
/// (`glTF`, version 2, total length), then chunks of (length, type, data), the JSON chunk
/// first. Chunks of other types are skipped. Every length is checked against the bytes
/// present before it is used.
///
/// # Errors
///
/// A one-line reason: bad magic or version, a length past the end of the file, no JSON chunk.
pub(super) fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), String> {
    let word = |at: usize| bytes.get(at..at + 4).map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]) as usize);
    if bytes.get(..4) != Some(b"glTF") {
        return Err("not a GLB file (no glTF magic)".to_string());
    }
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err(format!("the GLB header needs 12 bytes but the file has {}", bytes.len()));
    };
    if version != 2 {
        return Err(format!("GLB version {version} is not supported (only 2 is)"));
    }
    if length < 12 || length > bytes.len() {
        return Err(format!("the GLB header gives a length of {length} bytes but the file has {}", bytes.len()));
    }
    let bytes = &bytes[..length];
    let mut at = 12;
    let mut chunks = Vec::new();
    while at < length {
        let (Some(size), Some(kind)) = (word(at), word(at + 4)) else {
            return Err(format!("a GLB chunk header at byte {at} is cut short by the end of the file"));
        };
        let data = (at + 8).checked_add(size).and_then(|end| bytes.get(at + 8..end));
        let Some(data) = data else {
            return Err(format!("the GLB chunk at byte {at} claims {size} bytes, past the end of the file"));
        };
        chunks.push((kind as u32, data));
        at = (at + 8 + size).next_multiple_of(4);
    }
    match chunks.first() {
        Some(&(JSON_CHUNK, json)) => {
            Ok((json, chunks.iter().skip(1).find(|(kind, _)| *kind == BIN_CHUNK).map(|&(_, data)| data)))
        }
        _ => Err("the first GLB chunk is not a JSON chunk".to_string()),
    }
}

/// Writes `json` with `buffers` (one per entry of its `buffers` array, whose `byteLength` and
/// `uri` are set here) as `.glb` when `binary`, as `.gltf` otherwise.
pub(super) fn write(out: &mut impl Write, mut json: Value, buffers: &[Vec<u8>], binary: bool) -> io::Result<()> {
    let mut bin = None;
    if let Some(list) = json.get_mut("buffers").and_then(Value::as_array_mut) {
        for (i, buffer) in list.iter_mut().enumerate() {
            let (Some(object), Some(data)) = (buffer.as_object_mut(), buffers.get(i)) else { continue };
            object.insert("byteLength".into(), data.len().into());
            if binary && i == 0 {
                object.remove("uri");
                bin = Some(data.as_slice());
            } else {
                object.insert("uri".into(), data_uri(data).into());
            }
        }
    }
    let text = serde_json::to_vec(&json).map_err(io::Error::other)?;
    if binary {
        write_glb(out, text, bin)?;
    } else {
        out.write_all(&text)?;
    }
    out.flush()
}

/// The GLB container: 12-byte header, the JSON chunk padded with spaces, the BIN chunk padded
/// with zeros (each chunk a multiple of 4 bytes).
fn write_glb(out: &mut impl Write, mut json: Vec<u8>, bin: Option<&[u8]>) -> io::Result<()> {
    json.resize(json.len().next_multiple_of(4), b' ');
    let bin_length = bin.map(|b| b.len().next_multiple_of(4));
    let total = 12 + 8 + json.len() + bin_length.map_or(0, |n| 8 + n);
    let too_large = || io::Error::new(io::ErrorKind::InvalidInput, "a GLB file cannot exceed 4 GiB");
    let total = u32::try_from(total).map_err(|_| too_large())?;
    out.write_all(b"glTF")?;
    out.write_all(&2u32.to_le_bytes())?;
    out.write_all(&total.to_le_bytes())?;
    out.write_all(&(json.len() as u32).to_le_bytes())?;
    out.write_all(&JSON_CHUNK.to_le_bytes())?;
    out.write_all(&json)?;
    if let (Some(bin), Some(length)) = (bin, bin_length) {
        out.write_all(&(length as u32).to_le_bytes())?;
        out.write_all(&BIN_CHUNK.to_le_bytes())?;
        out.write_all(bin)?;
        out.write_all(&vec![0; length - bin.len()])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glb_chunks_are_aligned_and_parse_back() {
        let json = serde_json::json!({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 1, "uri": "x.bin"}]});
        let mut out = Vec::new();
        write(&mut out, json, &[vec![1, 2, 3, 4, 5]], true).unwrap();
        assert_eq!(out.len() % 4, 0);
        let glb = ::gltf::binary::Glb::from_slice(&out).unwrap();
        assert_eq!(glb.bin.as_deref(), Some(&[1, 2, 3, 4, 5, 0, 0, 0][..]));
        let back: Value = serde_json::from_slice(&glb.json).unwrap();
        assert_eq!(back["buffers"][0], serde_json::json!({"byteLength": 5}));
        let (json, bin) = split_glb(&out).unwrap();
        assert_eq!((json, bin), (&glb.json[..], Some(&[1, 2, 3, 4, 5, 0, 0, 0][..])));
    }

    #[test]
    fn glb_lengths_past_the_end_are_errors() {
        assert_eq!(split_glb(b"glTF\x02\0\0\0").unwrap_err(), "the GLB header needs 12 bytes but the file has 8");
        assert_eq!(
            split_glb(b"glTF\x02\0\0\0garbage").unwrap_err(),
            "the GLB header gives a length of 1651663207 bytes but the file has 15"
        );
        assert_eq!(split_glb(b"glTF\x01\0\0\0\x0c\0\0\0").unwrap_err(), "GLB version 1 is not supported (only 2 is)");
        let mut glb = b"glTF\x02\0\0\0\x18\0\0\0\xff\xff\xff\xffJSON{}  ".to_vec();
        assert_eq!(
            split_glb(&glb).unwrap_err(),
            "the GLB chunk at byte 12 claims 4294967295 bytes, past the end of the file"
        );
        glb[12..16].copy_from_slice(&4u32.to_le_bytes());
        assert_eq!(split_glb(&glb).unwrap(), (&b"{}  "[..], None));
        glb[16..20].copy_from_slice(b"BIN\0");
        assert_eq!(split_glb(&glb).unwrap_err(), "the first GLB chunk is not a JSON chunk");
        assert_eq!(split_glb(b"glb!").unwrap_err(), "not a GLB file (no glTF magic)");
    }
}
