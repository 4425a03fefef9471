//! Writing a glTF file back faithfully: the document as read with only moved vertices'
//! POSITION (and the NORMAL around them) changed.

use std::collections::{HashMap, HashSet};
use std::io::{self, Write};

use glam::{DMat4, DVec3};
use serde_json::{Value, json};

use super::aliasing::{self, Store};
use super::generic::{bounds, first_non_finite};
use super::{Block, GltfFile, Target, container, normals};
use crate::formats::loaded::Original;

/// Writes the glTF file `original` with new mesh positions (GLB when `binary`).
///
/// For each POSITION accessor, the elements whose mesh position changed in its first node
/// instance (any coordinate differs bit for bit from the positions as read) are mapped back
/// through the inverse of the node's world matrix and stored as f32 in place; the others keep
/// their bytes. Every later instance of the accessor must agree with what is stored
/// ([`check_instances`]): a glTF file cannot hold instances of one accessor deformed apart.
/// The accessor's `min`/`max` are recomputed. A sparse accessor (or one without a buffer
/// view) that moved is made dense: its elements go to a new buffer and buffer view, and
/// `sparse` is removed. Then, for each primitive with a dense float NORMAL, the vertices of
/// triangles that touch a moved vertex get the area-weighted normal of the primitive's
/// triangles at the new positions ([`normals`]). With no vertex moved the document and
/// buffers are written as read (JSON re-serialized, buffers embedded).
///
/// # Errors
///
/// `InvalidData` when a node's world matrix is not invertible, a position does not fit in
/// f32, two instances of one POSITION accessor moved differently, or two of the accessors
/// written share bytes ([`aliasing`]); any error of `out`.
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
    let buffer_lengths: Vec<usize> = buffers.iter().map(Vec::len).collect();
    let mut stores = Vec::new();
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
        let local = to_local(block, old, new, &mut moved[range.clone()])?;
        match block.target {
            Some(target) => {
                store(&mut buffers, target, &local, &moved[block.first..])?;
                let elements = moved[range].iter().enumerate().filter(|(_, m)| **m).map(|(i, _)| i).collect();
                stores.push(Store { accessor: block.accessor, semantic: "POSITION", target, elements });
            }
            None => make_dense(&mut json, &mut buffers, block.accessor, &local),
        }
        let (min, max) = bounds(&local);
        if let Some(accessor) = json.pointer_mut(&format!("/accessors/{}", block.accessor)) {
            accessor["min"] = min;
            accessor["max"] = max;
        }
        new_local.push(Some(local));
    }
    check_instances(file, original, positions, &new_local)?;
    for primitive in &file.primitives {
        let (Some((accessor, count, target)), Some(Some(local))) = (primitive.normal, new_local.get(primitive.block))
        else {
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
        let elements = keep.iter().enumerate().filter(|(_, k)| **k).map(|(i, _)| i).collect();
        stores.push(Store { accessor, semantic: "NORMAL", target, elements });
    }
    aliasing::check(&buffer_lengths, &stores)?;
    container::write(out, json, &buffers, binary)
}

/// Whether two positions are equal bit for bit.
fn same_bits(a: DVec3, b: DVec3) -> bool {
    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)
}

/// The inverse of the block's world matrix.
fn inverse(block: &Block) -> io::Result<DMat4> {
    let inverse = block.transform.inverse();
    if block.transform.determinant() == 0.0 || !inverse.is_finite() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "the node transform of POSITION accessor {} is not invertible; cannot write positions back",
                block.accessor
            ),
        ));
    }
    Ok(inverse)
}

/// The block's elements in local space: moved ones (flagged in `moved`) through the inverse
/// world matrix, the others as read.
fn to_local(block: &Block, old: &[DVec3], new: &[DVec3], moved: &mut [bool]) -> io::Result<Vec<[f32; 3]>> {
    let invalid = |message: String| io::Error::new(io::ErrorKind::InvalidData, message);
    let inverse = inverse(block)?;
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

/// Refuses to write when a POSITION accessor drawn by several instances (blocks) cannot serve
/// them all: the accessor is stored once, from its first instance (`new_local`, or the
/// elements as read when that instance did not move), and each later instance `b` reads it
/// back through its own world matrix `M_b`.
///
/// Element `i` of a later instance is in local space `q = M_b⁻¹·p_i` (its new mesh position
/// `p_i`; an unmoved element is exactly its value as read), and each coordinate `k` must lie
/// within
///
/// `ε₃₂·|w_k| + f32::MIN_POSITIVE + 64·ε₆₄·(|M_a⁻¹|·|p_a| + |M_b⁻¹|·|p_b|)_k`
///
/// of the stored `w`, where `w_k` is that coordinate of that element as stored. The
/// reasoning: two instances that moved alike have the same exact local position; the stored
/// `w_k` is the f32 rounding of the first one's, within half an ulp of it (≤ ½·ε₃₂·|w_k|
/// for a normal float, less than `f32::MIN_POSITIVE` when it underflows); and each computed
/// `q` carries the f64 rounding of the inverse and its product, bounded by a few ε₆₄ of the
/// magnitudes summed in it (`|M⁻¹|` the entrywise absolute matrix, the translation included).
/// So instances that moved alike pass with a margin of 2 on the f32 rounding and 16 on the
/// f64 one, and a later instance is written only when it reads back within about one f32 ulp
/// of its own local coordinates. The bound is per element and per coordinate: one far
/// element (or one large coordinate) does not widen what the others may disagree by.
/// Rigid instances left unmoved, or moved by one world motion that commutes with both node
/// matrices (a translation under translated nodes, a turn about an axis both nodes turn
/// about), agree.
///
/// # Errors
///
/// `InvalidData` naming the mesh, the accessor, the two nodes and the first vertex (of the
/// later instance) that disagrees; nothing is written.
fn check_instances(
    file: &GltfFile,
    original: &Original<GltfFile>,
    positions: &[DVec3],
    new_local: &[Option<Vec<[f32; 3]>>],
) -> io::Result<()> {
    let mut first_of: HashMap<usize, usize> = HashMap::new();
    for (index, b) in file.blocks.iter().enumerate() {
        let a = *first_of.entry(b.accessor).or_insert(index);
        if a == index {
            continue;
        }
        let first = &file.blocks[a];
        let stored = new_local.get(a).and_then(Option::as_ref).unwrap_or(&first.local);
        let (inverse_a, inverse_b) = (inverse(first)?, inverse(b)?);
        for (i, w) in stored.iter().enumerate() {
            let (_, error_a) = exact_local(first, &inverse_a, original, positions, i);
            let (q, error_b) = exact_local(b, &inverse_b, original, positions, i);
            let w = DVec3::from_array(w.map(f64::from));
            let rounding = f64::from(f32::EPSILON) * w.abs() + DVec3::splat(f64::from(f32::MIN_POSITIVE));
            let tolerance = rounding + 64.0 * f64::EPSILON * (error_a + error_b);
            if (q - w).abs().cmpgt(tolerance).any() {
                return Err(disagreement(first, b, b.first + i));
            }
        }
    }
    Ok(())
}

/// Element `i` of `block` in local space, and the magnitudes summed in computing it (zero for
/// an unmoved element, which is exactly its value as read).
fn exact_local(
    block: &Block,
    inverse: &DMat4,
    original: &Original<GltfFile>,
    positions: &[DVec3],
    i: usize,
) -> (DVec3, DVec3) {
    let read = DVec3::from_array(block.local.get(i).copied().unwrap_or_default().map(f64::from));
    let vertex = block.first + i;
    match (original.positions.get(vertex), positions.get(vertex)) {
        (Some(old), Some(new)) if !same_bits(*old, *new) => {
            let absolute = DMat4::from_cols(
                inverse.x_axis.abs(),
                inverse.y_axis.abs(),
                inverse.z_axis.abs(),
                inverse.w_axis.abs(),
            );
            (inverse.transform_point3(*new), absolute.transform_point3(new.abs()))
        }
        _ => (read, DVec3::ZERO),
    }
}

/// The error for two instances of one POSITION accessor that moved differently (first at
/// `vertex` of the later instance `b`).
fn disagreement(a: &Block, b: &Block, vertex: usize) -> io::Error {
    let mesh = if a.mesh == b.mesh { format!("mesh {}", a.mesh) } else { format!("meshes {} and {}", a.mesh, b.mesh) };
    let nodes = match (a.node, b.node) {
        (Some(x), Some(y)) if x == y => format!("two instances of node {x} (through different parents)"),
        (Some(x), Some(y)) => format!("nodes {x} and {y}"),
        _ => "their instances without a node".to_string(),
    };
    io::Error::new(
        io::ErrorKind::InvalidData,
        format!(
            "{mesh}: {nodes} draw POSITION accessor {} but moved it differently (vertex {vertex}, element {} of the \
             accessor); a glTF file shares one POSITION accessor between these nodes, so it cannot hold both: write \
             another format (.obj, .ply, .off), which keeps each instance's vertices",
            a.accessor,
            vertex - b.first
        ),
    )
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
