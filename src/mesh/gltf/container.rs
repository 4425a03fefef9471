//! Writing a glTF document with its buffers embedded: `.gltf` (JSON, every buffer a base64
//! data URI) or `.glb` (binary container: JSON chunk, then buffer 0 as the BIN chunk; other
//! buffers as data URIs).

use std::io::{self, Write};

use serde_json::Value;

use super::buffers::data_uri;

/// GLB chunk type of the JSON chunk (`JSON`, little-endian).
const JSON_CHUNK: u32 = 0x4E4F_534A;
/// GLB chunk type of the binary chunk (`BIN\0`, little-endian).
const BIN_CHUNK: u32 = 0x004E_4942;

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
    }
}
