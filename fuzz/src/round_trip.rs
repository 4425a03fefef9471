//! Target `write_round_trip`: a mesh parsed, moved, written in every format and read back.
//!
//! The first byte picks the input format (its value modulo 5: OBJ, PLY, OFF, glTF, GLB), the
//! rest is the file. The vertices are moved by a fixed finite similarity ([`moved`]), then the
//! mesh is saved with [`Mesh::save`] to each of `.obj`, `.ply`, `.off`, `.gltf` and `.glb`
//! (faithfully when the format is the input's). A save either fails, leaving no file behind,
//! or writes a file that reads back with the same positions, within the format's precision:
//! exact for the decimal OBJ and OFF, f32 for PLY and glTF.

use glam::{DAffine3, DQuat, DVec3};
use sweepffd::mesh::Mesh;

use super::mesh::parse;
use super::{Outcome, without_dir};

/// The mesh formats by extension, in the order the first byte picks them.
pub const EXTENSIONS: [&str; 5] = ["obj", "ply", "off", "gltf", "glb"];

/// The deformation: a turn of 30° about z, a scale of 1.25 and a shift.
pub fn moved(p: DVec3) -> DVec3 {
    let map = DAffine3::from_scale_rotation_translation(
        DVec3::splat(1.25),
        DQuat::from_rotation_z(30f64.to_radians()),
        DVec3::new(0.5, -0.25, 1.0),
    );
    map.transform_point3(p)
}

/// Parses, moves, writes and reads back the mesh in `data`; the first save error, if any, is
/// the outcome (the other formats are still tried).
pub fn write_round_trip(data: &[u8]) -> Outcome {
    let Some((&pick, file)) = data.split_first() else { return Ok(()) };
    let mesh = parse(&format!("mesh.{}", EXTENSIONS[usize::from(pick) % EXTENSIONS.len()]), file)?;
    let positions: Vec<DVec3> = mesh.mesh.positions.iter().map(|&p| moved(p)).collect();
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mut first_error = None;
    for extension in EXTENSIONS {
        let folder = dir.path().join(extension);
        std::fs::create_dir(&folder).expect("a folder for the output");
        let path = folder.join(format!("out.{extension}"));
        match mesh.save(&path, &positions) {
            Ok(()) => check_read_back(&path, &positions, extension),
            Err(e) => {
                let written: Vec<_> = std::fs::read_dir(&folder).expect("the output folder").collect();
                assert!(written.is_empty(), "{extension}: {} files left after the error {e}", written.len());
                first_error.get_or_insert_with(|| without_dir(&e.to_string(), dir.path()));
            }
        }
    }
    first_error.map_or(Ok(()), Err)
}

/// Asserts that the file at `path` reads back with `expected` positions.
fn check_read_back(path: &std::path::Path, expected: &[DVec3], extension: &str) {
    let read = Mesh::load(path).unwrap_or_else(|e| panic!("{extension}: the written file does not read back: {e}"));
    assert_eq!(read.positions.len(), expected.len(), "{extension}: vertex count read back");
    // f32 formats: half an ulp of the largest coordinate (node transforms mix coordinates),
    // twice for safety, and the smallest normal f32 for values that underflow.
    let largest = expected.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max);
    let tolerance = match extension {
        "obj" | "off" => 0.0,
        _ => largest * f64::from(f32::EPSILON) + f64::from(f32::MIN_POSITIVE),
    };
    for (vertex, (a, b)) in read.positions.iter().zip(expected).enumerate() {
        let error = (*a - *b).abs().max_element();
        assert!(
            error <= tolerance,
            "{extension}: vertex {vertex} reads back as {a}, written as {b} (error {error:e} over {tolerance:e})"
        );
    }
}
