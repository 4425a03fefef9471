//! Rig and pose validation.

use glam::{DQuat, DVec3};

use super::*;

const EXAMPLE: &str = r#"{"format": "sweepffd-rig", "version": 1,
 "sweeps": [{"name": "neck",
             "vertices": {"groups": ["neck"]},
             "keys": [{"center": [0, 0, 0], "rotation": [0, 0, 0, 1], "radii": [1, 1, 1, 1, 1, 1, 1, 1]},
                      {"center": [0, 0, 2], "rotation": [0, 0, 0, 1], "radii": [1, 1, 1, 1, 1, 1, 1, 1]}]}]}"#;

fn example() -> Rig {
    Rig::from_document(&RigDocument::parse(EXAMPLE).unwrap(), None).unwrap()
}

fn message(result: Result<impl std::fmt::Debug, RigError>) -> String {
    result.unwrap_err().to_string()
}

#[test]
fn example_rig_parses_with_chord_length_knots() {
    let rig = example();
    assert_eq!(rig.sweeps()[0].name, "neck");
    assert_eq!(rig.sweeps()[0].vertices, Some(VertexSelection::Groups(vec!["neck".into()])));
    assert_eq!(rig.rest()[0].knots(), &[0.0, 1.0]);
}

#[test]
fn document_round_trips_through_json() {
    let document = example().to_document();
    assert_eq!(RigDocument::parse(&document.to_json()).unwrap(), document);
}

#[test]
fn vertex_selection_spellings() {
    let parse = |json: &str| serde_json::from_str::<VertexSelection>(json);
    assert_eq!(parse(r#""all""#).unwrap(), VertexSelection::All);
    assert_eq!(parse(r#"{"indices": [3, 1]}"#).unwrap(), VertexSelection::Indices(vec![3, 1]));
    assert!(parse(r#"{"group": ["a"]}"#).unwrap_err().to_string().contains("unknown variant `group`"));
}

#[test]
fn errors_name_the_file_sweep_and_key() {
    let mut document = RigDocument::parse(EXAMPLE).unwrap();
    document.sweeps[0].keys[1].radii[2] = -0.5;
    let error = message(Rig::from_document(&document, Some("rigs/neck.json".into())));
    assert_eq!(error, "rigs/neck.json: sweep \"neck\": key 1: radius 2 is negative (-0.5)");
}

#[test]
fn wrong_format_and_version_are_rejected() {
    let mut document = RigDocument::parse(EXAMPLE).unwrap();
    document.format = "other".into();
    assert!(message(Rig::from_document(&document, None)).contains("\"format\" is \"other\""));
    let mut document = RigDocument::parse(EXAMPLE).unwrap();
    document.version = 7;
    assert!(message(Rig::from_document(&document, None)).contains("\"version\" is 7"));
}

#[test]
fn duplicate_sweep_names_are_rejected() {
    let mut document = RigDocument::parse(EXAMPLE).unwrap();
    document.sweeps.push(document.sweeps[0].clone());
    assert_eq!(message(Rig::from_document(&document, None)), "two sweeps are named \"neck\"");
}

#[test]
fn pose_reuses_the_rest_knots() {
    let rig = example();
    let keys = vec![vec![
        Key::circle(DVec3::ZERO, DQuat::IDENTITY, 1.0, 8),
        Key::circle(DVec3::new(0.0, 5.0, 0.0), DQuat::from_rotation_x(-1.0), 0.5, 8),
    ]];
    let posed = rig.pose(&keys).unwrap();
    assert_eq!(posed[0].knots(), rig.rest()[0].knots());
    assert_eq!(posed[0].center(1.0), DVec3::new(0.0, 5.0, 0.0));
}

#[test]
fn pose_must_match_the_rest_rig() {
    let rig = example();
    let key = Key::circle(DVec3::ZERO, DQuat::IDENTITY, 1.0, 8);
    assert_eq!(
        message(rig.pose(&[vec![key.clone(); 3]])),
        "sweep \"neck\": the pose has 3 keys but the rest rig has 2"
    );
    let short = Key::circle(DVec3::Z, DQuat::IDENTITY, 1.0, 6);
    assert_eq!(
        message(rig.pose(&[vec![key.clone(), short]])),
        "sweep \"neck\": key 1: the pose has 6 radii but the rest rig has 8"
    );
    let mut document = rig.pose_document(&[vec![key.clone(), key]]);
    document.sweeps[0].name = "tail".into();
    assert_eq!(
        message(rig.pose_from_document(&document, Some("pose.json".into()))),
        "pose.json: the pose has a sweep \"tail\", which the rest rig does not have"
    );
}

#[test]
fn pose_may_bring_coincident_centers_but_not_a_zero_rotation() {
    let rig = example();
    let key = Key::circle(DVec3::ZERO, DQuat::IDENTITY, 1.0, 8);
    assert!(rig.pose(&[vec![key.clone(), key.clone()]]).is_ok());
    let zero = Key { rotation: DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0), ..key.clone() };
    assert_eq!(message(rig.pose(&[vec![key, zero]])), "sweep \"neck\": key 1: rotation is the zero quaternion");
}

#[test]
fn a_pose_with_a_non_finite_number_is_not_written() {
    let rig = example();
    let mut document = rig.to_document();
    document.sweeps[0].keys[1].center[2] = f64::INFINITY;
    let error = document.try_to_json(std::path::Path::new("out/pose.json")).unwrap_err().to_string();
    assert_eq!(
        error,
        "out/pose.json: sweep \"neck\": key 1: center[2] is inf, not a finite number; nothing was written"
    );
    document.sweeps[0].keys[1].center[2] = 2.0;
    document.sweeps[0].keys[0].radii[5] = f64::NAN;
    let error = document.try_to_json(std::path::Path::new("pose.json")).unwrap_err().to_string();
    assert_eq!(error, "pose.json: sweep \"neck\": key 0: radii[5] is NaN, not a finite number; nothing was written");
}

#[test]
fn knots_may_be_null_or_absent_but_not_too_many() {
    let with_knots = |knots: &str| EXAMPLE.replacen("\"vertices\"", &format!("\"knots\": {knots}, \"vertices\""), 1);
    assert_eq!(RigDocument::parse(&with_knots("null")).unwrap().sweeps[0].knots, None);
    assert_eq!(RigDocument::parse(&with_knots("[0, 1]")).unwrap().sweeps[0].knots, Some(vec![0.0, 1.0]));
    let many = format!("[{}]", vec!["0.5"; crate::limits::MAX_KEYS_PER_SWEEP + 1].join(", "));
    let error = RigDocument::parse(&with_knots(&many)).unwrap_err().to_string();
    assert!(error.starts_with("sweeps[0].knots: more than 1024 values"), "{error}");
}

#[test]
fn a_rig_built_in_code_is_held_to_the_same_limits() {
    let key = Key::circle(DVec3::ZERO, DQuat::IDENTITY, 1.0, 4096);
    let sweep = |i: usize| RigSweep {
        name: format!("s{i}"),
        vertices: None,
        keys: (0..200).map(|k| Key { center: DVec3::new(0.0, 0.0, k as f64), ..key.clone() }).collect(),
        knots: None,
        parent: None,
        falloff: 0.0,
        rotation: Default::default(),
    };
    let error = message(Rig::new((0..2).map(sweep).collect()));
    assert_eq!(error, "sweep \"s1\": the rig holds more than 1048576 radii in all, the most a rig may have");
}

/// Radii far larger than the mesh place its vertices by a difference f64 cannot hold (radii of
/// 10¹⁵ moved a 4-unit tube's vertices by 0.3 under the rest pose): a rig whose radius is more
/// than 10⁶ times the mesh is refused when bound, naming the sweep and key; 10⁵ times binds and
/// keeps the rest pose to 10⁻⁹ of the mesh.
#[test]
fn radii_far_beyond_the_mesh_are_refused_when_bound() {
    use crate::synthetic::{Tube, tube_rig};
    let tube = Tube { rings: 12, around: 8, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let widened = |factor: f64| {
        let mut sweeps = tube_rig(&tube, 3, 8).sweeps().to_vec();
        for key in &mut sweeps[0].keys {
            key.radii.iter_mut().for_each(|r| *r *= factor);
        }
        Rig::new(sweeps).unwrap()
    };
    let error = widened(2e15).owners(&mesh, "tube.obj").unwrap_err();
    assert!(
        matches!(&error.kind, RigErrorKind::RadiusTooLarge { sweep, key: 0, radius, .. } if sweep == "tube" && *radius == 1e15),
        "{error}"
    );
    assert!(error.to_string().contains("radius 1e15 is more than 1e6 times the mesh tube.obj"), "{error}");
    let rig = widened(4e5 * mesh.diagonal());
    let owners = rig.owners(&mesh, "tube.obj").unwrap();
    let bindings = rig.bind_mesh(&mesh, &owners, &|_| {});
    let mut rest = vec![DVec3::ZERO; mesh.positions.len()];
    crate::deform::deform_vertices(rig.rest(), rig.rest(), &bindings, &mesh.positions, &mut rest);
    let worst = rest.iter().zip(&mesh.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    assert!(worst <= 1e-9 * mesh.diagonal(), "{worst}");
}
