//! Writing a mesh and poses of it as one glTF animation that other tools play: glTF animates
//! node transforms and morph target weights only, so each pose is a morph target (its
//! positions' and normals' displacements from the rest mesh) and one animation turns the
//! targets on in order.
//!
//! - **Rest mesh.** f32 POSITION and area-weighted unit NORMAL (as the engine's normals pass
//!   computes them, `[0, 0, 1]` for a vertex of no triangle), and TEXCOORD_0 where the source
//!   (an OBJ's `vt`, a glTF's TEXCOORD_0) gives each face corner texture coordinates, shared by one primitive per face group (the
//!   faces of no group in one more), each with its own u32 indices of its fan-triangulated
//!   faces; the group's name is the primitive's `extras.name`. glTF gives each vertex one
//!   texture coordinate, so a mesh vertex whose corners have several (a texture seam) becomes
//!   one glTF vertex per coordinate, each moving as the mesh vertex does; with texture
//!   coordinates, vertices of no face are left out.
//! - **Targets.** Per pose, POSITION and NORMAL displacements. Stored sparse (the indices of
//!   the vertices that move and their values) where at most half the vertices move, dense
//!   otherwise. `extras.targetNames` names them (three.js and Blender read it).
//! - **Animation.** Keyframe k at k × `seconds_per_pose`, where target k has weight 1 and every
//!   other 0; weights are linear between keyframes, so the mesh moves from pose to pose.

use std::io::{self, Write};

use glam::DVec3;
use serde_json::{Value, json};

use super::{container, normals};
use crate::formats::obj::texcoords::CornerTexcoords;
use crate::mesh::Mesh;

/// `componentType` FLOAT.
const FLOAT: u32 = 5126;
/// `componentType` UNSIGNED_INT.
const UNSIGNED_INT: u32 = 5125;
/// `bufferView.target` ARRAY_BUFFER and ELEMENT_ARRAY_BUFFER.
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// A pose of the mesh for `write_morph_animation`: its name and deformed positions, one per
/// mesh vertex.
#[derive(Clone, Copy, Debug)]
pub struct MorphPose<'a> {
    /// The target's name (`extras.targetNames`).
    pub name: &'a str,
    /// The deformed positions.
    pub positions: &'a [DVec3],
}

/// The glTF document (GLB when `binary`) of `mesh` at rest (with `texcoords`, its face corners'
/// texture coordinates, if given) with one morph target per pose of `poses` and one animation
/// playing them in order, `seconds_per_pose` apart (see the module docs). Fails on a pose with
/// another vertex count, a non-finite position or normal, or a `seconds_per_pose` that is not
/// positive and finite.
pub fn write_morph_animation(
    out: &mut impl Write,
    mesh: &Mesh,
    texcoords: Option<&CornerTexcoords>,
    poses: &[MorphPose],
    seconds_per_pose: f64,
    binary: bool,
) -> io::Result<()> {
    if !(seconds_per_pose.is_finite() && seconds_per_pose > 0.0) {
        return Err(invalid(format!("the seconds per pose must be positive and finite, not {seconds_per_pose}")));
    }
    if poses.is_empty() {
        return Err(invalid("an animation needs at least one pose".into()));
    }
    let count = mesh.positions.len();
    if let Some(pose) = poses.iter().find(|pose| pose.positions.len() != count) {
        return Err(invalid(format!(
            "pose {:?} has {} positions for a mesh of {count} vertices",
            pose.name,
            pose.positions.len()
        )));
    }
    let triangles: Vec<[u32; 3]> = mesh.faces.triangles().collect();
    let layout = Layout::of(mesh, texcoords);
    let rest = Shape::of(&mesh.positions, &triangles, "the rest mesh")?.gathered(&layout.source);
    let mut blob = Blob::default();
    let position = blob.dense(&rest.positions, true, ARRAY_BUFFER);
    let normal = blob.dense(&rest.normals, false, ARRAY_BUFFER);
    let texcoord = layout.texcoords.as_ref().map(|uv| blob.texcoords(uv));
    let targets: Vec<Value> = poses
        .iter()
        .map(|pose| {
            let shape = Shape::of(pose.positions, &triangles, pose.name)?.gathered(&layout.source);
            let moved = |a: &[[f32; 3]], b: &[[f32; 3]]| -> Vec<[f32; 3]> {
                a.iter().zip(b).map(|(p, r)| [p[0] - r[0], p[1] - r[1], p[2] - r[2]]).collect()
            };
            let (dp, dn) = (moved(&shape.positions, &rest.positions), moved(&shape.normals, &rest.normals));
            Ok(json!({"POSITION": blob.displacement(&dp, true), "NORMAL": blob.displacement(&dn, false)}))
        })
        .collect::<io::Result<_>>()?;
    let primitives: Vec<Value> = groups_of(mesh)
        .into_iter()
        .filter(|(_, faces)| !faces.is_empty())
        .map(|(name, faces)| {
            let indices: Vec<u32> = faces.iter().flat_map(|&f| fan(layout.face(f))).flatten().collect();
            let accessor = blob.indices(&indices);
            let mut attributes = json!({"POSITION": position, "NORMAL": normal});
            if let Some(texcoord) = texcoord {
                attributes["TEXCOORD_0"] = texcoord.into();
            }
            let mut primitive = json!({
                "attributes": attributes,
                "indices": accessor,
                "mode": 4,
                "targets": targets,
            });
            if let Some(name) = name {
                primitive["extras"] = json!({"name": name});
            }
            primitive
        })
        .collect();
    if primitives.is_empty() {
        return Err(invalid("the mesh has no faces to animate".into()));
    }
    let times: Vec<f32> = (0..poses.len()).map(|k| (k as f64 * seconds_per_pose) as f32).collect();
    let input = blob.scalars(&times, true);
    let weights: Vec<f32> =
        (0..poses.len()).flat_map(|k| (0..poses.len()).map(move |t| if t == k { 1.0 } else { 0.0 })).collect();
    let output = blob.scalars(&weights, false);
    let names: Vec<&str> = poses.iter().map(|pose| pose.name).collect();
    let document = json!({
        "asset": {"version": "2.0", "generator": "sweepffd"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "sweepffd"}],
        "meshes": [{
            "primitives": primitives,
            "weights": vec![0.0; poses.len()],
            "extras": {"targetNames": names},
        }],
        "animations": [{
            "name": "poses",
            "samplers": [{"input": input, "output": output, "interpolation": "LINEAR"}],
            "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}],
        }],
        "accessors": blob.accessors,
        "bufferViews": blob.views,
        "buffers": [{"byteLength": blob.data.len()}],
    });
    container::write(out, document, &[blob.data], binary)
}

/// The glTF vertices of a mesh: one per mesh vertex, or, with texture coordinates, one per
/// (mesh vertex, texture coordinate) pair its face corners use.
struct Layout {
    /// Per glTF vertex, its mesh vertex.
    source: Vec<u32>,
    /// Per face corner (the faces' corners in order), its glTF vertex.
    corners: Vec<u32>,
    /// Where each face's corners start in `corners`, and their end.
    offsets: Vec<usize>,
    /// Per glTF vertex, its texture coordinate (v down, as glTF has it).
    texcoords: Option<Vec<[f32; 2]>>,
}

impl Layout {
    fn of(mesh: &Mesh, texcoords: Option<&CornerTexcoords>) -> Layout {
        let mut offsets = vec![0];
        for face in mesh.faces.iter() {
            offsets.push(offsets[offsets.len() - 1] + face.len());
        }
        let flat: Vec<u32> = mesh.faces.iter().flatten().copied().collect();
        let Some(texcoords) = texcoords.filter(|t| t.corners.len() == flat.len()) else {
            return Layout {
                source: (0..mesh.positions.len() as u32).collect(),
                corners: flat,
                offsets,
                texcoords: None,
            };
        };
        let mut index: std::collections::HashMap<(u32, u32), u32> = std::collections::HashMap::new();
        let (mut source, mut uv) = (Vec::new(), Vec::new());
        let corners = flat
            .iter()
            .zip(&texcoords.corners)
            .map(|(&v, &t)| {
                *index.entry((v, t)).or_insert_with(|| {
                    source.push(v);
                    let [s, t] = texcoords.coords[t as usize];
                    uv.push([s, 1.0 - t]);
                    (source.len() - 1) as u32
                })
            })
            .collect();
        Layout { source, corners, offsets, texcoords: Some(uv) }
    }

    /// Face `f`'s glTF vertices.
    fn face(&self, f: usize) -> &[u32] {
        &self.corners[self.offsets[f]..self.offsets[f + 1]]
    }
}

/// A mesh's f32 positions and unit normals.
struct Shape {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
}

impl Shape {
    fn of(positions: &[DVec3], triangles: &[[u32; 3]], name: &str) -> io::Result<Shape> {
        let local: Vec<[f32; 3]> = positions.iter().map(|p| p.as_vec3().to_array()).collect();
        if let Some(v) = local.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(invalid(format!("{name}: vertex {v} is not finite in f32: {}", positions[v])));
        }
        let sums = normals::sums(|v| DVec3::from_array(local[v as usize].map(f64::from)), local.len(), triangles);
        let normals = sums.into_iter().map(|s| normals::unit(s).unwrap_or([0.0, 0.0, 1.0])).collect();
        Ok(Shape { positions: local, normals })
    }

    /// The shape at the glTF vertices whose mesh vertices are `source`.
    fn gathered(self, source: &[u32]) -> Shape {
        let pick = |values: &[[f32; 3]]| source.iter().map(|&v| values[v as usize]).collect();
        Shape { positions: pick(&self.positions), normals: pick(&self.normals) }
    }
}

/// The faces of each group (by name) and, last, those of no group (no name), in order.
fn groups_of(mesh: &Mesh) -> Vec<(Option<String>, Vec<usize>)> {
    let faces = mesh.faces.len();
    let mut owner = vec![usize::MAX; faces];
    for (g, group) in mesh.groups.iter().enumerate() {
        for &f in &group.faces {
            if let Some(slot) = owner.get_mut(f as usize).filter(|slot| **slot == usize::MAX) {
                *slot = g;
            }
        }
    }
    let mut groups: Vec<(Option<String>, Vec<usize>)> =
        mesh.groups.iter().map(|group| (Some(group.name.clone()), Vec::new())).collect();
    groups.push((None, Vec::new()));
    let last = groups.len() - 1;
    for (f, &g) in owner.iter().enumerate() {
        groups[if g == usize::MAX { last } else { g }].1.push(f);
    }
    groups
}

/// The binary buffer being built, its views and accessors.
#[derive(Default)]
struct Blob {
    data: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Blob {
    /// A new buffer view of `bytes` (with `target`, if any); its index.
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        let offset = self.data.len();
        self.data.extend_from_slice(bytes);
        let mut view = json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()});
        if let Some(target) = target {
            view["target"] = target.into();
        }
        self.views.push(view);
        self.views.len() - 1
    }

    fn accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// A dense VEC3 float accessor, with its bounds when `bounded`.
    fn dense(&mut self, values: &[[f32; 3]], bounded: bool, target: u32) -> usize {
        let view = self.view(bytemuck::cast_slice(values), Some(target));
        let mut accessor = json!({"bufferView": view, "componentType": FLOAT, "count": values.len(), "type": "VEC3"});
        if bounded {
            let (min, max) = bounds(values);
            accessor["min"] = json!(min);
            accessor["max"] = json!(max);
        }
        self.accessor(accessor)
    }

    /// A morph target's displacements: sparse (over zeros) where at most half are non-zero.
    fn displacement(&mut self, values: &[[f32; 3]], bounded: bool) -> usize {
        let moved: Vec<u32> = (0..values.len() as u32).filter(|&v| values[v as usize] != [0.0; 3]).collect();
        if 2 * moved.len() > values.len() {
            return self.dense(values, bounded, ARRAY_BUFFER);
        }
        let mut accessor = json!({"componentType": FLOAT, "count": values.len(), "type": "VEC3"});
        if bounded {
            let (min, max) = bounds(values);
            accessor["min"] = json!(min);
            accessor["max"] = json!(max);
        }
        if !moved.is_empty() {
            let picked: Vec<[f32; 3]> = moved.iter().map(|&v| values[v as usize]).collect();
            let indices = self.view(bytemuck::cast_slice(&moved), None);
            let values = self.view(bytemuck::cast_slice(&picked), None);
            accessor["sparse"] = json!({
                "count": moved.len(),
                "indices": {"bufferView": indices, "componentType": UNSIGNED_INT},
                "values": {"bufferView": values},
            });
        }
        self.accessor(accessor)
    }

    /// The TEXCOORD_0 accessor.
    fn texcoords(&mut self, values: &[[f32; 2]]) -> usize {
        let view = self.view(bytemuck::cast_slice(values), Some(ARRAY_BUFFER));
        self.accessor(json!({"bufferView": view, "componentType": FLOAT, "count": values.len(), "type": "VEC2"}))
    }

    /// The u32 indices of a primitive.
    fn indices(&mut self, indices: &[u32]) -> usize {
        let view = self.view(bytemuck::cast_slice(indices), Some(ELEMENT_ARRAY_BUFFER));
        self.accessor(
            json!({"bufferView": view, "componentType": UNSIGNED_INT, "count": indices.len(), "type": "SCALAR"}),
        )
    }

    /// A SCALAR float accessor (an animation's times, with their bounds, or its weights).
    fn scalars(&mut self, values: &[f32], bounded: bool) -> usize {
        let view = self.view(bytemuck::cast_slice(values), None);
        let mut accessor = json!({"bufferView": view, "componentType": FLOAT, "count": values.len(), "type": "SCALAR"});
        if bounded {
            let (lo, hi) =
                values.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
            accessor["min"] = json!([lo]);
            accessor["max"] = json!([hi]);
        }
        self.accessor(accessor)
    }
}

/// The fan triangles of one face, as [`crate::mesh::Faces::triangles`] makes them.
fn fan(face: &[u32]) -> impl Iterator<Item = [u32; 3]> + '_ {
    let first = face.first().copied().unwrap_or(0);
    face.windows(2).skip(1).map(move |pair| [first, pair[0], pair[1]])
}

fn bounds(values: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    values.iter().fold(([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]), |(lo, hi), p| {
        (std::array::from_fn(|i| lo[i].min(p[i])), std::array::from_fn(|i| hi[i].max(p[i])))
    })
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{FaceGroup, Faces};

    /// Two quads in two groups, and a loose vertex.
    fn mesh() -> Mesh {
        let positions = (0..6).map(|i| DVec3::new((i % 3) as f64, (i / 3) as f64, 0.0)).chain([DVec3::Z]).collect();
        let mut faces = Faces::new();
        faces.push(&[0, 1, 4, 3]);
        faces.push(&[1, 2, 5, 4]);
        let groups =
            vec![FaceGroup { name: "left".into(), faces: vec![0] }, FaceGroup { name: "right".into(), faces: vec![1] }];
        Mesh::from_parts(positions, faces, groups).unwrap()
    }

    fn document(mesh: &Mesh, poses: &[MorphPose]) -> Value {
        let mut out = Vec::new();
        write_morph_animation(&mut out, mesh, None, poses, 0.25, false).unwrap();
        serde_json::from_slice(&out).unwrap()
    }

    #[test]
    fn each_group_is_a_primitive_sharing_the_targets_and_few_moves_are_sparse() {
        let mesh = mesh();
        let mut one = mesh.positions.clone();
        one[5].z += 0.5;
        let all: Vec<DVec3> = mesh.positions.iter().map(|p| *p + DVec3::X).collect();
        let json =
            document(&mesh, &[MorphPose { name: "one", positions: &one }, MorphPose { name: "all", positions: &all }]);
        let primitives = json["meshes"][0]["primitives"].as_array().unwrap();
        assert_eq!(primitives.len(), 2, "the loose vertex is in no face: no third primitive");
        assert_eq!(
            (primitives[0]["extras"]["name"].as_str(), primitives[1]["extras"]["name"].as_str()),
            (Some("left"), Some("right"))
        );
        assert_eq!(primitives[0]["targets"], primitives[1]["targets"]);
        let accessor = |i: &Value| &json["accessors"][i.as_u64().unwrap() as usize];
        let moved_one = accessor(&primitives[0]["targets"][0]["POSITION"]);
        assert_eq!(moved_one["sparse"]["count"], 1, "one vertex of seven moves: sparse");
        assert_eq!(moved_one["max"][2], 0.5);
        assert!(
            accessor(&primitives[0]["targets"][1]["POSITION"]).get("sparse").is_none(),
            "every vertex moves: dense"
        );
        assert_eq!(json["meshes"][0]["extras"]["targetNames"], serde_json::json!(["one", "all"]));
        let sampler = &json["animations"][0]["samplers"][0];
        assert_eq!(accessor(&sampler["input"])["max"], serde_json::json!([0.25]));
        assert_eq!(accessor(&sampler["output"])["count"], 4);
    }

    #[test]
    fn bad_poses_and_timings_are_refused() {
        let mesh = mesh();
        let short = vec![DVec3::ZERO; 3];
        let mut out = Vec::new();
        let error =
            write_morph_animation(&mut out, &mesh, None, &[MorphPose { name: "short", positions: &short }], 1.0, true);
        assert!(error.unwrap_err().to_string().contains("3 positions for a mesh of 7 vertices"));
        let pose = [MorphPose { name: "rest", positions: &mesh.positions }];
        for seconds in [0.0, -1.0, f64::NAN] {
            assert!(write_morph_animation(&mut out, &mesh, None, &pose, seconds, true).is_err(), "{seconds}");
        }
        assert!(write_morph_animation(&mut out, &mesh, None, &[], 1.0, true).is_err(), "no pose");
        let mut bad = mesh.positions.clone();
        bad[2].x = f64::INFINITY;
        let error =
            write_morph_animation(&mut out, &mesh, None, &[MorphPose { name: "bad", positions: &bad }], 1.0, true);
        assert!(error.unwrap_err().to_string().contains("bad: vertex 2"));
    }
}
