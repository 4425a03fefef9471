//! Falloff through the command line: `deform` on every backend, with fresh bindings or a
//! bindings file from `bind` on every backend, gives the f64 reference's blended deformation;
//! vertices at weight 0 and unowned ones keep their input coordinates exactly.

use crate::common;

use common::falloff_tubes::attached_arm;
use glam::{DQuat, DVec3};
use sweepffd::deform::deform_vertices;
use sweepffd::edit::{Edit, KeyMode, Posing};
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;

fn succeed(dir: &std::path::Path, args: &[&str]) {
    let output = common::sweepffd(dir).arg("--quiet").args(args).output().unwrap();
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn every_path_of_the_command_line_deforms_with_the_bands() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, rig) = attached_arm(1.5);
    LoadedMesh::from(mesh.clone()).save(&dir.path().join("tube.obj"), &mesh.positions).unwrap();
    let mesh = Mesh::load(&dir.path().join("tube.obj")).unwrap();
    std::fs::write(dir.path().join("rig.json"), rig.to_document().to_json()).unwrap();
    let mut posing = Posing::new(&rig);
    let turn = DQuat::from_rotation_x(0.6);
    let edit = Edit::MoveKey {
        sweep: "arm".into(),
        key: 0,
        translate: [0.0, 0.2, 0.0],
        rotate: turn.to_array(),
        mode: KeyMode::Local,
    };
    posing.apply(&edit).unwrap();
    std::fs::write(dir.path().join("pose.json"), rig.pose_document(posing.keys()).to_json()).unwrap();

    let owners = rig.owners(&mesh, "tube.obj").unwrap();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    assert!(bindings.has_bands());
    let mut reference = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(rig.rest(), &rig.pose(posing.keys()).unwrap(), &bindings, &mesh.positions, &mut reference);
    let keeps = bindings.keeps_rest();

    let backends: &[&str] = if common::gpu().is_some() { &["reference", "cpu", "gpu"] } else { &["reference", "cpu"] };
    let deform = ["deform", "--mesh", "tube.obj", "--rig", "rig.json", "--pose", "pose.json"];
    for &bind_backend in backends {
        let file = format!("{bind_backend}.sffd");
        succeed(
            dir.path(),
            &["bind", "--mesh", "tube.obj", "--rig", "rig.json", "--out", &file, "--backend", bind_backend],
        );
        for &backend in backends {
            for saved in [false, true] {
                let out = format!("out-{bind_backend}-{backend}-{saved}.obj");
                let mut args = deform.to_vec();
                args.extend(["--out", &out, "--backend", backend]);
                if saved {
                    args.extend(["--bindings", &file]);
                }
                succeed(dir.path(), &args);
                let deformed = Mesh::load(&dir.path().join(&out)).unwrap();
                // Bindings from `bind --backend cpu|gpu` and positions from either are f32.
                let f64_only = backend == "reference" && (bind_backend == "reference" || !saved);
                let tolerance = if f64_only { 1e-9 } else { 1e-5 } * mesh.diagonal();
                let (mut worst, mut at) = (0.0, 0);
                for (v, (p, q)) in deformed.positions.iter().zip(&reference).enumerate() {
                    if keeps[v] {
                        assert_eq!(*p, mesh.positions[v], "{out}: vertex {v} keeps its rest position");
                    }
                    if p.distance(*q) > worst {
                        (worst, at) = (p.distance(*q), v);
                    }
                }
                eprintln!("{out}: worst {:.2e} × diagonal at vertex {at}", worst / mesh.diagonal());
                assert!(worst <= tolerance, "{out}: {worst:e} at vertex {at}");
            }
        }
    }
}
