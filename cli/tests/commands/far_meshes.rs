//! `deform` of a mesh far from the origin or at a tiny scale: the f32 backends compute in a
//! frame local to the mesh, so their accuracy is relative to it wherever it sits. The demo's
//! tube moved by 10⁷ once moved by 0.26 of its size under its own rest pose on the f32
//! backends, by 10⁴ of its size at 10¹², and scaled by 10⁻²⁵ by 0.12 of its size.

use std::path::Path;

use glam::DVec3;
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Key;
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

use crate::common;

/// The largest distance between the vertices of two meshes of the same size, over `size`.
fn worst(a: &Path, b: &Path, size: f64) -> f64 {
    let (a, b) = (Mesh::load(a).unwrap(), Mesh::load(b).unwrap());
    a.positions.iter().zip(&b.positions).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max) / size
}

/// Writes the demo's tube, moved to `p · scale + offset`, as `tube.obj`, its rig as
/// `rig.json` and a bend-twist-taper pose as `pose.json` in `dir`; returns the tube's size.
fn scene(dir: &Path, offset: DVec3, scale: f64) -> f64 {
    let tube = Tube { rings: 40, around: 24, length: 4.0, radius: 0.5 };
    let moved = |p: DVec3| p * scale + offset;
    let moved_keys = |keys: &[Key]| -> Vec<Key> {
        keys.iter()
            .map(|k| Key { center: moved(k.center), radii: k.radii.iter().map(|r| r * scale).collect(), ..k.clone() })
            .collect()
    };
    let mesh = tube.mesh();
    let positions: Vec<DVec3> = mesh.positions.iter().map(|&p| moved(p)).collect();
    let far = Mesh::from_parts(positions.clone(), mesh.faces.clone(), mesh.groups.clone()).unwrap();
    LoadedMesh::from(far).save(&dir.join("tube.obj"), &positions).unwrap();
    let rig = tube_rig(&tube, 5, 16);
    let pose = BendTwistTaper { bend: 0.5, twist: 0.4, taper: 0.7 }.keys(&rig);
    let mut sweeps = rig.sweeps().to_vec();
    sweeps.iter_mut().for_each(|s| s.keys = moved_keys(&s.keys));
    let far_rig = Rig::new(sweeps).unwrap();
    let far_pose: Vec<Vec<Key>> = pose.iter().map(|keys| moved_keys(keys)).collect();
    std::fs::write(dir.join("rig.json"), far_rig.to_document().to_json()).unwrap();
    std::fs::write(dir.join("pose.json"), far_rig.pose_document(&far_pose).to_json()).unwrap();
    4.0 * scale
}

fn deform(dir: &Path, pose: &str, backend: &str) -> std::path::PathBuf {
    let out = format!("{pose}-{backend}.obj");
    let output = common::sweepffd(dir)
        .args(["--quiet", "deform", "--mesh", "tube.obj", "--rig", "rig.json", "--pose", pose, "--out", &out])
        .args(["--backend", backend])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    dir.join(out)
}

#[test]
fn the_f32_backends_keep_their_accuracy_far_from_the_origin_and_at_tiny_scales() {
    let mut backends = vec!["cpu"];
    if common::gpu().is_some() {
        backends.push("gpu");
    }
    let cases = [
        ("moved by 1e7", DVec3::new(1e7, -2e7, 3e7), 1.0),
        ("moved by 1e12", DVec3::new(1e12, -2e12, 3e12), 1.0),
        ("scaled by 1e-25", DVec3::ZERO, 1e-25),
    ];
    for (case, offset, scale) in cases {
        let dir = tempfile::tempdir().unwrap();
        let size = scene(dir.path(), offset, scale);
        let reference = deform(dir.path(), "pose.json", "reference");
        for &backend in &backends {
            let rest = worst(&dir.path().join("tube.obj"), &deform(dir.path(), "rig.json", backend), size);
            eprintln!("{case}, {backend}: the rest pose moves a vertex by {rest:.2e} of the tube's size");
            assert!(rest <= 1e-6, "{case}, {backend}: the rest pose moves a vertex by {rest:e} of the size");
            let posed = worst(&reference, &deform(dir.path(), "pose.json", backend), size);
            eprintln!("{case}, {backend}: the pose is {posed:.2e} of the size from the reference");
            // At 1e12 the sweeps themselves are built in f64 world coordinates, whose spacing
            // there (1.2e-4) the reference shares: see docs/method.md.
            let tolerance = if scale == 1.0 && offset.x >= 1e12 { 1e-3 } else { 1e-6 };
            assert!(posed <= tolerance, "{case}, {backend}: {posed:e} of the size from the reference");
        }
    }
}
