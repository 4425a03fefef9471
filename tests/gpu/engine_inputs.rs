//! Inputs as an engine holds them: a `u32` triangle list ([`Faces::from_triangles`]) and named
//! vertex groups as index lists ([`Rig::owners_of`]), giving what the mesh-based entry points
//! give.

use glam::{DQuat, DVec3};
use sweepffd::mesh::{FaceGroup, Faces, Mesh};
use sweepffd::rig::{Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Key;

/// Two triangles sharing an edge and a lone third one, in groups "left" (faces 0, 2) and
/// "right" (face 1); vertex 6 is in no face.
fn mesh() -> Mesh {
    let positions = (0..7).map(|i| DVec3::new(i as f64, 0.5 * i as f64, 0.25)).collect();
    let faces = Faces::from_triangles(&[0, 1, 2, 2, 1, 3, 4, 5, 3]).unwrap();
    let groups =
        vec![FaceGroup { name: "left".into(), faces: vec![0, 2] }, FaceGroup { name: "right".into(), faces: vec![1] }];
    Mesh::from_parts(positions, faces, groups).unwrap()
}

fn rig(selections: Vec<Option<VertexSelection>>) -> Rig {
    let sweeps = selections
        .into_iter()
        .enumerate()
        .map(|(i, vertices)| RigSweep {
            name: format!("s{i}"),
            vertices,
            keys: (0..2).map(|k| Key::circle(DVec3::new(i as f64, 0.0, k as f64), DQuat::IDENTITY, 1.0, 4)).collect(),
            knots: None,
            parent: None,
            falloff: 0.0,
            rotation: Default::default(),
        })
        .collect();
    Rig::new(sweeps).unwrap()
}

fn groups_of(mesh: &Mesh) -> Vec<(String, Vec<u32>)> {
    mesh.groups.iter().map(|g| (g.name.clone(), mesh.group_vertices(&g.name).unwrap())).collect()
}

#[test]
fn owners_of_engine_groups_match_owners_of_the_mesh() {
    let mesh = mesh();
    let groups = groups_of(&mesh);
    let groups: Vec<(&str, &[u32])> = groups.iter().map(|(n, v)| (n.as_str(), v.as_slice())).collect();
    let rig =
        rig(vec![Some(VertexSelection::Groups(vec!["left".into()])), Some(VertexSelection::Indices(vec![6])), None]);
    let from_mesh = rig.owners(&mesh, "m").unwrap();
    assert_eq!(rig.owners_of(mesh.positions.len(), &groups, "m").unwrap(), from_mesh);
    assert_eq!(from_mesh, vec![0, 0, 0, 0, 0, 0, 1]);
}

#[test]
fn owners_of_reports_an_unknown_group_with_the_groups_it_has() {
    let rig = rig(vec![Some(VertexSelection::Groups(vec!["tail".into()]))]);
    let groups: [(&str, &[u32]); 2] = [("head", &[0, 1]), ("ears", &[2])];
    let error = rig.owners_of(3, &groups, "cat").unwrap_err().to_string();
    assert_eq!(error, "sweep \"s0\": the mesh cat has no group \"tail\" (its groups: head, ears)");
    let error = rig.owners_of(3, &[], "cat").unwrap_err().to_string();
    assert!(error.ends_with("(its groups: none)"), "{error}");
}

#[test]
fn owners_of_rejects_a_group_vertex_out_of_range() {
    let rig = rig(vec![Some(VertexSelection::Groups(vec!["head".into()]))]);
    let groups: [(&str, &[u32]); 1] = [("head", &[0, 9, 1])];
    let error = rig.owners_of(3, &groups, "cat").unwrap_err().to_string();
    assert_eq!(error, "sweep \"s0\": vertex index 9 (zero-based) is out of range (the mesh cat has 3 vertices)");
}

#[test]
fn owners_of_rejects_a_vertex_claimed_twice_through_groups() {
    let rig = rig(vec![
        Some(VertexSelection::Groups(vec!["head".into()])),
        Some(VertexSelection::Groups(vec!["ears".into()])),
    ]);
    let groups: [(&str, &[u32]); 2] = [("head", &[2, 0, 1, 1]), ("ears", &[2])];
    let error = rig.owners_of(3, &groups, "cat").unwrap_err().to_string();
    assert_eq!(error, "vertex index 2 (zero-based) is claimed by both sweep \"s0\" and sweep \"s1\"");
}

#[test]
fn a_triangle_list_of_the_wrong_length_is_refused() {
    assert!(Faces::from_triangles(&[0, 1, 2, 3, 4]).is_err());
    assert_eq!(Faces::from_triangles(&[0, 1, 2]).unwrap().len(), 1);
}
