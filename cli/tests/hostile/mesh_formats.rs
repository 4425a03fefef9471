//! OFF and glTF files in and out: the shared OFF meshes load with their documented counts,
//! COFF colours survive a deformation, malformed OFF names the file and line; glTF and GLB
//! round-trip a mesh built in code, keep every other attribute of a loaded file when only
//! positions change, respect node transforms both ways, and go through `sweepffd deform`.

use crate::common;

use std::fs;
use std::path::Path;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use glam::DVec3;
use serde_json::json;
use sweepffd::formats::{LoadedMesh, MeshError};
use sweepffd::mesh::{FaceGroup, Faces, Mesh};
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

// ---------------------------------------------------------------- OFF

#[test]
fn shared_off_meshes_have_the_readme_counts() {
    for (name, vertices, faces) in [("chair.off", 10_500, 21_008), ("dino.off", 3_916, 7_828)] {
        let Some(path) = common::shared_mesh(name) else { continue };
        let mesh = Mesh::load(&path).unwrap();
        assert_eq!((mesh.positions.len(), mesh.faces.len()), (vertices, faces), "{name}");
        assert!(mesh.faces.iter().all(|f| f.len() == 3), "{name}: triangles only");
        assert!(mesh.groups.is_empty());
    }
}

/// The data lines of an OFF file (comments and blank lines dropped), as token lists.
fn off_lines(text: &str) -> Vec<Vec<&str>> {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or("").split_whitespace().collect::<Vec<_>>())
        .filter(|t| !t.is_empty())
        .collect()
}

#[test]
fn dino_colours_survive_a_deformation() {
    let Some(path) = common::shared_mesh("dino.off") else { return };
    let mesh = LoadedMesh::load(&path).unwrap();
    let moved: Vec<DVec3> = mesh.mesh.positions.iter().map(|p| *p * 2.0 + DVec3::X).collect();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("dino2.off");
    mesh.save(&out, &moved).unwrap();
    let input = fs::read_to_string(&path).unwrap();
    let output = fs::read_to_string(&out).unwrap();
    let (input, output) = (off_lines(&input), off_lines(&output));
    assert_eq!(input.len(), output.len());
    assert_eq!(output[0], ["COFF"]);
    for v in 0..mesh.mesh.positions.len() {
        assert_eq!(output[2 + v][3..], input[2 + v][3..], "colour of vertex {v}");
        assert_eq!(output[2 + v][3..].len(), 4, "RGBA of vertex {v}");
    }
    assert_eq!(output[2 + mesh.mesh.positions.len()..], input[2 + mesh.mesh.positions.len()..], "faces");
    let back = Mesh::load(&out).unwrap();
    assert_eq!(back.positions, moved, "shortest round-trip digits read back exactly");
    assert_eq!(back.faces, mesh.mesh.faces);
    // Unchanged positions: byte-identical.
    let same = dir.path().join("same.off");
    mesh.save(&same, &mesh.mesh.positions).unwrap();
    assert_eq!(fs::read(&same).unwrap(), fs::read(&path).unwrap());
}

#[test]
fn off_errors_name_the_file_and_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "truncated.off",
            "OFF\n4 1 0\n0 0 0\n1 0 0\n",
            "truncated.off:4: the file ends after 2 of the 4 vertices the header declares",
        ),
        (
            "counts.off",
            "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            "counts.off:6: the file ends after 1 of the 2 faces the header declares",
        ),
        (
            "range.off",
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
            "range.off:6: face 0 refers to vertex 7 but the file has 3 vertices (indices start at 0)",
        ),
        (
            "token.off",
            "# c\nOFF\n3 1 0\n0 0 0\n1 0,5 0\n0 1 0\n3 0 1 2\n",
            "token.off:5: vertex coordinate \"0,5\" is not a number",
        ),
        (
            "extra.off",
            "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            "extra.off:6: unexpected data after the last of the 0 faces the header declares",
        ),
    ];
    for (name, text, expected) in cases {
        let path = dir.path().join(name);
        fs::write(&path, text).unwrap();
        let error = Mesh::load(&path).unwrap_err();
        assert!(matches!(error, MeshError::Off { .. }), "{error:?}");
        assert_eq!(error.to_string(), format!("{}", path.display()).replace(name, expected), "{name}");
    }
}

/// A square (as a quad) and a triangle on it, in two groups.
fn house() -> Mesh {
    let positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.5, 1.6, 0.1),
    ];
    let mut faces = Faces::new();
    faces.push(&[0, 1, 2, 3]);
    faces.push(&[3, 2, 4]);
    let groups =
        vec![FaceGroup { name: "walls".into(), faces: vec![0] }, FaceGroup { name: "roof".into(), faces: vec![1] }];
    Mesh::from_parts(positions, faces, groups).unwrap()
}

#[test]
fn off_generic_save_keeps_polygons() {
    let mesh = LoadedMesh::from(house());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("house.OFF");
    mesh.save(&path, &mesh.mesh.positions).unwrap();
    let back = Mesh::load(&path).unwrap();
    assert_eq!(back.positions, mesh.mesh.positions);
    assert_eq!(back.faces, mesh.mesh.faces);
}

// ---------------------------------------------------------------- glTF

#[test]
fn code_mesh_round_trips_through_glb_and_gltf() {
    let mesh = LoadedMesh::from(house());
    let dir = tempfile::tempdir().unwrap();
    for name in ["house.glb", "house.gltf"] {
        let path = dir.path().join(name);
        mesh.save(&path, &mesh.mesh.positions).unwrap();
        let back = Mesh::load(&path).unwrap();
        let expected: Vec<DVec3> = mesh.mesh.positions.iter().map(|p| p.as_vec3().as_dvec3()).collect();
        assert_eq!(back.positions, expected, "{name}: f32 positions");
        let triangles: Vec<[u32; 3]> = back.faces.iter().map(|f| [f[0], f[1], f[2]]).collect();
        assert_eq!(triangles, mesh.mesh.faces.triangles().collect::<Vec<_>>(), "{name}: fan-triangulated faces");
        assert_eq!(back.groups, [FaceGroup { name: "mesh0".into(), faces: vec![0, 1, 2] }], "{name}");
    }
    let glb = fs::read(dir.path().join("house.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    let gltf: serde_json::Value = serde_json::from_slice(&fs::read(dir.path().join("house.gltf")).unwrap()).unwrap();
    assert!(gltf["buffers"][0]["uri"].as_str().unwrap().starts_with("data:application/octet-stream;base64,"));
    assert_eq!(gltf["meshes"][0]["primitives"][0]["attributes"]["NORMAL"], 1);
}

/// A glTF document with a quad `plate` (POSITION, NORMAL, TEXCOORD_0, u16 indices) under a
/// node translated by (1, 2, 3) and scaled by 2, its buffer a data URI.
fn plate_gltf() -> (serde_json::Value, Vec<u8>) {
    let positions: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let normals = [[0.0f32, 0.0, 1.0]; 4];
    let uvs: [[f32; 2]; 4] = [[0.1, 0.2], [0.9, 0.2], [0.9, 0.8], [0.1, 0.8]];
    let indices: [u16; 6] = [0, 1, 2, 0, 2, 3];
    let mut data = Vec::new();
    for p in positions.iter().flatten().chain(normals.iter().flatten()).chain(uvs.iter().flatten()) {
        data.extend_from_slice(&p.to_le_bytes());
    }
    for i in indices {
        data.extend_from_slice(&i.to_le_bytes());
    }
    let document = json!({
        "asset": {"version": "2.0", "generator": "test"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "root", "translation": [1.0, 2.0, 3.0], "children": [1]}, {"scale": [2.0, 2.0, 2.0], "mesh": 0}],
        "meshes": [{"name": "plate", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.0, 0.0, 1.0]}, "extras": {"keep": "me"}}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 96},
            {"buffer": 0, "byteOffset": 96, "byteLength": 32},
            {"buffer": 0, "byteOffset": 128, "byteLength": 12}
        ],
        "buffers": [{"byteLength": data.len(), "uri": format!("data:application/octet-stream;base64,{}", STANDARD.encode(&data))}]
    });
    (document, data)
}

/// The JSON and the data of buffer 0 of a written glTF or GLB file.
fn parts(path: &Path) -> (serde_json::Value, Vec<u8>) {
    let bytes = fs::read(path).unwrap();
    if bytes.starts_with(b"glTF") {
        let glb = gltf::binary::Glb::from_slice(&bytes).unwrap();
        let json: serde_json::Value = serde_json::from_slice(&glb.json).unwrap();
        let length = json["buffers"][0]["byteLength"].as_u64().unwrap() as usize;
        (json, glb.bin.unwrap()[..length].to_vec())
    } else {
        let json: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
        let uri = json["buffers"][0]["uri"].as_str().unwrap().to_string();
        let data = STANDARD.decode(uri.split_once(',').unwrap().1).unwrap();
        (json, data)
    }
}

fn f32s(bytes: &[u8]) -> Vec<f32> {
    bytes.chunks_exact(4).map(|c| f32::from_le_bytes(c.try_into().unwrap())).collect()
}

#[test]
fn gltf_node_transforms_apply_on_load_and_invert_on_save() {
    let (document, data) = plate_gltf();
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("plate.gltf");
    fs::write(&input, serde_json::to_vec(&document).unwrap()).unwrap();
    let mesh = LoadedMesh::load(&input).unwrap();
    assert_eq!(mesh.mesh.positions[2], DVec3::new(3.0, 4.0, 3.0), "scale 2, then translate (1, 2, 3)");
    assert_eq!(mesh.mesh.groups, [FaceGroup { name: "plate".into(), faces: vec![0, 1] }]);

    let mut moved = mesh.mesh.positions.clone();
    moved[0] += DVec3::new(0.0, 0.0, 1.0);
    for name in ["moved.glb", "moved.gltf"] {
        let out = dir.path().join(name);
        mesh.save(&out, &moved).unwrap();
        let back = Mesh::load(&out).unwrap();
        assert_eq!(back.positions, moved, "{name}: positions in world space");
        let (json, bytes) = parts(&out);
        let local = f32s(&bytes[..48]);
        assert_eq!(local[..3], [0.0, 0.0, 0.5], "{name}: vertex 0 back in local space");
        assert_eq!(bytes[12..48], data[12..48], "{name}: unmoved positions keep their bytes");
        assert_eq!(bytes[96..], data[96..], "{name}: TEXCOORD_0 and indices unchanged");
        assert_eq!(json["accessors"][0]["max"], json!([1.0, 1.0, 0.5]), "{name}: max updated");
        assert_eq!(json["materials"], document["materials"], "{name}: material and extras kept");
        assert_eq!(json["nodes"], document["nodes"], "{name}: nodes kept");
        let normals = f32s(&bytes[48..96]);
        for v in 0..4 {
            let n = DVec3::new(normals[3 * v].into(), normals[3 * v + 1].into(), normals[3 * v + 2].into());
            assert!((n.length() - 1.0).abs() < 1e-6, "{name}: normal {v} is unit");
        }
        assert!(normals[2] < 0.99, "{name}: the normal of the moved vertex is recomputed: {:?}", &normals[..3]);
        // Every vertex shares a triangle with vertex 0, so vertex 1's normal is recomputed too:
        // the triangle (0, 0, 0.5), (1, 0, 0), (1, 1, 0) has normal (0.5, 0, 1) / √1.25.
        assert!((normals[5] - 1.0 / 1.25f32.sqrt()).abs() < 1e-6, "{name}: {:?}", &normals[3..6]);
    }
}

#[test]
fn unchanged_gltf_save_keeps_buffer_bytes_and_values() {
    let (document, data) = plate_gltf();
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("plate.gltf");
    fs::write(&input, serde_json::to_vec(&document).unwrap()).unwrap();
    let mesh = LoadedMesh::load(&input).unwrap();
    for name in ["same.gltf", "same.glb"] {
        let out = dir.path().join(name);
        mesh.save(&out, &mesh.mesh.positions).unwrap();
        let (json, bytes) = parts(&out);
        assert_eq!(bytes, data, "{name}: buffer byte-identical");
        assert_eq!(json["accessors"], document["accessors"], "{name}");
        let back = LoadedMesh::load(&out).unwrap();
        assert_eq!(back.mesh.positions, mesh.mesh.positions, "{name}");
        assert_eq!(back.mesh.faces, mesh.mesh.faces, "{name}");
        // And again from the re-written file: stable.
        let again = dir.path().join(format!("again.{}", name.rsplit('.').next().unwrap()));
        back.save(&again, &back.mesh.positions).unwrap();
        assert_eq!(fs::read(&again).unwrap(), fs::read(&out).unwrap(), "{name}: second save byte-identical");
    }
}

#[test]
fn gltf_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let (mut document, _) = plate_gltf();
    document["meshes"][0]["primitives"][0]["mode"] = json!(1);
    let path = dir.path().join("lines.gltf");
    fs::write(&path, serde_json::to_vec(&document).unwrap()).unwrap();
    let message = Mesh::load(&path).unwrap_err().to_string();
    assert!(message.ends_with("lines.gltf: mesh 0 primitive 0: LINES primitives are not supported (triangles, strips, fans and points are)"), "{message}");

    let path = dir.path().join("garbage.glb");
    fs::write(&path, b"glTF\x02\0\0\0garbage").unwrap();
    let message = Mesh::load(&path).unwrap_err().to_string();
    assert!(message.contains("garbage.glb: not a valid glTF file: "), "{message}");

    let (mut document, _) = plate_gltf();
    document["buffers"][0]["uri"] = json!("missing.bin");
    let path = dir.path().join("missing.gltf");
    fs::write(&path, serde_json::to_vec(&document).unwrap()).unwrap();
    let message = Mesh::load(&path).unwrap_err().to_string();
    assert!(message.contains("missing.gltf: buffer 0: cannot read "), "{message}");

    let (mut document, _) = plate_gltf();
    document["accessors"][3]["count"] = json!(60);
    let path = dir.path().join("short.gltf");
    fs::write(&path, serde_json::to_vec(&document).unwrap()).unwrap();
    assert!(Mesh::load(&path).is_err());
}

#[test]
fn deform_a_glb_tube_through_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let tube = Tube { rings: 20, around: 16, length: 2.0, radius: 0.3 };
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.path().join("tube.glb"), &mesh.mesh.positions).unwrap();
    mesh.save(&dir.path().join("tube.obj"), &mesh.mesh.positions).unwrap();
    let rig = tube_rig(&tube, 4, 8);
    fs::write(dir.path().join("rig.json"), rig.to_document().to_json()).unwrap();
    let keys = BendTwistTaper { bend: 0.8, twist: 1.0, taper: 0.7 }.keys(&rig);
    fs::write(dir.path().join("pose.json"), rig.pose_document(&keys).to_json()).unwrap();
    for (input, output) in [("tube.glb", "out.glb"), ("tube.obj", "out.obj")] {
        let status = common::sweepffd(dir.path())
            .args(["deform", "--mesh", input, "--rig", "rig.json", "--pose", "pose.json", "--out", output])
            .args(["--backend", "cpu"])
            .output()
            .unwrap();
        assert!(status.status.success(), "{input}: {}", String::from_utf8_lossy(&status.stderr));
    }
    let glb_in = Mesh::load(&dir.path().join("tube.glb")).unwrap();
    let glb = Mesh::load(&dir.path().join("out.glb")).unwrap();
    let obj = Mesh::load(&dir.path().join("out.obj")).unwrap();
    assert_eq!(glb.faces, glb_in.faces);
    let worst = glb.positions.iter().zip(&obj.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    let moved = glb.positions.iter().zip(&glb_in.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    assert!(moved > 0.1, "the pose moves the tube: {moved}");
    assert!(worst < 1e-5, "GLB and OBJ outputs differ by {worst}");
    let (json, _) = parts(&dir.path().join("out.glb"));
    assert_eq!(json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"], 1);
}

#[test]
fn corrupted_glb_and_off_do_not_panic() {
    let mesh = LoadedMesh::from(house());
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("house.glb");
    mesh.save(&glb, &mesh.mesh.positions).unwrap();
    let bytes = fs::read(&glb).unwrap();
    let noisy = dir.path().join("noisy.glb");
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    for _ in 0..300 {
        let mut corrupt = bytes.clone();
        for _ in 0..3 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let at = (state % corrupt.len() as u64) as usize;
            corrupt[at] = (state >> 40) as u8;
        }
        fs::write(&noisy, &corrupt).unwrap();
        if let Ok(loaded) = LoadedMesh::load(&noisy) {
            let _ = loaded.save(&dir.path().join("again.glb"), &loaded.mesh.positions);
        }
    }
}

/// Two meshes: `plate` drawn by two nodes, its two primitives sharing one POSITION accessor,
/// and an unnamed triangle whose positions are sparse (element 1 replaced).
fn scene_gltf() -> serde_json::Value {
    let mut data = Vec::new();
    let floats: [f32; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
    for f in floats {
        data.extend_from_slice(&f.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        data.extend_from_slice(&i.to_le_bytes());
    }
    // Sparse substitution: index 1 → (5, 5, 5), at byte 60 (u16 index, padded) and 64.
    data.extend_from_slice(&1u16.to_le_bytes());
    data.extend_from_slice(&[0, 0]);
    for f in [5.0f32, 5.0, 5.0] {
        data.extend_from_slice(&f.to_le_bytes());
    }
    json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0}, {"mesh": 0, "translation": [0.0, 0.0, 10.0]}, {"mesh": 1}],
        "meshes": [
            {"name": "plate", "primitives": [
                {"attributes": {"POSITION": 0}, "indices": 1},
                {"attributes": {"POSITION": 0}, "indices": 2}
            ]},
            {"primitives": [{"attributes": {"POSITION": 3}}]}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
            {"bufferView": 1, "byteOffset": 6, "componentType": 5123, "count": 3, "type": "SCALAR"},
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [5.0, 5.0, 5.0],
             "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5123}, "values": {"bufferView": 3}}}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 12},
            {"buffer": 0, "byteOffset": 60, "byteLength": 2},
            {"buffer": 0, "byteOffset": 64, "byteLength": 12}
        ],
        "buffers": [{"byteLength": data.len(), "uri": format!("data:application/octet-stream;base64,{}", STANDARD.encode(&data))}]
    })
}

#[test]
fn gltf_instances_shared_accessors_sparse_positions_and_groups() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("scene.gltf");
    fs::write(&input, serde_json::to_vec(&scene_gltf()).unwrap()).unwrap();
    let mesh = LoadedMesh::load(&input).unwrap();
    // Two instances of the plate's 4 shared vertices, then the sparse triangle's 3.
    assert_eq!(mesh.mesh.positions.len(), 11);
    assert_eq!(mesh.mesh.positions[6], DVec3::new(1.0, 1.0, 10.0));
    assert_eq!(mesh.mesh.positions[9], DVec3::new(5.0, 5.0, 5.0), "sparse substitution applied");
    assert_eq!(mesh.mesh.faces.face(1), &[0, 2, 3]);
    assert_eq!(mesh.mesh.faces.face(2), &[4, 5, 6]);
    let names: Vec<&str> = mesh.mesh.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["plate", "mesh1"]);
    assert_eq!(mesh.mesh.groups[0].faces, [0, 1, 2, 3]);
    assert_eq!(mesh.mesh.group_vertices("mesh1").unwrap(), [8, 9, 10]);

    let mut moved = mesh.mesh.positions.clone();
    moved[9] = DVec3::new(6.0, 6.0, 6.0);
    moved[1] = DVec3::new(2.0, 0.0, 0.0);
    // The plate's instances share one accessor: both must move alike (else nothing is written).
    moved[5] = DVec3::new(2.0, 0.0, 10.0);
    let out = dir.path().join("scene.glb");
    mesh.save(&out, &moved).unwrap();
    let back = Mesh::load(&out).unwrap();
    assert_eq!(back.positions[9], moved[9], "the sparse accessor was made dense");
    assert_eq!(back.positions[1], moved[1]);
    assert_eq!(back.positions[5], moved[5], "the second instance, moved alike");
    let (json, _) = parts(&out);
    assert!(json["accessors"][3].get("sparse").is_none());
    assert_eq!(json["accessors"][3]["max"], json!([6.0, 6.0, 6.0]));
}
