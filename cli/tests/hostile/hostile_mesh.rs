//! Hostile OBJ, PLY and OFF files, and positions no format can hold: every case is an error
//! that names the file (and the line, vertex, element or property), never a panic, never a
//! non-finite value passed through, and never an output file.

use crate::common;

use std::fs;
use std::path::{Path, PathBuf};

use glam::DVec3;
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::{Faces, Mesh};

/// Parses `bytes` as the file `name`, expecting an error, and returns its message.
fn parse_error(name: &str, bytes: impl Into<Vec<u8>>) -> String {
    match Mesh::parse(Path::new(name), bytes.into()) {
        Ok(mesh) => panic!("{name} was accepted ({} vertices)", mesh.positions.len()),
        Err(e) => e.to_string(),
    }
}

/// A binary little-endian PLY file of this header (without `ply`, `format` and `end_header`
/// lines) and these bytes after it.
fn binary_ply(header: &str, body: &[u8]) -> Vec<u8> {
    let mut bytes = format!("ply\nformat binary_little_endian 1.0\n{header}end_header\n").into_bytes();
    bytes.extend_from_slice(body);
    bytes
}

/// The little-endian bytes of these f32 values.
fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

const XYZ: &str = "property float x\nproperty float y\nproperty float z\n";
const TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
const TRIANGLE_OFF: &str = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

// Case 2: values no output can hold.

/// A triangle built in code whose vertex 1 is at `x` on the x axis.
fn triangle_at(x: f64) -> (LoadedMesh, Vec<DVec3>) {
    let mut faces = Faces::new();
    faces.push(&[0, 1, 2]);
    let mesh = LoadedMesh::from(Mesh::from_parts(vec![DVec3::ZERO, DVec3::X, DVec3::Y], faces, Vec::new()).unwrap());
    let moved = vec![DVec3::ZERO, DVec3::new(x, 0.0, 0.0), DVec3::Y];
    (mesh, moved)
}

/// Saves `positions` to `name` in a fresh folder, expecting an error; asserts nothing was
/// written and returns the message with the folder left out.
fn save_error(mesh: &LoadedMesh, name: &str, positions: &[DVec3]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join(name);
    let message = mesh.save(&out, positions).unwrap_err().to_string();
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0, "{name}: something was written");
    message.replace(&format!("{}/", dir.path().display()), "")
}

#[test]
fn a_coordinate_over_f32_is_refused_by_every_f32_writer() {
    let (mesh, moved) = triangle_at(1e39);
    for name in ["out.ply", "out.glb", "out.gltf"] {
        assert_eq!(
            save_error(&mesh, name, &moved),
            format!(
                "{name}: vertex 1 has the coordinate 1e39, which does not fit in the f32 this format stores; nothing was written"
            )
        );
    }
}

#[test]
fn a_coordinate_over_f32_is_refused_by_the_faithful_float_ply_writer() {
    let ply =
        binary_ply(&format!("element vertex 3\n{XYZ}"), &f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]));
    let mesh = LoadedMesh::parse(Path::new("in.ply"), ply).unwrap();
    let mut moved = mesh.mesh.positions.clone();
    moved[2].z = -1e39;
    assert_eq!(
        save_error(&mesh, "out.ply", &moved),
        "out.ply: vertex 2 has the coordinate -1e39, which does not fit in the f32 this format stores; nothing was written"
    );
}

#[test]
fn f64_writers_keep_a_coordinate_over_f32() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, moved) = triangle_at(1e39);
    for name in ["out.obj", "out.off"] {
        let out = dir.path().join(name);
        mesh.save(&out, &moved).unwrap();
        assert_eq!(Mesh::load(&out).unwrap().positions, moved, "{name}");
    }
    let doubles = "property double x\nproperty double y\nproperty double z\n";
    let ply = format!("ply\nformat ascii 1.0\nelement vertex 3\n{doubles}end_header\n0 0 0\n1 0 0\n0 1 0\n");
    let mesh = LoadedMesh::parse(Path::new("in.ply"), ply.into_bytes()).unwrap();
    let out = dir.path().join("out.ply");
    mesh.save(&out, &moved).unwrap();
    assert_eq!(Mesh::load(&out).unwrap().positions, moved);
}

#[test]
fn non_finite_coordinates_are_refused_by_every_writer() {
    let (mesh, mut moved) = triangle_at(f64::INFINITY);
    for name in ["out.obj", "out.off", "out.ply", "out.glb"] {
        assert_eq!(
            save_error(&mesh, name, &moved),
            format!("{name}: vertex 1 has the coordinate inf, which is not finite; nothing was written")
        );
    }
    moved[1].x = 0.5;
    moved[2].y = f64::NAN;
    let mesh = LoadedMesh::parse(Path::new("in.obj"), TRIANGLE_OBJ.as_bytes().to_vec()).unwrap();
    assert_eq!(
        save_error(&mesh, "out.obj", &moved),
        "out.obj: vertex 2 has the coordinate NaN, which is not finite; nothing was written"
    );
}

/// The rig of the deformation test: one sweep along z owning every vertex, radius `radius`.
fn tube_rig(radius: &str) -> String {
    let key = |z: u32| {
        format!(
            r#"{{"center": [0, 0, {z}], "rotation": [0, 0, 0, 1], "radii": [{radius}, {radius}, {radius}, {radius}]}}"#
        )
    };
    format!(
        "{{\"format\": \"sweepffd-rig\", \"version\": 1, \"sweeps\": [\n  {{\"name\": \"tube\", \"vertices\": \"all\", \"keys\": [{}, {}]}}\n]}}\n",
        key(0),
        key(2)
    )
}

#[test]
fn deform_refuses_a_ply_output_that_overflows_f32() {
    // Poses cannot push a coordinate past f32 (rig coordinates and radii stay within 1e15), so
    // the overflow comes from the input: an OBJ (which stores f64) vertex the rig does not own,
    // at 1e39, written to a PLY of f32.
    let dir = tempfile::tempdir().unwrap();
    let square = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    let mut obj = String::new();
    for z in [0.0, 2.0] {
        for p in square {
            obj.push_str(&format!("v {} {} {z}\n", p[0], p[1]));
        }
    }
    obj.push_str("v 1e39 0 0\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
    fs::write(dir.path().join("in.obj"), obj).unwrap();
    let owned = |radius: &str| {
        tube_rig(radius).replace(r#""vertices": "all""#, r#""vertices": {"indices": [0, 1, 2, 3, 4, 5, 6, 7]}"#)
    };
    fs::write(dir.path().join("rig.json"), owned("1")).unwrap();
    fs::write(dir.path().join("pose.json"), owned("2")).unwrap();
    let args = ["deform", "--mesh", "in.obj", "--rig", "rig.json", "--pose", "pose.json", "--out", "out.ply"];
    let output = common::sweepffd(dir.path()).args(args).args(["--backend", "cpu"]).output().unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert_eq!(
        stderr,
        "error: out.ply: vertex 8 has the coordinate 1e39, which does not fit in the f32 this format stores; nothing was written\n"
    );
    assert!(!dir.path().join("out.ply").exists());
    let mut names: Vec<PathBuf> = fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().path()).collect();
    names.sort();
    assert_eq!(names.len(), 3, "{names:?}");
}

// Case 10: non-finite values in any field a reader accepts.

#[test]
fn obj_non_finite_normals_texture_coordinates_and_w_are_errors_at_their_line() {
    let cases = [
        ("vn nan 0 1\n", "m.obj:5: normal coordinate \"nan\" is not finite"),
        ("vt 0.5 inf\n", "m.obj:5: texture coordinate \"inf\" is not finite"),
        ("vp 0.5 1e999\n", "m.obj:5: parameter-space coordinate \"1e999\" is not finite"),
        ("v 0 0 1 nan\n", "m.obj:5: vertex value \"nan\" is not finite"),
        ("v 0 0 1 0.5 -infinity 0.5\n", "m.obj:5: vertex value \"-infinity\" is not finite"),
        ("vt 0.5 half\n", "m.obj:5: texture coordinate \"half\" is not a number"),
        ("v 0 0 1 red\n", "m.obj:5: vertex value \"red\" is not a number"),
    ];
    for (line, message) in cases {
        assert_eq!(parse_error("m.obj", format!("{TRIANGLE_OBJ}{line}")), message, "{line:?}");
    }
    let fine = format!("{TRIANGLE_OBJ}vt 0.5 0.5 # uv\nvn 0 0 1\nv 0 0 1 1.0\nusemtl inf\n");
    assert_eq!(Mesh::parse(Path::new("m.obj"), fine.into_bytes()).unwrap().positions.len(), 4);
}

#[test]
fn off_non_finite_header_counts_and_values_are_errors_at_their_line() {
    let cases = [
        ("OFF\n3 1 inf\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "m.off:2: edge count \"inf\" is not a number"),
        ("OFF\ninf 1 0\n", "m.off:2: vertex count \"inf\" is not a number"),
        (
            "NOFF\n3 1 0\n0 0 0 0 0 nan\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
            "m.off:3: vertex 0 has the non-finite value \"nan\"",
        ),
        (
            "COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 1 1e400 1\n0 1 0 1 1 1\n3 0 1 2\n",
            "m.off:4: vertex 1 has the non-finite value \"1e400\"",
        ),
        ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 inf 0.5\n", "m.off:6: face 0 has the non-finite value \"inf\""),
        ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 red\n", "m.off:6: face colour value \"red\" is not a number"),
    ];
    for (text, message) in cases {
        assert_eq!(parse_error("m.off", text), message, "{text:?}");
    }
}

#[test]
fn ply_non_finite_values_of_any_float_property_name_element_and_property() {
    let header = format!("element vertex 2\n{XYZ}property float nx\nproperty double quality\n");
    let body = [f32_bytes(&[0.0, 0.0, 0.0, f32::NAN]), 1.0_f64.to_le_bytes().to_vec()].concat();
    let body = [body.clone(), f32_bytes(&[1.0, 0.0, 0.0, 0.0]), f64::INFINITY.to_le_bytes().to_vec()].concat();
    assert_eq!(
        parse_error("m.ply", binary_ply(&header, &body)),
        "m.ply: element \"vertex\" entry 0, property \"nx\": the value NaN is not finite"
    );
    let body = [f32_bytes(&[0.0; 4]), 1.0_f64.to_le_bytes().to_vec(), f32_bytes(&[1.0, 0.0, 0.0, 0.0])].concat();
    let body = [body, f64::NEG_INFINITY.to_le_bytes().to_vec()].concat();
    assert_eq!(
        parse_error("m.ply", binary_ply(&header, &body)),
        "m.ply: element \"vertex\" entry 1, property \"quality\": the value -inf is not finite"
    );
    // ASCII has no NaN, but a number too large for a float reads as infinity.
    let text = format!(
        "ply\nformat ascii 1.0\nelement vertex 1\n{XYZ}element extra 1\nproperty list uchar float w\nend_header\n0 0 0\n2 1 1e39\n"
    );
    assert_eq!(
        parse_error("m.ply", text),
        "m.ply: element \"extra\" entry 0, property \"w\": the value inf is not finite"
    );
    let text = format!("ply\nformat ascii 1.0\nelement vertex 1\n{XYZ}end_header\n0 1e39 0\n");
    assert_eq!(parse_error("m.ply", text), "m.ply: vertex 0 has a non-finite coordinate");
}

// Case 11: a PLY property declared twice.

#[test]
fn ply_duplicated_property_or_element_is_an_error_naming_it() {
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty float x\nend_header\n0 0 0 5\n";
    assert_eq!(parse_error("m.ply", text), "m.ply:7: element \"vertex\" declares property \"x\" twice");
    let text =
        format!("ply\nformat ascii 1.0\nelement vertex 1\n{XYZ}element vertex 1\n{XYZ}end_header\n0 0 0\n0 0 0\n");
    assert_eq!(parse_error("m.ply", text), "m.ply:7: element \"vertex\" is declared twice");
}

// Allocation bombs: counts that must never size an allocation.

#[test]
fn ply_header_counts_over_the_limits_are_refused_before_reading() {
    let bomb = binary_ply(&format!("element vertex 18446744073709551615\n{XYZ}"), &[0; 12]);
    assert_eq!(
        parse_error("m.ply", bomb),
        "m.ply:3: element \"vertex\": 18446744073709551615 vertices, over the limit of 33554432 (limits::MAX_VERTICES)"
    );
    let bomb = binary_ply(
        &format!("element vertex 1\n{XYZ}element face 18446744073709551615\nproperty list uchar int vertex_indices\n"),
        &[0; 12],
    );
    assert_eq!(
        parse_error("m.ply", bomb),
        "m.ply:7: element \"face\": 18446744073709551615 faces, over the limit of 67108864 (limits::MAX_FACES)"
    );
    let bomb = binary_ply(&format!("element vertex 1\n{XYZ}element nothing 1000000\n"), &[0; 12]);
    assert_eq!(parse_error("m.ply", bomb), "m.ply:7: element \"nothing\" has 1000000 entries but no property");
}

#[test]
fn ply_face_of_too_many_corners_is_refused() {
    let header = format!("element vertex 3\n{XYZ}element face 1\nproperty list uint int vertex_indices\n");
    let mut body = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let corners = 65_537_u32;
    body.extend_from_slice(&corners.to_le_bytes());
    body.extend((0..corners).flat_map(|i| ((i % 3) as i32).to_le_bytes()));
    assert_eq!(
        parse_error("m.ply", binary_ply(&header, &body)),
        "m.ply: 65537 vertices in one face, over the limit of 65536 (limits::MAX_FACE_CORNERS)"
    );
    // A list count far past the data ends the file, it sizes nothing.
    let mut body = f32_bytes(&[0.0; 9]);
    body.extend_from_slice(&u32::MAX.to_le_bytes());
    body.extend_from_slice(&[0; 12]);
    assert!(parse_error("m.ply", binary_ply(&header, &body)).starts_with("m.ply: not a valid PLY file: "));
}

#[test]
fn off_counts_over_the_limits_are_refused_at_the_counts_line() {
    assert_eq!(
        parse_error("m.off", "OFF\n18446744073709551615 1 0\n0 0 0\n"),
        "m.off:2: 18446744073709551615 vertices, over the limit of 33554432 (limits::MAX_VERTICES)"
    );
    assert_eq!(
        parse_error("m.off", "OFF\n3 18446744073709551615 0\n0 0 0\n"),
        "m.off:2: 18446744073709551615 faces, over the limit of 67108864 (limits::MAX_FACES)"
    );
    assert_eq!(
        parse_error("m.off", "OFF\n18446744073709551616 1 0\n"),
        "m.off:2: vertex count \"18446744073709551616\" is not a number"
    );
    assert_eq!(
        parse_error("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4294967295 0 1 2\n"),
        "m.off:6: 4294967295 vertices in one face, over the limit of 65536 (limits::MAX_FACE_CORNERS)"
    );
}

#[test]
fn obj_face_of_too_many_corners_is_refused_at_its_line() {
    let face: String = (0..65_537).map(|i| format!(" {}", i % 3 + 1)).collect();
    assert_eq!(
        parse_error("m.obj", format!("{TRIANGLE_OBJ}f{face}\n")),
        "m.obj:5: 65537 vertices in one face, over the limit of 65536 (limits::MAX_FACE_CORNERS)"
    );
}

// Anything else a hand-made file can try.

#[test]
fn short_faces_and_bad_indices_are_errors_in_every_format() {
    let cases = [
        ("m.obj", format!("{TRIANGLE_OBJ}f 1 2\n"), "m.obj:5: face has 2 vertices; a face needs at least 3"),
        ("m.obj", format!("{TRIANGLE_OBJ}f\n"), "m.obj:5: face has 0 vertices; a face needs at least 3"),
        (
            "m.obj",
            format!("{TRIANGLE_OBJ}f 1 2 -4\n"),
            "m.obj:5: face refers to vertex -4 but only 3 vertices precede it",
        ),
        ("m.obj", format!("{TRIANGLE_OBJ}f 1 2 4\n"), "m.obj:5: face refers to vertex 4 but the file has 3 vertices"),
        ("m.off", TRIANGLE_OFF.replace("3 0 1 2", "1 0"), "m.off:6: face 0 has 1 vertices; a face needs at least 3"),
        (
            "m.off",
            TRIANGLE_OFF.replace("3 0 1 2", "3 0 1 3"),
            "m.off:6: face 0 refers to vertex 3 but the file has 3 vertices (indices start at 0)",
        ),
    ];
    for (name, text, message) in cases {
        assert_eq!(parse_error(name, text.clone()), message, "{text:?}");
    }
    let header = format!("element vertex 3\n{XYZ}element face 1\nproperty list uchar int vertex_indices\n");
    let vertices = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let face = |list: &[i32]| {
        let mut body = vertices.clone();
        body.push(list.len() as u8);
        body.extend(list.iter().flat_map(|i| i.to_le_bytes()));
        binary_ply(&header, &body)
    };
    assert_eq!(parse_error("m.ply", face(&[0, 1])), "m.ply: face 0 has 2 vertices; a face needs at least 3");
    assert_eq!(parse_error("m.ply", face(&[])), "m.ply: face 0 has 0 vertices; a face needs at least 3");
    assert_eq!(
        parse_error("m.ply", face(&[0, 1, -7])),
        "m.ply: face 0 refers to vertex -7 but the mesh has 3 vertices"
    );
    assert_eq!(parse_error("m.ply", face(&[0, 1, 3])), "m.ply: face 0 refers to vertex 3 but the mesh has 3 vertices");
}

#[test]
fn truncated_and_wrongly_ordered_binary_ply_are_errors() {
    let header = format!("element vertex 3\n{XYZ}element face 1\nproperty list uchar int vertex_indices\n");
    let mut body = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    body.push(255);
    body.extend_from_slice(&[0; 12]);
    assert!(parse_error("m.ply", binary_ply(&header, &body)).starts_with("m.ply: not a valid PLY file: "));
    // Little-endian data under a big-endian header: 1.0 reads as a tiny number, and the
    // all-ones NaN, the same in both orders, is caught.
    let nan_both_ways = f32::from_bits(0xffff_ffff);
    let mut body = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, nan_both_ways, 0.0, 1.0, 0.0]);
    body.extend_from_slice(&[3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0]);
    let text = String::from_utf8_lossy(&binary_ply(&header, &[])).replace("binary_little_endian", "binary_big_endian");
    let bytes = [text.into_bytes(), body].concat();
    let message = parse_error("m.ply", bytes);
    assert_eq!(message, "m.ply: vertex 1 has a non-finite coordinate");
}

#[test]
fn a_huge_ascii_line_gives_a_short_message() {
    let long = "9 ".repeat(1_000_000);
    let text = format!("ply\nformat ascii 1.0\nelement vertex 1\n{XYZ}end_header\n0 0 x {long}\n");
    let message = parse_error("m.ply", text);
    assert!(message.starts_with("m.ply: not a valid PLY file: "), "{message}");
    assert!(message.chars().count() < 400, "{} characters", message.chars().count());
}

#[test]
fn nul_bytes_invalid_utf8_and_crlf_do_not_panic() {
    let inputs: [(&str, &[u8]); 8] = [
        ("m.obj", b"v 0 0 0\0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        ("m.obj", b"v \xff 0 0\n"),
        ("m.obj", b"v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n"),
        ("m.off", b"OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n"),
        ("m.off", b"OFF\n3 1 0\n0 \xc3\x28 0\n"),
        ("m.off", b"\0OFF\n"),
        ("m.ply", b"ply\r\nformat ascii 1.0\r\nelement vertex 1\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\nend_header\r\n0 0 0\r\n"),
        ("m.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float \xff\nend_header\n0\n"),
    ];
    for (name, bytes) in inputs {
        if let Ok(mesh) = Mesh::parse(Path::new(name), bytes.to_vec()) {
            assert!(mesh.positions.iter().all(|p| p.is_finite()), "{name}: {bytes:?}");
        }
    }
    let crlf = Mesh::parse(Path::new("m.off"), inputs[3].1.to_vec()).unwrap();
    assert_eq!(crlf.positions[1], DVec3::X);
}

/// Mutations of small files of each format, from a fixed seed: any result but a panic, and
/// what is accepted is finite and within its faces.
#[test]
fn mutated_small_files_never_panic_nor_pass_non_finite_values() {
    let ply = binary_ply(
        &format!("element vertex 3\n{XYZ}property float nx\nelement face 1\nproperty list uchar int vertex_indices\n"),
        &[
            f32_bytes(&[0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0]),
            vec![3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0],
        ]
        .concat(),
    );
    let seeds: [(&str, Vec<u8>); 3] = [
        ("m.obj", format!("{TRIANGLE_OBJ}vt 0 1\nvn 0 0 1\nv 1 1 1 0.5\n").into_bytes()),
        ("m.off", b"NOFF\n3 1 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2 0.5 0.5 0.5\n".to_vec()),
        ("m.ply", ply),
    ];
    let pieces: [&[u8]; 8] = [b"nan", b"inf", b"1e39", b"-1", b"\0", b"\xff", b"\r\n", b"4294967295"];
    let mut state = 0x853c_49e6_748f_ea9b_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for (name, seed) in &seeds {
        for _ in 0..1500 {
            let mut bytes = seed.clone();
            for _ in 0..1 + next() % 3 {
                let at = (next() % bytes.len() as u64) as usize;
                match next() % 3 {
                    0 => bytes[at] = next() as u8,
                    1 => {
                        let piece = pieces[(next() % pieces.len() as u64) as usize];
                        bytes.splice(at..at, piece.iter().copied());
                    }
                    _ => bytes.truncate(at.max(1)),
                }
            }
            if let Ok(mesh) = Mesh::parse(Path::new(name), bytes.clone()) {
                assert!(mesh.positions.iter().all(|p| p.is_finite()), "{name}: {bytes:?}");
                let count = mesh.positions.len() as u32;
                assert!(mesh.faces.indices.iter().all(|&i| i < count), "{name}: {bytes:?}");
            }
        }
    }
}

#[test]
fn shared_meshes_still_load() {
    for name in ["bunny_stanford_zipper.ply", "bunny_stanford_zipper.obj", "chair.off", "dino.off", "teapot_newell.obj"]
    {
        let Some(path) = common::shared_mesh(name) else { return };
        let mesh = Mesh::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(!mesh.positions.is_empty(), "{name}");
    }
}
