#![allow(dead_code, reason = "the tests use keys_through on their own, the example only the rig")]
//! The teapot rig the tests, the edit bench and the `teapot` example share: keys measured from
//! the Newell teapot's part groups (§5, Fig. 1).

use glam::{DQuat, DVec3};
use sweepffd::mesh::Mesh;
use sweepffd::rig::{LinkKind, ParentLink, Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Key;

/// Keys through the centers `centers` (a polyline along a part), frames carried along it by
/// parallel transport, with `samples` radii averaged from the points `points` of the part
/// that lie within half the key spacing of each key's plane and within `reach` of its center.
pub fn keys_through(points: &[DVec3], centers: &[DVec3], samples: usize, reach: f64) -> Vec<Key> {
    let n = centers.len();
    let mut rotation = DQuat::from_rotation_arc(DVec3::Z, (centers[1] - centers[0]).normalize());
    (0..n)
        .map(|i| {
            let tangent = (centers[(i + 1).min(n - 1)] - centers[i.saturating_sub(1)]).normalize();
            rotation = (DQuat::from_rotation_arc(rotation * DVec3::Z, tangent) * rotation).normalize();
            let spacing = 0.5 * centers[(i + 1).min(n - 1)].distance(centers[i.saturating_sub(1)]);
            let mut sums = vec![(0.0, 0usize); samples];
            for p in points {
                let local = rotation.inverse() * (*p - centers[i]);
                if local.z.abs() > 0.5 * spacing || local.length() > reach {
                    continue;
                }
                let theta = local.y.atan2(local.x).rem_euclid(std::f64::consts::TAU);
                let j = ((theta / std::f64::consts::TAU * samples as f64) as usize).min(samples - 1);
                sums[j].0 += local.truncate().length();
                sums[j].1 += 1;
            }
            let (total, count) = sums.iter().fold((0.0, 0), |(t, c), (s, k)| (t + s, c + k));
            let mean = if count > 0 { total / count as f64 } else { 0.1 * reach };
            let radii = sums.iter().map(|&(s, k)| if k > 0 { s / k as f64 } else { mean }).collect();
            Key { center: centers[i], rotation, radii }
        })
        .collect()
}

/// The centroid of the points whose `coordinate` lies in [lo, hi).
fn centroid_where(points: &[DVec3], coordinate: impl Fn(&DVec3) -> f64, lo: f64, hi: f64) -> DVec3 {
    let inside: Vec<DVec3> = points.iter().copied().filter(|p| (lo..hi).contains(&coordinate(p))).collect();
    inside.iter().copied().sum::<DVec3>() / inside.len() as f64
}

/// A rig for the Newell teapot with its part groups (`teapot_newell_parts.obj`, y up): the body
/// (groups body_rim, body, body_bottom) along the y axis, the spout as a branch of the body
/// and the handle as a loop of it (§5, Fig. 1). The handle owns its group's vertices but vertex
/// 375 (zero-based), which the body's group shares.
pub fn teapot_rig(mesh: &Mesh) -> Rig {
    let group = |names: &[&str]| -> Vec<u32> {
        let mut vertices: Vec<u32> = names.iter().flat_map(|name| mesh.group_vertices(name).unwrap()).collect();
        vertices.sort_unstable();
        vertices.dedup();
        vertices
    };
    let points = |vertices: &[u32]| -> Vec<DVec3> { vertices.iter().map(|&v| mesh.positions[v as usize]).collect() };
    let body_points = points(&group(&["body_rim", "body", "body_bottom"]));
    let body_centers: Vec<DVec3> =
        [0.05, 0.45, 0.85, 1.25, 1.65, 2.05, 2.45].iter().map(|&y| DVec3::new(0.0, y, 0.0)).collect();
    let body = keys_through(&body_points, &body_centers, 16, 2.5);

    let spout_points = points(&group(&["spout"]));
    let spout_centers: Vec<DVec3> = [1.75, 2.05, 2.35, 2.65, 2.95, 3.25]
        .iter()
        .map(|&x| centroid_where(&spout_points, |p| p.x, x, x + 0.3))
        .collect();
    let spout = keys_through(&spout_points, &spout_centers, 12, 0.8);

    let handle_vertices: Vec<u32> = group(&["handle"]).into_iter().filter(|&v| v != 375).collect();
    let handle_points = points(&handle_vertices);
    let around = |p: &DVec3| (p.y - 1.45).atan2(p.x + 1.6).to_degrees().rem_euclid(360.0);
    let handle_centers: Vec<DVec3> = (0..7)
        .map(|i| 90.0 + 25.0 * i as f64)
        .map(|a| centroid_where(&handle_points, around, a - 7.5, a + 7.5))
        .collect();
    let handle = keys_through(&handle_points, &handle_centers, 12, 0.5);

    let sweep = |name: &str, vertices: VertexSelection, keys: Vec<Key>, parent: Option<(&str, LinkKind)>| RigSweep {
        name: name.to_string(),
        vertices: Some(vertices),
        keys,
        knots: None,
        parent: parent.map(|(sweep, kind)| ParentLink { sweep: sweep.to_string(), kind }),
        falloff: 0.0,
        rotation: Default::default(),
    };
    let groups = |names: &[&str]| VertexSelection::Groups(names.iter().map(|n| n.to_string()).collect());
    Rig::new(vec![
        sweep("body", groups(&["body_rim", "body", "body_bottom"]), body, None),
        sweep("spout", groups(&["spout"]), spout, Some(("body", LinkKind::Branch))),
        sweep("handle", VertexSelection::Indices(handle_vertices), handle, Some(("body", LinkKind::Loop))),
    ])
    .expect("the teapot rig is valid")
}
