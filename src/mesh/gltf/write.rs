//! Writing a glTF file back faithfully: the document as read with only moved vertices'
//! POSITION (and the NORMAL around them) changed.

use std::collections::HashSet;
use std::io::{self, Write};

use glam::DVec3;
use serde_json::{Value, json};

use super::generic::{bounds, first_non_finite};
use super::{Block, GltfFile, Target, container, normals};
use crate::mesh::source::Original;

/// Writes the glTF file `original` with new mesh positions (GLB when `binary`).
///
/// For each POSITION accessor (from the first node instance that uses it), the elements whose
/// mesh position changed (any coordinate differs bit for bit from the positions as read) are
/// mapped back through the inverse of the node's world matrix and stored as f32 in place;
/// the others keep their bytes. The accessor's `min`/`max` are recomputed. A sparse accessor
/// (or one without a buffer view) that moved is made dense: its elements go to a new buffer
/// and buffer view, and `sparse` is removed. Then, for each primitive with a dense float
/// NORMAL, the vertices of triangles that touch a moved vertex get the area-weighted normal of
/// the primitive's triangles at the new positions ([`normals`]). With no vertex moved the
/// document and buffers are written as read (JSON re-serialized, buffers embedded).
///
/// # Errors
///
/// `InvalidData` when a node's world matrix is not invertible or a position does not fit in
/// f32; any error of `out`.
pub(crate) fn write_faithful(
    out: &mut impl Write,
    original: &Original<GltfFile>,
    positions: &[DVec3],
    binary: bool,
) -> io::Result<()> {
    let file = &original.file;
    let mut json = file.json.clone();
    let mut buffers = file.buffers.clone();
    let mut written = HashSet::new();
    let mut moved = vec![false; positions.len()];
    let mut new_local: Vec<Option<Vec<[f32; 3]>>> = Vec::with_capacity(file.blocks.len());
    for block in &file.blocks {
        let range = block.first..block.first + block.local.len();
        let old = original.positions.get(range.clone()).unwrap_or_default();
        let new = positions.get(range.clone()).unwrap_or_default();
        let any = old.iter().zip(new).any(|(a, b)| !same_bits(*a, *b));
        if !written.insert(block.accessor) || !any {
            new_local.push(None);
            continue;
        }
        let local = to_local(block, old, new, &mut moved[range])?;
        match block.target {
            Some(target) => store(&mut buffers, target, &local, &moved[block.first..])?,
            None => make_dense(&mut json, &mut buffers, block.accessor, &local),
        }
        let (min, max) = bounds(&local);
        if let Some(accessor) = json.pointer_mut(&format!("/accessors/{}", block.accessor)) {
            accessor["min"] = min;
            accessor["max"] = max;
        }
        new_local.push(Some(local));
    }
    for primitive in &file.primitives {
        let (Some((count, target)), Some(Some(local))) = (primitive.normal, new_local.get(primitive.block)) else {
            continue;
        };
        let first = file.blocks[primitive.block].first;
        let triangles: Vec<[u32; 3]> = primitive
            .faces
            .clone()
            .map(|f| {
                let face = original.faces.face(f);
                [0, 1, 2].map(|k| face.get(k).map_or(0, |&v| (v as usize - first) as u32))
            })
            .collect();
        let mut dirty = vec![false; count.min(local.len())];
        for t in &triangles {
            if t.iter().any(|&v| moved.get(first + v as usize) == Some(&true)) {
                for &v in t {
                    if let Some(d) = dirty.get_mut(v as usize) {
                        *d = true;
                    }
                }
            }
        }
        let sums = normals::sums(|v| DVec3::from_array(local[v as usize].map(f64::from)), dirty.len(), &triangles);
        let unit: Vec<[f32; 3]> = sums.into_iter().map(|s| normals::unit(s).unwrap_or([0.0; 3])).collect();
        if let Some((element, value)) = first_non_finite(&unit) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("vertex {}: its normal has the non-finite component {value}", first + element),
            ));
        }
        let keep: Vec<bool> = dirty.iter().zip(&unit).map(|(&d, n)| d && *n != [0.0; 3]).collect();
        store(&mut buffers, target, &unit, &keep)?;
    }
    container::write(out, json, &buffers, binary)
}

/// Whether two positions are equal bit for bit.
fn same_bits(a: DVec3, b: DVec3) -> bool {
    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)
}

/// The block's elements in local space: moved ones (flagged in `moved`) through the inverse
/// world matrix, the others as read.
fn to_local(block: &Block, old: &[DVec3], new: &[DVec3], moved: &mut [bool]) -> io::Result<Vec<[f32; 3]>> {
    let invalid = |message: String| io::Error::new(io::ErrorKind::InvalidData, message);
    let inverse = block.transform.inverse();
    if block.transform.determinant() == 0.0 || !inverse.is_finite() {
        return Err(invalid(format!(
            "the node transform of POSITION accessor {} is not invertible; cannot write positions back",
            block.accessor
        )));
    }
    let mut local = block.local.clone();
    for (i, ((a, b), flag)) in old.iter().zip(new).zip(moved.iter_mut()).enumerate() {
        if same_bits(*a, *b) {
            continue;
        }
        *flag = true;
        let exact = inverse.transform_point3(*b);
        let p = exact.as_vec3();
        if let Some(value) = exact.to_array().into_iter().find(|c| !(*c as f32).is_finite()) {
            return Err(invalid(format!(
                "vertex {}: its node-local coordinate {value:?} does not fit in f32",
                block.first + i
            )));
        }
        local[i] = p.to_array();
    }
    Ok(local)
}

/// Stores `values[i]` as element `i` of the dense accessor at `target`, for every `i` with
/// `keep[i]`.
fn store(buffers: &mut [Vec<u8>], target: Target, values: &[[f32; 3]], keep: &[bool]) -> io::Result<()> {
    let short = || io::Error::new(io::ErrorKind::InvalidData, format!("buffer {} is too short", target.buffer));
    let data = buffers.get_mut(target.buffer).ok_or_else(short)?;
    for (i, (value, _)) in values.iter().zip(keep).enumerate().filter(|(_, (_, k))| **k) {
        let at = target.offset + i * target.stride;
        let bytes = data.get_mut(at..at + 12).ok_or_else(short)?;
        bytes.copy_from_slice(bytemuck::cast_slice(value));
    }
    Ok(())
}

/// Points `accessor` at a new buffer (and buffer view) holding `values`, and drops its
/// `sparse` substitution.
fn make_dense(json: &mut Value, buffers: &mut Vec<Vec<u8>>, accessor: usize, values: &[[f32; 3]]) {
    let data: Vec<u8> = bytemuck::cast_slice(values).to_vec();
    let length = data.len();
    let buffer = buffers.len();
    buffers.push(data);
    let array = |json: &mut Value, key: &str| -> usize {
        if !json[key].is_array() {
            json[key] = json!([]);
        }
        json[key].as_array().map_or(0, Vec::len)
    };
    array(json, "buffers");
    if let Some(list) = json["buffers"].as_array_mut() {
        list.resize(buffer, json!({"byteLength": 0}));
        list.push(json!({"byteLength": length}));
    }
    let view = array(json, "bufferViews");
    if let Some(list) = json["bufferViews"].as_array_mut() {
        list.push(json!({"buffer": buffer, "byteLength": length}));
    }
    if let Some(object) = json.pointer_mut(&format!("/accessors/{accessor}")).and_then(Value::as_object_mut) {
        object.insert("bufferView".into(), view.into());
        object.insert("byteOffset".into(), 0.into());
        object.remove("sparse");
    }
}
