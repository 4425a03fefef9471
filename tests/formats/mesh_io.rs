//! Mesh files in and out: the shared test meshes load with their documented counts and groups,
//! faithful saves change nothing but moved vertices, generic saves round-trip, failed saves
//! leave nothing behind, and enclosed volumes match closed forms.

use crate::common;

use std::fs;
use std::path::{Path, PathBuf};

use glam::DVec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Encoding, Ply, Property};
use ply_rs_bw::writer::Writer;
use sweepffd::formats::{LoadedMesh, MeshError};
use sweepffd::mesh::{FaceGroup, Faces, Mesh};

fn load(name: &str) -> Option<LoadedMesh> {
    common::shared_mesh(name).map(|path| LoadedMesh::load(&path).unwrap())
}

fn dir_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

fn parse_ply(bytes: &[u8]) -> Ply<DefaultElement> {
    Parser::<DefaultElement>::new().read_ply(&mut &bytes[..]).unwrap()
}

/// Largest |a − b| over all coordinates, with the index of the worst vertex.
fn worst_difference(a: &[DVec3], b: &[DVec3]) -> (f64, usize) {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).abs().max_element())
        .enumerate()
        .fold((0.0, 0), |(m, w), (i, d)| if d > m { (d, i) } else { (m, w) })
}

#[test]
fn shared_meshes_have_the_readme_counts() {
    let table = [
        ("bunny_stanford_zipper.obj", 35_947, 69_451),
        ("bunny_stanford_zipper.ply", 35_947, 69_451),
        ("bunny_closed.obj", 34_817, 69_630),
        ("armadillo_50k.obj", 49_990, 99_976),
        ("teapot_newell_parts.obj", 3_644, 6_320),
        ("teapot_mcguire/teapot.obj", 7_850, 8_028),
        ("spot_control_mesh.obj", 188, 180),
    ];
    for (name, vertices, faces) in table {
        let Some(mesh) = load(name) else { continue };
        assert_eq!(mesh.mesh.positions.len(), vertices, "{name}");
        assert_eq!(mesh.mesh.faces.len(), faces, "{name}");
    }
}

#[test]
fn bunny_keeps_its_unused_vertices() {
    let Some(mesh) = load("bunny_stanford_zipper.obj") else {
        return;
    };
    let mut used = vec![false; mesh.mesh.positions.len()];
    for &i in &mesh.mesh.faces.indices {
        used[i as usize] = true;
    }
    assert_eq!(used.iter().filter(|&&u| !u).count(), 1_113);
}

#[test]
fn mcguire_teapot_has_quads_triangles_and_two_groups() {
    let Some(mesh) = load("teapot_mcguire/teapot.obj") else {
        return;
    };
    let quads = mesh.mesh.faces.iter().filter(|f| f.len() == 4).count();
    let triangles = mesh.mesh.faces.iter().filter(|f| f.len() == 3).count();
    assert_eq!((quads, triangles), (7_676, 352));
    let names: Vec<&str> = mesh.mesh.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["Base", "Top"]);
    let in_groups: usize = mesh.mesh.groups.iter().map(|g| g.faces.len()).sum();
    assert_eq!(in_groups, mesh.mesh.faces.len());
    let (min, max) = mesh.mesh.bounds();
    assert!((min.x + 71.9).abs() < 0.05 && (max.x - 82.3).abs() < 0.05, "{min} {max}");
}

#[test]
fn spot_control_mesh_has_pentagons_quads_and_triangles() {
    let Some(mesh) = load("spot_control_mesh.obj") else {
        return;
    };
    let count = |n| mesh.mesh.faces.iter().filter(|f| f.len() == n).count();
    assert_eq!((count(3), count(4), count(5)), (4, 160, 16));
    assert_eq!(mesh.mesh.faces.triangles().count(), 4 + 2 * 160 + 3 * 16);
}

#[test]
fn bunny_obj_and_ply_agree() {
    let (Some(obj), Some(ply)) = (load("bunny_stanford_zipper.obj"), load("bunny_stanford_zipper.ply")) else {
        return;
    };
    assert_eq!(obj.mesh.faces, ply.mesh.faces);
    let (worst, at) = worst_difference(&obj.mesh.positions, &ply.mesh.positions);
    assert!(worst <= 1e-6, "worst difference {worst} at vertex {at}");
}

#[test]
fn teapot_parts_groups_match_the_readme() {
    let Some(mesh) = load("teapot_newell_parts.obj") else {
        return;
    };
    let expected = [
        ("body_rim", 1, 800),
        ("body", 801, 2400),
        ("handle", 2401, 3200),
        ("spout", 3201, 4000),
        ("lid", 4001, 5560),
        ("body_bottom", 5561, 6320),
    ];
    assert_eq!(mesh.mesh.groups.len(), expected.len());
    for (group, (name, first, last)) in mesh.mesh.groups.iter().zip(expected) {
        assert_eq!(group.name, name);
        let faces: Vec<u32> = (first - 1..last).collect();
        assert_eq!(group.faces, faces, "{name}");
    }
    let body = mesh.mesh.group_vertices("body").unwrap();
    let handle = mesh.mesh.group_vertices("handle").unwrap();
    let shared: Vec<u32> = body.iter().copied().filter(|v| handle.binary_search(v).is_ok()).collect();
    assert_eq!(shared, vec![375]);
    assert_eq!(mesh.mesh.positions[375], DVec3::new(-2.0, 0.9, 0.0));
    assert_eq!(mesh.mesh.group_vertices("spoon"), None);
}

#[test]
fn faithful_obj_save_of_shared_meshes_is_byte_identical() {
    let dir = tempfile::tempdir().unwrap();
    for name in [
        "bunny_stanford_zipper.obj",
        "teapot_newell_parts.obj",
        "teapot_mcguire/teapot.obj",
        "spot_control_mesh.obj",
        "armadillo_50k.obj",
    ] {
        let Some(path) = common::shared_mesh(name) else {
            continue;
        };
        let mesh = LoadedMesh::load(&path).unwrap();
        let out = dir.path().join("out.obj");
        mesh.save(&out, &mesh.mesh.positions).unwrap();
        assert!(fs::read(&out).unwrap() == fs::read(&path).unwrap(), "{name}");
    }
}

const INLINE: &[u8] = b"# inline test\r\nmtllib a.mtl\r\n\r\no part\r\ng left right\r\n  v 0 0 0\r\nv 1 0 0 1.0\r\nv 1 \\\r\n 1 0\r\nv 0 1 0 0.5 0.5 0.5 # grey\r\nvt 0 0\r\nvn 0 0 1\r\ns off\r\nf 1/1/1 2/1/1 3/1/1 4/1/1\r\ng\nf -4 \\\n -2 -1\n# no final newline";

#[test]
fn faithful_obj_save_of_inline_file_is_byte_identical() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.obj");
    fs::write(&input, INLINE).unwrap();
    let mesh = LoadedMesh::load(&input).unwrap();
    assert_eq!(mesh.mesh.positions.len(), 4);
    assert_eq!(mesh.mesh.faces.len(), 2);
    let names: Vec<&str> = mesh.mesh.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["part", "left", "right"]);
    assert_eq!(mesh.mesh.groups[0].faces, vec![0, 1]);
    assert_eq!(mesh.mesh.groups[1].faces, vec![0]);
    let out = dir.path().join("out.obj");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    assert_eq!(fs::read(&out).unwrap(), INLINE);
}

#[test]
fn faithful_obj_save_changes_exactly_the_moved_vertex_lines() {
    let Some(path) = common::shared_mesh("teapot_newell_parts.obj") else {
        return;
    };
    let mesh = LoadedMesh::load(&path).unwrap();
    let moved_vertices = [0_usize, 375, 1000, 3643];
    let mut positions = mesh.mesh.positions.clone();
    for &v in &moved_vertices {
        positions[v] += DVec3::new(0.125, -1.0 / 3.0, 1e-9);
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("moved.obj");
    mesh.save(&out, &positions).unwrap();

    let before = fs::read_to_string(&path).unwrap();
    let after = fs::read_to_string(&out).unwrap();
    let (before, after): (Vec<&str>, Vec<&str>) = (before.lines().collect(), after.lines().collect());
    assert_eq!(before.len(), after.len());
    let vertex_lines: Vec<usize> = (0..before.len()).filter(|&i| before[i].starts_with("v ")).collect();
    let expected: Vec<usize> = moved_vertices.iter().map(|&v| vertex_lines[v]).collect();
    let changed: Vec<usize> = (0..before.len()).filter(|&i| before[i] != after[i]).collect();
    assert_eq!(changed, expected);
    for &v in &moved_vertices {
        let p = positions[v];
        let numbers: Vec<f64> =
            after[vertex_lines[v]].strip_prefix("v ").unwrap().split_whitespace().map(|n| n.parse().unwrap()).collect();
        assert_eq!(numbers, vec![p.x, p.y, p.z], "the rewritten line reads back exactly");
    }
    let reloaded = Mesh::load(&out).unwrap();
    assert_eq!(reloaded.positions, positions);
    assert_eq!(reloaded.faces, mesh.mesh.faces);
    assert_eq!(reloaded.groups, mesh.mesh.groups);
}

#[test]
fn faithful_ply_save_of_ascii_bunny_parses_to_identical_data() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.ply") else {
        return;
    };
    let mesh = LoadedMesh::load(&path).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.ply");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    let original = parse_ply(&fs::read(&path).unwrap());
    let saved = parse_ply(&fs::read(&out).unwrap());
    assert_eq!(saved.header.encoding, Encoding::Ascii);
    assert!(saved == original, "faithful save changed the PLY data");
}

#[test]
fn faithful_ply_save_of_binary_bunny_keeps_data_and_moves_only_moved_vertices() {
    let Some(path) = common::shared_mesh("bunny_stanford_zipper.ply") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for encoding in [Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
        let mut binary = parse_ply(&fs::read(&path).unwrap());
        binary.header.encoding = encoding;
        let input = dir.path().join("binary.ply");
        let mut bytes = Vec::new();
        Writer::new().write_ply(&mut bytes, &mut binary).unwrap();
        fs::write(&input, &bytes).unwrap();

        let mesh = LoadedMesh::load(&input).unwrap();
        assert_eq!(mesh.mesh.positions.len(), 35_947);
        let out = dir.path().join("out.ply");
        mesh.save(&out, &mesh.mesh.positions).unwrap();
        assert!(parse_ply(&fs::read(&out).unwrap()) == binary, "{encoding:?}");

        let mut positions = mesh.mesh.positions.clone();
        positions[7] = DVec3::new(0.5, 0.25, -0.125);
        mesh.save(&out, &positions).unwrap();
        let mut expected = binary.clone();
        let vertex = &mut expected.payload["vertex"][7];
        for (name, value) in [("x", 0.5), ("y", 0.25), ("z", -0.125)] {
            vertex.insert(name.to_string(), Property::Float(value));
        }
        assert!(parse_ply(&fs::read(&out).unwrap()) == expected, "{encoding:?}");
        assert_eq!(Mesh::load(&out).unwrap().positions, positions);
    }
}

#[test]
fn obj_to_ply_generic_save_round_trips_within_f32() {
    let Some(mesh) = load("teapot_newell_parts.obj") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("teapot.PLY");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    let back = Mesh::load(&out).unwrap();
    assert_eq!(back.faces, mesh.mesh.faces);
    assert!(back.groups.is_empty());
    let (worst, at) = worst_difference(&back.positions, &mesh.mesh.positions);
    let tolerance =
        mesh.mesh.positions.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max) * f64::from(f32::EPSILON);
    assert!(worst <= tolerance, "worst {worst} at vertex {at}, tolerance {tolerance}");
    assert!(worst > 0.0, "f32 rounding should show somewhere");
}

#[test]
fn ply_to_obj_generic_save_round_trips_exactly() {
    let Some(mesh) = load("bunny_stanford_zipper.ply") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bunny.obj");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    let text = fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("# written by sweepffd\n"));
    let back = Mesh::load(&out).unwrap();
    assert_eq!(back.faces, mesh.mesh.faces);
    assert_eq!(back.positions, mesh.mesh.positions);
}

#[test]
fn generic_obj_save_of_built_mesh_keeps_groups() {
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let mut faces = Faces::new();
    for face in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
        faces.push(&face);
    }
    let groups = vec![
        FaceGroup { name: "bottom".into(), faces: vec![0] },
        FaceGroup { name: "sides".into(), faces: vec![1, 2, 3] },
    ];
    let mesh = LoadedMesh::from(Mesh::from_parts(positions, faces, groups).unwrap());
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tet.obj");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    let back = Mesh::load(&out).unwrap();
    assert_eq!(back.positions, mesh.mesh.positions);
    assert_eq!(back.faces, mesh.mesh.faces);
    assert_eq!(back.groups, mesh.mesh.groups);
}

#[test]
fn failed_saves_leave_no_file_and_no_temporary() {
    let mesh = LoadedMesh::from(
        Mesh::from_parts(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            {
                let mut f = Faces::new();
                f.push(&[0, 1, 2]);
                f
            },
            Vec::new(),
        )
        .unwrap(),
    );
    let dir = tempfile::tempdir().unwrap();

    let missing_dir = dir.path().join("no_such_dir").join("out.obj");
    let err = mesh.save(&missing_dir, &mesh.mesh.positions).unwrap_err();
    assert!(matches!(err, MeshError::Write { .. }), "{err}");
    assert!(err.to_string().contains("out.obj"), "{err}");

    let out = dir.path().join("out.ply");
    let err = mesh.save(&out, &mesh.mesh.positions[..2]).unwrap_err();
    assert_eq!(err.to_string(), "positions has 2 entries but the mesh has 3 vertices");

    let nan = vec![DVec3::ZERO, DVec3::X, DVec3::new(0.0, f64::NAN, 0.0)];
    let err = mesh.save(&out, &nan).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("{}: vertex 2 has the coordinate NaN, which is not finite; nothing was written", out.display())
    );

    let err = mesh.save(&dir.path().join("out.stl"), &mesh.mesh.positions).unwrap_err();
    assert!(matches!(err, MeshError::UnsupportedFormat { .. }), "{err}");
    assert!(dir_names(dir.path()).is_empty(), "{:?}", dir_names(dir.path()));

    fs::write(&out, b"keep").unwrap();
    assert!(mesh.save(&out, &mesh.mesh.positions[..1]).is_err());
    assert_eq!(fs::read(&out).unwrap(), b"keep");
    assert_eq!(dir_names(dir.path()), ["out.ply"]);
}

#[test]
fn load_errors_name_the_file() {
    let err = Mesh::load(Path::new("no_such_mesh.obj")).unwrap_err();
    assert!(matches!(err, MeshError::Read { .. }), "{err}");
    assert!(err.to_string().starts_with("cannot read no_such_mesh.obj: "), "{err}");
    let err = Mesh::load(Path::new("x.stl")).unwrap_err();
    assert_eq!(err.to_string(), "x.stl: unsupported mesh format (expected .obj, .ply, .off, .gltf or .glb)");

    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.obj");
    fs::write(&empty, b"# nothing here\n").unwrap();
    let err = Mesh::load(&empty).unwrap_err();
    assert_eq!(err.to_string(), format!("{}: the mesh has no vertices", empty.display()));

    let bad = dir.path().join("bad.ply");
    fs::write(&bad, b"\x00\x01binary garbage\xff").unwrap();
    let err = Mesh::load(&bad).unwrap_err();
    assert!(err.to_string().starts_with(&format!("{}: not a valid PLY file: ", bad.display())), "{err}");
}

fn volume_after_translation(name: &str) {
    let Some(mesh) = load(name) else { return };
    let v = mesh.mesh.enclosed_volume(&mesh.mesh.positions);
    assert!(v > 0.0, "{name}: volume {v}");
    let shifted: Vec<DVec3> = mesh.mesh.positions.iter().map(|&p| p + DVec3::new(1000.0, -1000.0, 1000.0)).collect();
    let w = mesh.mesh.enclosed_volume(&shifted);
    assert!(((w - v) / v).abs() < 1e-9, "{name}: {v} vs {w} after translation");
}

#[test]
fn closed_bunny_volume_is_positive_and_translation_invariant() {
    volume_after_translation("bunny_closed.obj");
}

#[test]
fn armadillo_volume_is_positive_and_translation_invariant() {
    volume_after_translation("armadillo_50k.obj");
}

fn load_inline(name: &str, text: &str) -> LoadedMesh {
    let dir = tempfile::tempdir().unwrap();
    let path: PathBuf = dir.path().join(name);
    fs::write(&path, text).unwrap();
    LoadedMesh::load(&path).unwrap()
}

#[test]
fn inline_unit_cube_of_outward_quads_has_volume_one() {
    let cube = load_inline(
        "cube.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n\
         f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n",
    );
    let v = cube.mesh.enclosed_volume(&cube.mesh.positions);
    assert!((v - 1.0).abs() < 1e-14, "{v}");
}

#[test]
fn inline_tetrahedron_has_its_closed_form_volume() {
    let (a, b, c) = (2.0, 3.0, 5.0);
    let tet = load_inline(
        "tet.obj",
        &format!("v 0 0 0\nv {a} 0 0\nv 0 {b} 0\nv 0 0 {c}\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"),
    );
    let v = tet.mesh.enclosed_volume(&tet.mesh.positions);
    let exact = a * b * c / 6.0;
    assert!((v - exact).abs() < 1e-14 * exact, "{v} vs {exact}");
}

#[test]
fn edited_faces_fall_back_to_the_generic_obj_writer() {
    let mut mesh = load_inline("quad.obj", "# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    mesh.mesh.faces = Faces::new();
    mesh.mesh.faces.push(&[0, 1, 2]);
    mesh.mesh.faces.push(&[0, 2, 3]);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("split.obj");
    mesh.save(&out, &mesh.mesh.positions).unwrap();
    let text = fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("# written by sweepffd\n"), "{text}");
    assert_eq!(Mesh::load(&out).unwrap().faces, mesh.mesh.faces);
}
