//! Allocation bombs: small files that claim (or, through sharing, make) huge counts. Under a
//! 4 GB address-space limit (`ulimit -v 4000000`) each must be refused with an error (exit
//! status 1, `error: ` naming the file, no panic), never abort the process, and leave no
//! output behind.

#[path = "../../../tests/common/gltf_graphs.rs"]
mod gltf_graphs;

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use sweepffd::formats::LoadedMesh;
use sweepffd::synthetic::{Tube, tube_rig};

/// How long a refusal may take before the test gives up on the process.
const DEADLINE: Duration = Duration::from_secs(120);

/// A folder with a small tube mesh (`tube.obj`) and its rig (`rig.json`), the valid halves
/// of the commands below.
fn scene() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let tube = Tube { rings: 6, around: 8, length: 3.0, radius: 0.4 };
    let mesh = LoadedMesh::from(tube.mesh());
    mesh.save(&dir.path().join("tube.obj"), &mesh.mesh.positions).unwrap();
    std::fs::write(dir.path().join("rig.json"), tube_rig(&tube, 3, 8).to_document().to_json()).unwrap();
    dir
}

/// Runs `sweepffd args` in `dir` under the address-space limit; asserts exit status 1 (not a
/// signal), stderr exactly `error: <expected>`, and that `out` was not written.
fn assert_refused(dir: &Path, args: &[&str], expected: &str, out: &str) {
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(r#"ulimit -v 4000000; exec "$0" "$@""#)
        .arg(env!("CARGO_BIN_EXE_sweepffd"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > DEADLINE {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("sweepffd {}: still running after {DEADLINE:?}", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut stderr = String::new();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    let command = format!("sweepffd {}", args.join(" "));
    assert_eq!(status.code(), Some(1), "{command}: {status} after {:?}, stderr «{stderr}»", start.elapsed());
    assert_eq!(stderr, format!("error: {expected}\n"), "{command}");
    assert!(!dir.join(out).exists(), "{command}: {out} was written");
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with('.'))
        .collect();
    assert!(leftovers.is_empty(), "{command}: temporary files left: {leftovers:?}");
}

/// `deform` of the mesh file `name` (written with `bytes`) by the tube's rig, to `out.obj`.
fn deform_refuses(name: &str, bytes: &[u8], expected: &str) {
    let dir = scene();
    std::fs::write(dir.path().join(name), bytes).unwrap();
    let args = ["deform", "--mesh", name, "--rig", "rig.json", "--pose", "rig.json", "--out", "out.obj"];
    assert_refused(dir.path(), &[&args[..], &["--backend", "cpu"]].concat(), expected, "out.obj");
}

const MAX_U64: &str = "18446744073709551615";

#[test]
fn ply_vertex_count_of_2_pow_64_minus_1() {
    let header = format!(
        "ply\nformat ascii 1.0\nelement vertex {MAX_U64}\nproperty float x\nproperty float y\nproperty float z\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    );
    deform_refuses(
        "count.ply",
        header.as_bytes(),
        "count.ply:3: element \"vertex\": 18446744073709551615 vertices, over the limit of 33554432 (limits::MAX_VERTICES)",
    );
}

#[test]
fn ply_face_count_of_2_pow_64_minus_1() {
    let header = format!(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
         element face {MAX_U64}\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    );
    deform_refuses(
        "faces.ply",
        header.as_bytes(),
        "faces.ply:7: element \"face\": 18446744073709551615 faces, over the limit of 67108864 (limits::MAX_FACES)",
    );
}

#[test]
fn binary_ply_claiming_2_pow_32_faces() {
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nelement face 4294967296\nproperty list uchar int vertex_indices\nend_header\n"
        .to_vec();
    for c in [0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        bytes.extend_from_slice(&c.to_le_bytes());
    }
    bytes.push(3);
    for i in 0i32..3 {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    deform_refuses(
        "binary.ply",
        &bytes,
        "binary.ply:7: element \"face\": 4294967296 faces, over the limit of 67108864 (limits::MAX_FACES)",
    );
}

#[test]
fn off_counts_of_2_pow_64_minus_1() {
    deform_refuses(
        "vertices.off",
        format!("OFF\n{MAX_U64} 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").as_bytes(),
        "vertices.off:2: 18446744073709551615 vertices, over the limit of 33554432 (limits::MAX_VERTICES)",
    );
    deform_refuses(
        "faces.off",
        format!("OFF\n3 {MAX_U64} 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").as_bytes(),
        "faces.off:2: 18446744073709551615 faces, over the limit of 67108864 (limits::MAX_FACES)",
    );
}

#[test]
fn rig_key_with_a_million_radii() {
    let dir = scene();
    let radii = vec!["0.4"; 1_000_000].join(",");
    let key = |z: f64| format!(r#"{{"center":[0,0,{z}],"rotation":[0,0,0,1],"radii":[{radii}]}}"#);
    let rig = format!(
        r#"{{"format":"sweepffd-rig","version":1,"sweeps":[{{"name":"tube","vertices":"all","keys":[{},{}]}}]}}"#,
        key(0.0),
        key(3.0)
    );
    assert!(rig.len() < 10_000_000, "{} bytes", rig.len());
    std::fs::write(dir.path().join("radii.json"), rig).unwrap();
    let args = ["bind", "--mesh", "tube.obj", "--rig", "radii.json", "--out", "out.bin", "--backend", "cpu"];
    assert_refused(
        dir.path(),
        &args,
        "radii.json: not a valid rig file: sweeps[0].keys[0].radii: more than 4096 values (the most a key may have) at line 1 column 16523",
        "out.bin",
    );
}

#[test]
fn gltf_node_chain_20000_deep() {
    deform_refuses(
        "deep.glb",
        &gltf_graphs::triangle_glb(&gltf_graphs::chain(20_000)),
        "deep.glb: node 1025 is at depth 1025 of the node hierarchy, deeper than the limit of 1024 (MAX_GLTF_NODE_DEPTH in sweepffd::limits)",
    );
}

#[test]
fn gltf_graph_doubling_over_30_levels() {
    deform_refuses(
        "wide.glb",
        &gltf_graphs::triangle_glb(&gltf_graphs::doubling(30)),
        "wide.glb: the scene would give 1073741824 mesh instances, more than the limit of 65536 (MAX_GLTF_INSTANCES in sweepffd::limits)",
    );
}

#[test]
fn gltf_buffer_reading_dev_zero() {
    let dir = scene();
    let gltf = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "buffers":[{"byteLength":36,"uri":"/dev/zero"}],"bufferViews":[{"buffer":0,"byteLength":36}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[0,0,0]}]}"#;
    std::fs::write(dir.path().join("zero.gltf"), gltf).unwrap();
    let args = ["deform", "--mesh", "zero.gltf", "--rig", "rig.json", "--pose", "rig.json", "--out", "out.obj"];
    assert_refused(
        dir.path(),
        &[&args[..], &["--backend", "cpu"]].concat(),
        "zero.gltf: buffer 0: uri \"/dev/zero\" is an absolute path; only paths relative to the file's folder are read",
        "out.obj",
    );
}
