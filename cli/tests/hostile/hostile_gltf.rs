//! Hostile glTF and GLB files: deep and exponentially shared node graphs, buffer URIs that
//! point outside the file's folder, malformed accessors, non-finite values. Each is an error
//! that names the file and what is wrong, in bounded time and memory, without a panic
//! message, and nothing is written.
//!
//! The files are built here: the JSON with `serde_json`, the GLB container by hand.

use crate::common;

use std::fs;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use glam::DVec3;
use serde_json::{Value, json};
use sweepffd::formats::LoadedMesh;
use sweepffd::limits::{MAX_GLTF_INSTANCES, MAX_GLTF_NODE_DEPTH};
use sweepffd::mesh::{Faces, Mesh};

/// A GLB container: header, the JSON chunk padded with spaces, the BIN chunk padded with zeros.
fn glb(document: &Value, bin: &[u8]) -> Vec<u8> {
    let mut text = serde_json::to_vec(document).unwrap();
    text.resize(text.len().next_multiple_of(4), b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().next_multiple_of(4), 0);
    let total = 12 + 8 + text.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = b"glTF".to_vec();
    for word in [2, total as u32, text.len() as u32, 0x4E4F_534A] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&text);
    if !bin.is_empty() {
        for word in [bin.len() as u32, 0x004E_4942] {
            out.extend_from_slice(&word.to_le_bytes());
        }
        out.extend_from_slice(&bin);
    }
    out
}

/// Little-endian bytes of f32 values.
fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// One triangle: POSITION (accessor 0, bytes 0..36), NORMAL (1, 36..72), TEXCOORD_0
/// (2, 72..96), u16 indices (3, 96..102), one buffer view each, all in buffer 0 (the BIN chunk).
/// One node draws the mesh.
fn triangle() -> (Value, Vec<u8>) {
    let mut data = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    data.extend(f32_bytes(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0]));
    data.extend(f32_bytes(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]));
    data.extend([0u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    data.extend([0, 0]);
    let document = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 36},
            {"buffer": 0, "byteOffset": 72, "byteLength": 24},
            {"buffer": 0, "byteOffset": 96, "byteLength": 6}
        ],
        "buffers": [{"byteLength": data.len()}]
    });
    (document, data)
}

/// Writes `bytes` as `name` in `dir` and loads it: the mesh, or the error's message.
fn load(dir: &Path, name: &str, bytes: &[u8]) -> Result<LoadedMesh, String> {
    let path = dir.join(name);
    fs::write(&path, bytes).unwrap();
    LoadedMesh::load(&path).map_err(|e| e.to_string())
}

/// Loads `bytes` as `name` in `dir`, expecting the error `"<path>: <message>"`.
fn fails(dir: &Path, name: &str, bytes: &[u8], message: &str) {
    let error = load(dir, name, bytes).err().unwrap_or_else(|| panic!("{name} loaded"));
    assert_eq!(error, format!("{}: {message}", dir.join(name).display()));
}

/// A node chain of `length` nodes (node i the parent of node i + 1), the last drawing the
/// triangle.
fn chain(length: usize) -> Vec<u8> {
    let (mut document, data) = triangle();
    let mut nodes: Vec<Value> = (1..length).map(|i| json!({"children": [i]})).collect();
    nodes.push(json!({"mesh": 0}));
    document["nodes"] = Value::Array(nodes);
    glb(&document, &data)
}

#[test]
fn a_deep_node_chain_is_refused_naming_the_node_and_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    // Case 3: 20,000 nodes overflowed the stack of the recursive walk.
    let limit = MAX_GLTF_NODE_DEPTH;
    fails(
        dir.path(),
        "deep.glb",
        &chain(20_000),
        &format!(
            "node {} is at depth {} of the node hierarchy, deeper than the limit of {limit} (MAX_GLTF_NODE_DEPTH in sweepffd::limits)",
            limit + 1,
            limit + 1
        ),
    );
    // The deepest chain allowed loads, its triangle at depth MAX_GLTF_NODE_DEPTH.
    let mesh = load(dir.path(), "deepest.glb", &chain(limit + 1)).unwrap();
    assert_eq!(mesh.mesh.positions.len(), 3);
}

#[test]
fn a_cycle_in_the_node_graph_is_still_found() {
    let dir = tempfile::tempdir().unwrap();
    let (mut document, data) = triangle();
    document["nodes"] = json!([{"children": [1]}, {"children": [2], "mesh": 0}, {"children": [1]}]);
    fails(dir.path(), "cycle.glb", &glb(&document, &data), "the node hierarchy has a cycle (through node 1)");
}

/// `levels` nodes, each with the next node as both of its children, the last drawing the
/// triangle: 2^levels instances from a file of a few hundred bytes.
fn doubling(levels: usize) -> Vec<u8> {
    let (mut document, data) = triangle();
    let mut nodes: Vec<Value> = (1..=levels).map(|i| json!({"children": [i, i]})).collect();
    nodes.push(json!({"mesh": 0}));
    document["nodes"] = Value::Array(nodes);
    glb(&document, &data)
}

#[test]
fn exponential_instancing_is_refused_before_anything_is_built() {
    let dir = tempfile::tempdir().unwrap();
    // Case 4: depth 18 took 10 s and 2.5 GB; depth 22 aborted.
    let start = Instant::now();
    fails(
        dir.path(),
        "doubling18.glb",
        &doubling(18),
        "the scene would give 262144 mesh instances, more than the limit of 65536 (MAX_GLTF_INSTANCES in sweepffd::limits)",
    );
    // Past 2^64 the count saturates: still refused, still at once.
    fails(
        dir.path(),
        "doubling200.glb",
        &doubling(200),
        &format!(
            "the scene would give at least {} mesh instances, more than the limit of 65536 (MAX_GLTF_INSTANCES in sweepffd::limits)",
            usize::MAX
        ),
    );
    assert!(start.elapsed() < Duration::from_secs(2), "took {:?}", start.elapsed());
    // 2^16 instances is the limit itself: it loads.
    assert_eq!(1 << 16, MAX_GLTF_INSTANCES);
    let mesh = load(dir.path(), "doubling16.glb", &doubling(16)).unwrap();
    assert_eq!(mesh.mesh.positions.len(), 3 << 16);
}

#[test]
fn instances_of_large_meshes_are_refused_by_their_vertex_count() {
    let dir = tempfile::tempdir().unwrap();
    // 2^12 instances of a mesh declaring 2^14 vertices: 2^26 vertices, over MAX_VERTICES, refused
    // from the declared counts before a buffer is read.
    let (mut document, data) = triangle();
    document["accessors"][0]["count"] = json!(1 << 14);
    let mut nodes: Vec<Value> = (1..=12).map(|i| json!({"children": [i, i]})).collect();
    nodes.push(json!({"mesh": 0}));
    document["nodes"] = Value::Array(nodes);
    fails(
        dir.path(),
        "wide.glb",
        &glb(&document, &data),
        "the scene would give 67108864 vertices, more than the limit of 33554432 (MAX_VERTICES in sweepffd::limits)",
    );
}

#[test]
fn long_paths_below_shared_children_are_refused_by_the_node_instance_count() {
    let dir = tempfile::tempdir().unwrap();
    // 13 doubling levels (8192 instances, within the limit), then a chain of 600 nodes above
    // the mesh: each instance walks the chain, 4.9 million node instances in all.
    let (mut document, data) = triangle();
    let mut nodes: Vec<Value> = (1..=13).map(|i| json!({"children": [i, i]})).collect();
    nodes.extend((14..613).map(|i| json!({"children": [i]})));
    nodes.push(json!({"mesh": 0}));
    document["nodes"] = Value::Array(nodes);
    fails(
        dir.path(),
        "long.glb",
        &glb(&document, &data),
        "the scene would give 4923391 node instances, more than the limit of 4194304 (MAX_GLTF_NODE_INSTANCES in sweepffd::limits)",
    );
}

/// A `.gltf` of the triangle whose buffer has the URI `uri` (and the right byte length).
fn gltf_with_uri(uri: &str) -> Vec<u8> {
    let (mut document, _) = triangle();
    document["buffers"][0]["uri"] = json!(uri);
    serde_json::to_vec(&document).unwrap()
}

#[test]
fn buffer_uris_outside_the_folder_are_refused() {
    // Case 5: /etc/passwd, ../secret, /dev/zero, a FIFO and URLs were read.
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("model");
    fs::create_dir(&dir).unwrap();
    let (_, data) = triangle();
    fs::write(root.path().join("secret.bin"), &data).unwrap();
    let only = "only data URIs and relative paths inside the file's folder are read";
    let cases: Vec<(&str, String)> = vec![
        (
            "/etc/passwd",
            "buffer 0: uri \"/etc/passwd\" is an absolute path; only paths relative to the file's folder are read"
                .into(),
        ),
        (
            "/dev/zero",
            "buffer 0: uri \"/dev/zero\" is an absolute path; only paths relative to the file's folder are read".into(),
        ),
        ("../secret.bin", "buffer 0: uri \"../secret.bin\" leads outside the folder of the glTF file".into()),
        ("%2e%2e/secret.bin", "buffer 0: uri \"%2e%2e/secret.bin\" leads outside the folder of the glTF file".into()),
        (
            "%2Fetc%2Fpasswd",
            "buffer 0: uri \"%2Fetc%2Fpasswd\" is an absolute path; only paths relative to the file's folder are read"
                .into(),
        ),
        (
            "http://example.com/a.bin",
            format!("buffer 0: uri \"http://example.com/a.bin\" has the scheme \"http\"; {only}"),
        ),
        ("file:///etc/passwd", format!("buffer 0: uri \"file:///etc/passwd\" has the scheme \"file\"; {only}")),
        ("a%zz.bin", "buffer 0: uri \"a%zz.bin\": a malformed percent escape".into()),
    ];
    for (uri, message) in &cases {
        fails(&dir, "bad.gltf", &gltf_with_uri(uri), message);
    }
    // A link inside the folder that leads out of it, to a file or to a device.
    std::os::unix::fs::symlink(root.path().join("secret.bin"), dir.join("link.bin")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
    for uri in ["link.bin", "zero.bin"] {
        let message = format!("buffer 0: uri \"{uri}\" leads outside the folder of the glTF file");
        fails(&dir, "link.gltf", &gltf_with_uri(uri), &message);
    }
    // A FIFO or a folder inside the folder: not a regular file, refused without opening it.
    let fifo = dir.join("fifo.bin");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    fs::create_dir(dir.join("sub")).unwrap();
    for uri in ["fifo.bin", "sub"] {
        fails(&dir, "fifo.gltf", &gltf_with_uri(uri), &format!("buffer 0: uri \"{uri}\" does not name a regular file"));
    }
    // Nothing beside the input was written.
    let mut names: Vec<String> =
        fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    assert_eq!(names, ["bad.gltf", "fifo.bin", "fifo.gltf", "link.bin", "link.gltf", "sub", "zero.bin"]);
}

#[test]
fn relative_buffer_files_inside_the_folder_are_read_up_to_their_byte_length() {
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("sub dir")).unwrap();
    let (_, mut data) = triangle();
    let length = data.len();
    // Trailing bytes past byteLength are not read.
    data.extend([0xAB; 1000]);
    fs::write(dir.path().join("sub dir/data.bin"), &data).unwrap();
    let mesh = load(dir.path(), "ok.gltf", &gltf_with_uri("sub%20dir/data.bin")).unwrap();
    assert_eq!(mesh.mesh.positions[1], DVec3::X);
    // A link that stays inside the folder is followed.
    std::os::unix::fs::symlink(dir.path().join("sub dir/data.bin"), dir.path().join("inside.bin")).unwrap();
    let mesh = load(dir.path(), "inside.gltf", &gltf_with_uri("./sub%20dir/../inside.bin")).unwrap();
    assert_eq!(mesh.mesh.positions[2], DVec3::Y);
    // Written back, the buffer is embedded with its byteLength bytes only.
    let out = dir.path().join("out.gltf");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    let written: Value = serde_json::from_slice(&fs::read(&out).unwrap()).unwrap();
    let uri = written["buffers"][0]["uri"].as_str().unwrap();
    let embedded = STANDARD.decode(uri.split_once(',').unwrap().1).unwrap();
    assert_eq!(embedded, data[..length]);
    // A missing file names the uri.
    let error = load(dir.path(), "missing.gltf", &gltf_with_uri("nothing.bin")).unwrap_err();
    assert!(error.contains("missing.gltf: buffer 0: cannot read uri \"nothing.bin\": "), "{error}");
}

#[test]
fn image_uris_are_never_read() {
    let dir = tempfile::tempdir().unwrap();
    let (mut document, data) = triangle();
    document["images"] =
        json!([{"uri": "/etc/passwd"}, {"uri": "../../secret.png"}, {"uri": "http://example.com/a.png"}]);
    document["textures"] = json!([{"source": 0}]);
    let mesh = load(dir.path(), "images.glb", &glb(&document, &data)).unwrap();
    let out = dir.path().join("out.glb");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    let bytes = fs::read(&out).unwrap();
    assert!(!bytes.windows(5).any(|w| w == b"root:"), "nothing of /etc/passwd is embedded");
    let text = String::from_utf8_lossy(&bytes);
    assert!(text.contains("\"uri\":\"/etc/passwd\""), "the image URI is kept as it is");
}

#[test]
fn malformed_accessors_are_errors_not_panics() {
    // Case 6 and accessor bounds: each of these made the gltf crate panic, or could size an
    // allocation from the JSON alone.
    let dir = tempfile::tempdir().unwrap();
    type Edit = fn(&mut Value);
    let cases: [(&str, Edit, &str); 11] = [
        (
            "position_index.glb",
            |d| d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(9),
            "not a valid glTF file: mesh 0 primitive 0: POSITION is accessor 9 but the file has 4 accessors",
        ),
        (
            "float_indices.glb",
            |d| d["accessors"][3] = json!({"bufferView": 1, "componentType": 5126, "count": 3, "type": "SCALAR"}),
            "mesh 0 primitive 0: indices accessor 3 is FLOAT SCALAR, not an unsigned integer SCALAR",
        ),
        (
            "vec2_indices.glb",
            |d| d["accessors"][3]["type"] = json!("VEC2"),
            "mesh 0 primitive 0: indices accessor 3 is UNSIGNED_SHORT VEC2, not an unsigned integer SCALAR",
        ),
        (
            "int_positions.glb",
            |d| d["accessors"][0]["componentType"] = json!(5125),
            "mesh 0 primitive 0: POSITION is not float VEC3 (quantized positions are not supported)",
        ),
        (
            "offset.glb",
            |d| d["accessors"][0]["byteOffset"] = json!(4000),
            "accessor 0: its data needs 4036 bytes but buffer view 0 holds 36",
        ),
        (
            "huge_count.glb",
            |d| d["accessors"][3]["count"] = json!(u32::MAX),
            "the scene would give 1431655765 triangles, more than the limit of 67108864 (MAX_FACES in sweepffd::limits)",
        ),
        (
            "huge_points.glb",
            |d| {
                d["meshes"][0]["primitives"][0]["mode"] = json!(0);
                d["accessors"][3]["count"] = json!(100_000_000);
            },
            "accessor 3: its data needs 200000000 bytes but buffer view 3 holds 6",
        ),
        (
            "huge_point_count.glb",
            |d| {
                d["meshes"][0]["primitives"][0]["mode"] = json!(0);
                d["accessors"][3]["count"] = json!(u32::MAX);
            },
            "accessor 3 has 4294967295 elements, more than the limit of 201326592 (3 × MAX_FACES in sweepffd::limits)",
        ),
        (
            "view_past_buffer.glb",
            |d| d["bufferViews"][2]["byteLength"] = json!(4_000_000_000u64),
            "accessor 2: its buffer view needs 4000000072 bytes but buffer 0 holds 104",
        ),
        (
            "stride.glb",
            |d| d["bufferViews"][0]["byteStride"] = json!(4),
            "accessor 0: its buffer view's byteStride 4 is less than its element size 12",
        ),
        (
            "sparse_count.glb",
            |d| {
                d["accessors"][0] = json!({
                    "componentType": 5126, "count": 3, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0],
                    "sparse": {"count": 1000, "indices": {"bufferView": 3, "componentType": 5123}, "values": {"bufferView": 0}}
                });
            },
            "accessor 0: its sparse count 1000 is more than its count 3",
        ),
    ];
    for (name, edit, message) in cases {
        let (mut document, data) = triangle();
        edit(&mut document);
        fails(dir.path(), name, &glb(&document, &data), message);
    }
    // A sparse POSITION accessor without a buffer view declaring 2^32 − 1 elements is refused by
    // the vertex limit before anything is allocated.
    let (mut document, data) = triangle();
    document["accessors"][0] = json!({
        "componentType": 5126, "count": u32::MAX, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0],
        "sparse": {"count": 1, "indices": {"bufferView": 3, "componentType": 5123}, "values": {"bufferView": 0}}
    });
    document["meshes"][0]["primitives"][0].as_object_mut().unwrap().remove("indices");
    fails(
        dir.path(),
        "sparse_huge.glb",
        &glb(&document, &data),
        "the scene would give 4294967295 vertices, more than the limit of 33554432 (MAX_VERTICES in sweepffd::limits)",
    );
    // A GLB whose header and chunk lengths lie.
    fails(
        dir.path(),
        "header.glb",
        b"glTF\x02\0\0\0\xff\xff\xff\xff",
        "not a valid glTF file: the GLB header gives a length of 4294967295 bytes but the file has 12",
    );
}

#[test]
fn a_sparse_position_accessor_substitutes_its_values() {
    let dir = tempfile::tempdir().unwrap();
    let (mut document, mut data) = triangle();
    // Element 1 replaced by (5, 6, 7), stored after the index data.
    data.extend(f32_bytes(&[5.0, 6.0, 7.0]));
    data.extend([1u16, 0].iter().flat_map(|i| i.to_le_bytes()));
    document["buffers"][0]["byteLength"] = json!(data.len());
    document["bufferViews"].as_array_mut().unwrap().extend([
        json!({"buffer": 0, "byteOffset": 104, "byteLength": 12}),
        json!({"buffer": 0, "byteOffset": 116, "byteLength": 2}),
    ]);
    document["accessors"][0]["sparse"] =
        json!({"count": 1, "indices": {"bufferView": 5, "componentType": 5123}, "values": {"bufferView": 4}});
    let mesh = load(dir.path(), "sparse.glb", &glb(&document, &data)).unwrap();
    assert_eq!(mesh.mesh.positions, [DVec3::ZERO, DVec3::new(5.0, 6.0, 7.0), DVec3::Y]);
    // Two sparse indices that do not increase: 1, 0.
    document["accessors"][0]["sparse"]["count"] = json!(2);
    document["bufferViews"][5]["byteLength"] = json!(4);
    document["bufferViews"][4]["byteLength"] = json!(24);
    data.extend([0u8; 10]);
    document["buffers"][0]["byteLength"] = json!(data.len());
    fails(
        dir.path(),
        "sparse_order.glb",
        &glb(&document, &data),
        "accessor 0: sparse index 1 is 0: sparse indices must increase strictly and stay below the count 3",
    );
}

#[test]
fn non_finite_attributes_and_transforms_are_errors_naming_the_value() {
    let dir = tempfile::tempdir().unwrap();
    let patch = |at: usize, value: f32| {
        let (document, mut data) = triangle();
        data[at..at + 4].copy_from_slice(&value.to_le_bytes());
        glb(&document, &data)
    };
    fails(
        dir.path(),
        "position.glb",
        &patch(16, f32::NAN),
        "mesh 0 primitive 0: POSITION accessor 0 element 1 has the non-finite value NaN",
    );
    fails(
        dir.path(),
        "normal.glb",
        &patch(36 + 24, f32::NEG_INFINITY),
        "mesh 0 primitive 0: NORMAL accessor 1 element 2 has the non-finite value -inf",
    );
    fails(
        dir.path(),
        "uv.glb",
        &patch(72 + 4, f32::INFINITY),
        "mesh 0 primitive 0: TEXCOORD_0 accessor 2 element 0 has the non-finite value inf",
    );
    // JSON has no infinity, and a number beyond f32 (1e39) in a node's transform is refused
    // by the parser.
    type Edit = fn(&mut Value);
    let beyond: [(&str, Edit); 3] = [
        ("scale.glb", |d| d["nodes"][0]["scale"] = json!([1.0, 1e39, 1.0])),
        ("translation.glb", |d| d["nodes"][0]["translation"] = json!([-1e39, 0.0, 0.0])),
        ("matrix.glb", |d| {
            let mut m = vec![json!(0.0); 16];
            m[15] = json!(1e40);
            d["nodes"][0]["matrix"] = Value::Array(m);
        }),
    ];
    for (name, edit) in beyond {
        let (mut document, data) = triangle();
        edit(&mut document);
        let error = load(dir.path(), name, &glb(&document, &data)).unwrap_err();
        let prefix = format!(
            "{}: not a valid glTF file: number out of range at line 1 column ",
            dir.path().join(name).display()
        );
        assert!(error.starts_with(&prefix), "{error}");
    }
    // Nine nested scales of 1e38, each finite: their product, 1e342, overflows f64.
    let (mut document, data) = triangle();
    let mut nodes: Vec<Value> = (1..9).map(|i| json!({"children": [i], "scale": [1e38, 1e38, 1e38]})).collect();
    nodes.push(json!({"mesh": 0, "scale": [1e38, 1e38, 1e38]}));
    document["nodes"] = Value::Array(nodes);
    fails(dir.path(), "world.glb", &glb(&document, &data), "node 8: its world matrix overflows (a value of inf)");
    // A finite world matrix under which a position overflows.
    let (mut document, mut data) = triangle();
    data[12..16].copy_from_slice(&3e38f32.to_le_bytes());
    let mut nodes: Vec<Value> = (1..8).map(|i| json!({"children": [i], "scale": [1e38, 1e38, 1e38]})).collect();
    nodes.push(json!({"mesh": 0, "scale": [1e38, 1e38, 1e38]}));
    document["nodes"] = Value::Array(nodes);
    fails(
        dir.path(),
        "overflow.glb",
        &glb(&document, &data),
        "mesh 0 primitive 0: POSITION accessor 0 element 1 overflows under the world matrix of node 7 (a coordinate of inf)",
    );
}

#[test]
fn the_glb_writers_refuse_coordinates_beyond_f32_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mut faces = Faces::new();
    faces.push(&[0, 1, 2]);
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let mesh = LoadedMesh::from(Mesh::from_parts(positions.clone(), faces, Vec::new()).unwrap());
    let far = vec![DVec3::ZERO, DVec3::new(1e39, 0.0, 0.0), DVec3::Y];
    for name in ["generic.glb", "generic.gltf"] {
        // `Mesh::save` refuses it before any writer runs.
        let out = dir.path().join(name);
        let error = mesh.save(&out, &far).unwrap_err().to_string();
        let expected = format!(
            "{}: vertex 1 has the coordinate 1e39, which does not fit in the f32 this format stores; nothing was written",
            out.display()
        );
        assert_eq!(error, expected);
        assert!(!out.exists());
    }
    // The faithful writer stores node-local coordinates: a world coordinate that fits in f32
    // can overflow it under a node that scales down.
    let (mut document, data) = triangle();
    document["nodes"] = json!([{"mesh": 0, "scale": [0.01, 0.01, 0.01]}]);
    let mesh = load(dir.path(), "in.glb", &glb(&document, &data)).unwrap();
    let out = dir.path().join("out.glb");
    let near_max = vec![DVec3::ZERO, DVec3::new(1e37, 0.0, 0.0), DVec3::Y];
    let error = mesh.save(&out, &near_max).unwrap_err().to_string();
    // 1e37 / 0.01f32 (the scale is stored as f32).
    let expected = format!(
        "cannot write {}: vertex 1: its node-local coordinate 1.0000000223517425e39 does not fit in f32",
        out.display()
    );
    assert_eq!(error, expected);
    assert!(!out.exists());
    let mut names: Vec<PathBuf> = fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().path()).collect();
    names.sort();
    assert_eq!(names, [dir.path().join("in.glb")], "no temporary file left");
}

/// The triangle drawn by two nodes, node 1's with the extra local transform `second`.
fn two_instances(second: Value) -> Vec<u8> {
    let (mut document, data) = triangle();
    let mut node = json!({"mesh": 0});
    node.as_object_mut().unwrap().extend(second.as_object().unwrap().clone());
    document["nodes"] = json!([{"mesh": 0, "translation": [0.0, 0.0, 2.0]}, node]);
    document["scenes"] = json!([{"nodes": [0, 1]}]);
    glb(&document, &data)
}

/// Asserts that `path` reads back with `expected` positions, within f32 rounding.
fn reads_back(path: &Path, expected: &[DVec3]) {
    let read = Mesh::load(path).unwrap();
    assert_eq!(read.positions.len(), expected.len());
    for (vertex, (a, b)) in read.positions.iter().zip(expected).enumerate() {
        let error = (*a - *b).abs().max_element();
        assert!(error <= 1e-6, "vertex {vertex} reads back as {a}, written as {b}");
    }
}

#[test]
fn instances_of_one_position_accessor_write_only_when_they_moved_alike() {
    let dir = tempfile::tempdir().unwrap();
    let bytes = two_instances(json!({"translation": [5.0, 0.0, 0.0]}));
    let mesh = load(dir.path(), "in.glb", &bytes).unwrap();
    assert_eq!(mesh.mesh.positions.len(), 6, "one copy of the triangle per node");
    let shift = DVec3::new(0.5, 0.25, -1.0);
    // Under translated nodes a world translation is the same local translation for both.
    let both: Vec<DVec3> = mesh.mesh.positions.iter().map(|&p| p + shift).collect();
    let out = dir.path().join("both.glb");
    mesh.save(&out, &both).unwrap();
    reads_back(&out, &both);
    // The second instance alone: the one accessor cannot hold both triangles.
    let second: Vec<DVec3> =
        mesh.mesh.positions.iter().enumerate().map(|(v, &p)| if v < 3 { p } else { p + shift }).collect();
    for name in ["second.glb", "second.gltf"] {
        let out = dir.path().join(name);
        let error = mesh.save(&out, &second).unwrap_err().to_string();
        let expected = format!(
            "cannot write {}: mesh 0: nodes 0 and 1 draw POSITION accessor 0 but moved it differently (vertex 3, \
             element 0 of the accessor); a glTF file shares one POSITION accessor between these nodes, so it cannot \
             hold both: write another format (.obj, .ply, .off), which keeps each instance's vertices",
            out.display()
        );
        assert_eq!(error, expected);
        assert!(!out.exists());
    }
    // Those formats keep them.
    let out = dir.path().join("second.ply");
    mesh.save(&out, &second).unwrap();
    reads_back(&out, &second);
}

#[test]
fn unmoved_instances_of_one_position_accessor_still_write() {
    let dir = tempfile::tempdir().unwrap();
    // A turned and scaled second node: unmoved vertices keep their bytes.
    let bytes = two_instances(json!({"rotation": [0.0, 0.0, 0.38268343, 0.9238795], "scale": [2.0, 2.0, 2.0]}));
    let mesh = load(dir.path(), "in.glb", &bytes).unwrap();
    let out = dir.path().join("out.glb");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    reads_back(&out, &mesh.mesh.positions);
    let mut names: Vec<PathBuf> = fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().path()).collect();
    names.sort();
    assert_eq!(names, [dir.path().join("in.glb"), out]);
}

/// The triangle with vertex 2 at y = 4e6, drawn by two nodes with the local transforms
/// `first` and `second`.
fn far_vertex_instances(first: Value, second: Value) -> Vec<u8> {
    let (mut document, mut data) = triangle();
    data[24..36].copy_from_slice(&f32_bytes(&[0.0, 4.0e6, 0.0]));
    document["accessors"][0]["max"] = json!([1.0, 4.0e6, 0.0]);
    let node = |extra: Value| {
        let mut node = json!({"mesh": 0});
        node.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
        node
    };
    document["nodes"] = json!([node(first), node(second)]);
    document["scenes"] = json!([{"nodes": [0, 1]}]);
    glb(&document, &data)
}

#[test]
fn one_far_element_does_not_let_instances_moved_apart_through() {
    // Issue 12 (fuzz/regressions/write_round_trip/fuzz_instanced_mutated.glb): the allowed
    // disagreement was 4 f32 ulps of the accessor's largest coordinate, for every element, so
    // one far element (here 4e6: 1.9 local units) let a later instance that moved apart by a
    // fraction of a unit be written, and it read back where the first one was written.
    let dir = tempfile::tempdir().unwrap();
    let bytes = far_vertex_instances(json!({"translation": [0.0, 0.0, 2.0]}), json!({"scale": [2.0, 2.0, 2.0]}));
    let mesh = load(dir.path(), "in.glb", &bytes).unwrap();
    assert_eq!(mesh.mesh.positions[5], DVec3::new(0.0, 8.0e6, 0.0), "the far vertex, second instance");
    // A world translation d is d locally under node 0 but d / 2 under node 1 (scaled by 2).
    let shift = DVec3::new(0.5, 0.25, -1.0);
    let moved: Vec<DVec3> = mesh.mesh.positions.iter().map(|&p| p + shift).collect();
    for name in ["apart.glb", "apart.gltf"] {
        let out = dir.path().join(name);
        let error = mesh.save(&out, &moved).err().map(|e| e.to_string());
        let expected = format!(
            "cannot write {}: mesh 0: nodes 0 and 1 draw POSITION accessor 0 but moved it differently (vertex 3, \
             element 0 of the accessor); a glTF file shares one POSITION accessor between these nodes, so it cannot \
             hold both: write another format (.obj, .ply, .off), which keeps each instance's vertices",
            out.display()
        );
        assert_eq!(error, Some(expected), "{name}");
        assert!(!out.exists());
    }
    // Moved alike, the far element stays writable: a translation under translated nodes, and
    // a turn about z under nodes turned about z and scaled uniformly (their local motion is
    // the same turn), whose stored coordinates are rounded to f32.
    let bytes = far_vertex_instances(json!({"translation": [0.0, 0.0, 2.0]}), json!({"translation": [5.0, 0.0, 0.0]}));
    let mesh = load(dir.path(), "alike.glb", &bytes).unwrap();
    let moved: Vec<DVec3> = mesh.mesh.positions.iter().map(|&p| p + shift).collect();
    let out = dir.path().join("translated.glb");
    mesh.save(&out, &moved).unwrap();
    reads_back(&out, &moved);
    let bytes = far_vertex_instances(
        json!({"rotation": [0.0, 0.0, 0.2588190, 0.9659258]}),
        json!({"rotation": [0.0, 0.0, -0.6087614, 0.7933533], "scale": [2.0, 2.0, 2.0]}),
    );
    let mesh = load(dir.path(), "turned.glb", &bytes).unwrap();
    for degrees in [1.0f64, 17.0, 30.0, 123.0, 271.5] {
        let turn = glam::DQuat::from_rotation_z(degrees.to_radians());
        let moved: Vec<DVec3> = mesh.mesh.positions.iter().map(|&p| turn * p).collect();
        let out = dir.path().join(format!("turned{degrees}.glb"));
        mesh.save(&out, &moved).unwrap_or_else(|e| panic!("turned by {degrees}°: {e}"));
        let read = Mesh::load(&out).unwrap();
        for (vertex, (a, b)) in read.positions.iter().zip(&moved).enumerate() {
            let error = (*a - *b).abs().max_element();
            assert!(error <= 2.0 * f64::from(f32::EPSILON) * b.length(), "vertex {vertex}: {a} for {b}");
        }
    }
}

/// Runs `sweepffd fit --mesh <name> --out rig.json` on `bytes` in a fresh folder, with
/// `RUST_BACKTRACE=1`, expecting failure; returns stderr.
fn fit_fails(name: &str, bytes: &[u8]) -> String {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join(name), bytes).unwrap();
    let output = common::sweepffd(dir.path())
        .args(["fit", "--mesh", name, "--out", "rig.json"])
        .env("RUST_BACKTRACE", "1")
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(output.stdout.is_empty());
    assert!(!dir.path().join("rig.json").exists());
    String::from_utf8(output.stderr).unwrap()
}

#[test]
fn only_the_error_reaches_stderr() {
    // Case 6: the gltf crate's panic message (and backtrace) used to precede the error.
    let (mut document, data) = triangle();
    document["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(9);
    assert_eq!(
        fit_fails("bad.glb", &glb(&document, &data)),
        "error: bad.glb: not a valid glTF file: mesh 0 primitive 0: POSITION is accessor 9 but the file has 4 accessors\n"
    );
    let (mut document, data) = triangle();
    document["accessors"][3]["componentType"] = json!(5126);
    assert_eq!(
        fit_fails("float.glb", &glb(&document, &data)),
        "error: float.glb: mesh 0 primitive 0: indices accessor 3 is FLOAT SCALAR, not an unsigned integer SCALAR\n"
    );
    assert_eq!(
        fit_fails("deep.glb", &chain(20_000)),
        "error: deep.glb: node 1025 is at depth 1025 of the node hierarchy, deeper than the limit of 1024 (MAX_GLTF_NODE_DEPTH in sweepffd::limits)\n"
    );
}

/// A triangle whose NORMAL is POSITION's own accessor, or a second accessor on POSITION's
/// buffer view: writing the normals back would overwrite the positions (the file read back
/// 4.2 off). The write is refused naming both accessors, and nothing is written; interleaved
/// attributes in one buffer view (no byte shared) still write faithfully.
#[test]
fn aliased_normals_are_refused_naming_the_accessors() {
    let dir = tempfile::tempdir().unwrap();
    let moved = |mesh: &LoadedMesh| -> Vec<DVec3> { mesh.mesh.positions.iter().map(|&p| p * 1.5).collect() };
    for (case, normal) in [("same accessor", 0), ("same buffer view", 1)] {
        let (mut document, data) = triangle();
        document["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = json!(normal);
        document["accessors"][1]["bufferView"] = json!(0);
        let mesh = load(dir.path(), "aliased.glb", &glb(&document, &data)).unwrap();
        let out = dir.path().join("out.glb");
        let error = mesh.save(&out, &moved(&mesh)).unwrap_err().to_string();
        assert_eq!(
            error,
            format!(
                "cannot write {}: accessor 0 (POSITION) and accessor {normal} (NORMAL) share bytes of buffer 0: writing \
                 one would overwrite the other (write .obj, .ply or .off instead)",
                out.display()
            ),
            "{case}"
        );
        assert!(!out.exists(), "{case}");
    }
    // POSITION and NORMAL interleaved at a stride of 24 share a buffer view but no byte.
    let mut data = Vec::new();
    for (p, n) in
        [([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]), ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]), ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0])]
    {
        data.extend(f32_bytes(&p));
        data.extend(f32_bytes(&n));
    }
    let (mut document, _) = triangle();
    document["meshes"][0]["primitives"][0]["attributes"] = json!({"POSITION": 0, "NORMAL": 1});
    document["meshes"][0]["primitives"][0].as_object_mut().unwrap().remove("indices");
    document["accessors"][1]["bufferView"] = json!(0);
    document["accessors"][1]["byteOffset"] = json!(12);
    document["bufferViews"] = json!([{"buffer": 0, "byteOffset": 0, "byteLength": 72, "byteStride": 24}]);
    document["buffers"] = json!([{"byteLength": 72}]);
    document["accessors"].as_array_mut().unwrap().truncate(2);
    let mesh = load(dir.path(), "interleaved.glb", &glb(&document, &data)).unwrap();
    let out = dir.path().join("interleaved-out.glb");
    let positions = moved(&mesh);
    mesh.save(&out, &positions).unwrap();
    reads_back(&out, &positions);
}
