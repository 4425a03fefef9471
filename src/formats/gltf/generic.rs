//! Writing a mesh as a new glTF file: one node, one mesh, one primitive.

use std::io::{self, Write};

use glam::DVec3;
use serde_json::{Value, json};

use super::{container, normals};
use crate::mesh::Faces;

/// `componentType` FLOAT.
const FLOAT: u32 = 5126;
/// `componentType` UNSIGNED_INT.
const UNSIGNED_INT: u32 = 5125;

/// Writes `positions` and `faces` as a glTF document (GLB when `binary`): one buffer holding
/// f32 POSITION, area-weighted unit NORMAL (`[0, 0, 1]` for a vertex of no triangle) and u32
/// indices of the fan-triangulated faces ([`Faces::triangles`]), in that order, each in its
/// own buffer view. A mesh without faces is written as one POINTS primitive without normals.
pub(crate) fn write_generic(out: &mut impl Write, positions: &[DVec3], faces: &Faces, binary: bool) -> io::Result<()> {
    let local: Vec<[f32; 3]> = positions.iter().map(|p| p.as_vec3().to_array()).collect();
    finite_f32(positions, &local)?;
    let triangles: Vec<[u32; 3]> = faces.triangles().collect();
    let (min, max) = bounds(&local);
    let mut data: Vec<u8> = bytemuck::cast_slice(&local).to_vec();
    let mut views = vec![json!({"buffer": 0, "byteOffset": 0, "byteLength": data.len(), "target": 34962})];
    let mut accessors = vec![json!({
        "bufferView": 0, "componentType": FLOAT, "count": local.len(), "type": "VEC3", "min": min, "max": max,
    })];
    let mut primitive = json!({"attributes": {"POSITION": 0}, "mode": 0});
    if !triangles.is_empty() {
        let sums = normals::sums(|v| DVec3::from_array(local[v as usize].map(f64::from)), local.len(), &triangles);
        let unit: Vec<[f32; 3]> = sums.into_iter().map(|s| normals::unit(s).unwrap_or([0.0, 0.0, 1.0])).collect();
        if let Some((vertex, value)) = first_non_finite(&unit) {
            return Err(invalid(format!("vertex {vertex}: its normal has the non-finite component {value}")));
        }
        let offset = data.len();
        data.extend_from_slice(bytemuck::cast_slice(&unit));
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": data.len() - offset, "target": 34962}));
        accessors.push(json!({"bufferView": 1, "componentType": FLOAT, "count": unit.len(), "type": "VEC3"}));
        let offset = data.len();
        data.extend_from_slice(bytemuck::cast_slice(&triangles));
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": data.len() - offset, "target": 34963}));
        accessors.push(
            json!({"bufferView": 2, "componentType": UNSIGNED_INT, "count": 3 * triangles.len(), "type": "SCALAR"}),
        );
        primitive = json!({"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "mode": 4});
    }
    let document = json!({
        "asset": {"version": "2.0", "generator": "sweepffd"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [primitive]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": data.len()}],
    });
    container::write(out, document, &[data], binary)
}

/// An `InvalidInput` error with `message`.
pub(super) fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// Refuses a position whose f32 conversion `local` is not finite, naming the vertex and the
/// coordinate.
fn finite_f32(positions: &[DVec3], local: &[[f32; 3]]) -> io::Result<()> {
    match first_non_finite(local) {
        Some((vertex, _)) => {
            let value = positions[vertex].to_array().into_iter().find(|c| !(*c as f32).is_finite()).unwrap_or_default();
            Err(invalid(format!("vertex {vertex}: the coordinate {value:?} does not fit in f32")))
        }
        None => Ok(()),
    }
}

/// The first element with a non-finite component, and that component.
pub(super) fn first_non_finite(values: &[[f32; 3]]) -> Option<(usize, f32)> {
    values.iter().enumerate().find_map(|(i, v)| v.iter().find(|c| !c.is_finite()).map(|&c| (i, c)))
}

/// The componentwise minimum and maximum of `points`, as JSON arrays (zeros for none: JSON
/// has no infinity).
pub(super) fn bounds(points: &[[f32; 3]]) -> (Value, Value) {
    if points.is_empty() {
        return (json!([0.0, 0.0, 0.0]), json!([0.0, 0.0, 0.0]));
    }
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
    }
    (json!(min), json!(max))
}
