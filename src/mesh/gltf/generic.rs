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
    if local.iter().flatten().any(|c| !c.is_finite()) {
        return Err(io::Error::new(io::ErrorKind::InvalidInput, "a position overflows f32"));
    }
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

/// The componentwise minimum and maximum of `points`, as JSON arrays.
pub(super) fn bounds(points: &[[f32; 3]]) -> (Value, Value) {
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
