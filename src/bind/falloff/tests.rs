use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::f64::consts::SQRT_2;

use glam::{DQuat, DVec3};

use super::boundary::{boundary_label, sources};
use super::geodesic::triangle_update;
use super::*;
use crate::synthetic::Tube;

/// Vertex (i, j) of a grid `nx` wide: index i + nx·j.
fn at(nx: u32, i: u32, j: u32) -> u32 {
    i + nx * j
}

/// A flat grid of nx × ny vertices spaced h, vertex (i, j) at (i·h, j·h, 0), with the cells
/// for which `keep(i, j)` holds, each split along its anti-diagonal (i + 1, j)–(i, j + 1).
fn grid(nx: u32, ny: u32, h: f64, keep: impl Fn(u32, u32) -> bool) -> (Faces, Vec<DVec3>) {
    let positions = (0..ny).flat_map(|j| (0..nx).map(move |i| DVec3::new(i as f64 * h, j as f64 * h, 0.0))).collect();
    let mut faces = Faces::new();
    for j in 0..ny - 1 {
        for i in (0..nx - 1).filter(|&i| keep(i, j)) {
            faces.push(&[at(nx, i, j), at(nx, i + 1, j), at(nx, i, j + 1)]);
            faces.push(&[at(nx, i + 1, j), at(nx, i + 1, j + 1), at(nx, i, j + 1)]);
        }
    }
    (faces, positions)
}

/// The owner of each vertex (i, j) of an nx × ny grid.
fn grid_owners(nx: u32, ny: u32, owner: impl Fn(u32, u32) -> u32) -> Vec<u32> {
    (0..ny).flat_map(|j| (0..nx).map(move |i| (i, j))).map(|(i, j)| owner(i, j)).collect()
}

/// The old behaviour, as an oracle: Dijkstra over the triangles' edges whose ends are both
/// owned by `sweep`, from `sources` at distance 0.
fn edge_dijkstra(faces: &Faces, positions: &[DVec3], owners: &[u32], sweep: u32, sources: &[u32]) -> Vec<f64> {
    let mut edges = vec![Vec::new(); positions.len()];
    for [a, b, c] in faces.triangles() {
        for (u, v) in [(a, b), (b, c), (c, a)] {
            if owners[u as usize] == sweep && owners[v as usize] == sweep {
                edges[u as usize].push(v as usize);
                edges[v as usize].push(u as usize);
            }
        }
    }
    let mut distance = vec![f64::INFINITY; positions.len()];
    let mut heap = BinaryHeap::new();
    for &s in sources {
        distance[s as usize] = 0.0;
        heap.push(Reverse((0u64, s as usize)));
    }
    while let Some(Reverse((bits, u))) = heap.pop() {
        if f64::from_bits(bits) > distance[u] {
            continue;
        }
        for &v in &edges[u] {
            let d = distance[u] + positions[u].distance(positions[v]);
            if d < distance[v] {
                distance[v] = d;
                heap.push(Reverse((d.to_bits(), v)));
            }
        }
    }
    distance
}

/// The relative error |g − exact| / exact, or |g| where the exact distance is 0.
fn relative_error(g: f64, exact: f64) -> f64 {
    if exact == 0.0 { g.abs() } else { (g - exact).abs() / exact }
}

#[test]
fn grid_distance_to_an_axis_aligned_boundary_is_exact() {
    // Sweep 0 owns i ≤ 20, the rest is unowned: the boundary is the line x = 2.
    let (nx, ny, h) = (41, 21, 0.1);
    let (faces, positions) = grid(nx, ny, h, |_, _| true);
    let owners = grid_owners(nx, ny, |i, _| if i <= 20 { 0 } else { UNOWNED });
    let width = 1.55;
    let reached = band_distances(&faces, &positions, &owners, &[width]);
    let mut worst = (0.0, u32::MAX);
    for r in &reached {
        let i = r.vertex % nx;
        let exact = (20 - i) as f64 * h;
        let error = relative_error(r.distance, exact);
        if error > worst.0 {
            worst = (error, r.vertex);
        }
        assert_eq!(r.label, UNOWNED);
    }
    assert!(worst.0 < 0.02, "max relative error {} at vertex {}", worst.0, worst.1);
    // Exactly the columns 20 − i ≤ 15 (g = 1.5 < 1.55) are in the band.
    let mut expected: Vec<u32> = (0..ny).flat_map(|j| (5..=20).map(move |i| at(nx, i, j))).collect();
    expected.sort_unstable();
    assert_eq!(reached.iter().map(|r| r.vertex).collect::<Vec<_>>(), expected);
}

#[test]
fn grid_distance_to_a_diagonal_boundary_beats_edge_dijkstra() {
    // Sweep 0 owns i + j ≤ 40: the boundary is the line x + y = 4, at 45° to the grid.
    let (n, h) = (41, 0.1);
    let (faces, positions) = grid(n, n, h, |_, _| true);
    let owners = grid_owners(n, n, |i, j| if i + j <= 40 { 0 } else { UNOWNED });
    let width = 1.0;
    let reached = band_distances(&faces, &positions, &owners, &[width]);
    let boundary: Vec<u32> = reached.iter().filter(|r| r.distance == 0.0).map(|r| r.vertex).collect();
    assert_eq!(boundary, (0..n).rev().map(|i| at(n, i, 40 - i)).collect::<Vec<_>>(), "the boundary is the line");
    let dijkstra = edge_dijkstra(&faces, &positions, &owners, 0, &boundary);
    let (mut fmm_worst, mut dijkstra_worst) = ((0.0, u32::MAX), (0.0, u32::MAX));
    for r in &reached {
        let (i, j) = (r.vertex % n, r.vertex / n);
        let exact = (40 - i - j) as f64 * h / SQRT_2;
        let fmm = relative_error(r.distance, exact);
        let old = relative_error(dijkstra[r.vertex as usize], exact);
        if fmm > fmm_worst.0 {
            fmm_worst = (fmm, r.vertex);
        }
        if old > dijkstra_worst.0 {
            dijkstra_worst = (old, r.vertex);
        }
    }
    assert!(fmm_worst.0 < 0.02, "fast marching: max relative error {} at vertex {}", fmm_worst.0, fmm_worst.1);
    assert!(dijkstra_worst.0 > 0.05, "edge Dijkstra: max relative error only {}", dijkstra_worst.0);
    // Every owned vertex closer than W is in the band: 40 − i − j ≤ 14 (g ≈ 0.99).
    let expected = (0..n * n).filter(|&v| owners[v as usize] == 0 && 40 - (v % n) - (v / n) <= 14).count();
    assert_eq!(reached.len(), expected);
}

#[test]
fn cylinder_distance_runs_along_the_surface() {
    // Rings 0..=19 of a tube of quads (0.1 apart) and its bottom cap centre are sweep 0's; the
    // boundary is ring 19, and g on ring r is (19 − r)·0.1 along the wall.
    let tube = Tube { rings: 41, around: 32, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let ring_of = |v: u32| v / tube.around;
    let owners: Vec<u32> = (0..mesh.positions.len() as u32)
        .map(|v| if ring_of(v) < 20 || v == tube.rings * tube.around { 0 } else { UNOWNED })
        .collect();
    let reached = band_distances(&mesh.faces, &mesh.positions, &owners, &[1.05]);
    assert_eq!(reached.len(), 11 * 32, "rings 9..=19");
    for r in &reached {
        let exact = (19 - ring_of(r.vertex)) as f64 * 0.1;
        assert!(relative_error(r.distance, exact) < 1e-9, "vertex {}: {} vs {exact}", r.vertex, r.distance);
    }
}

/// A U in the plane z = 0, cells 0.1 wide: a bridge (y < 1) across x ∈ [0, 2.2] and two arms up
/// to y = 10, A over x ∈ [0, 1] and B over x ∈ [1.2, 2.2], 0.2 apart in space. Sweep 0 owns
/// it but for the tops of the arms (A from y = 9, B from y = 6). `keep_arm_b` keeps or removes
/// B's cells; `place` moves B's vertices above the bridge.
fn u_shape(keep_arm_b: bool, place: impl Fn(DVec3) -> DVec3) -> (Faces, Vec<DVec3>, Vec<u32>) {
    let (nx, ny) = (23, 101);
    let (faces, mut positions) = grid(nx, ny, 0.1, |i, j| j < 10 || i < 10 || (i >= 12 && keep_arm_b));
    let owners = grid_owners(nx, ny, |i, j| match (i, j) {
        (0..=10, 90..) | (12.., 60..) | (11, 11..) => UNOWNED,
        _ => 0,
    });
    for (v, p) in positions.iter_mut().enumerate() {
        if v as u32 % nx >= 12 && v as u32 / nx > 10 {
            *p = place(*p);
        }
    }
    (faces, positions, owners)
}

/// Arm A's vertices of [`u_shape`].
fn on_arm_a(v: u32) -> bool {
    v % 23 <= 10 && v / 23 >= 10
}

/// The weight a Euclidean falloff would give: S(min |p − b| / W) over the boundary vertices b.
fn euclidean_weight(p: DVec3, boundary: &[DVec3], width: f64) -> f64 {
    smoothstep(boundary.iter().map(|b| p.distance(*b)).fold(f64::INFINITY, f64::min) / width)
}

#[test]
fn u_shape_arm_weights_are_geodesic_not_euclidean() {
    let width = 2.45;
    let (faces, positions, owners) = u_shape(true, |p| p);
    let (removed_faces, removed_positions, removed_owners) = u_shape(false, |p| p);
    // Arm B folded up by 90° about the bridge's top edge (y = 1): an isometry of the surface
    // that takes B's boundary far from A.
    let fold = |p: DVec3| DVec3::new(p.x, 1.0, p.y - 1.0);
    let (folded_faces, folded_positions, folded_owners) = u_shape(true, fold);

    let weights = band_weights(&faces, &positions, &owners, &[width]);
    let arm_a: Vec<BandWeight> = weights.iter().copied().filter(|w| on_arm_a(w.vertex)).collect();
    assert_eq!(arm_a.len(), 25 * 11, "rows 65..=89 of arm A");
    let removed: Vec<BandWeight> = band_weights(&removed_faces, &removed_positions, &removed_owners, &[width])
        .into_iter()
        .filter(|w| on_arm_a(w.vertex))
        .collect();
    let folded = band_weights(&folded_faces, &folded_positions, &folded_owners, &[width]);
    let same = |a: &[BandWeight], b: &[BandWeight]| {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .all(|(a, b)| a.vertex == b.vertex && a.neighbour == b.neighbour && (a.weight - b.weight).abs() < 1e-12)
    };
    assert!(same(&arm_a, &removed), "removing arm B changed arm A's weights");
    assert!(same(&weights, &folded), "folding arm B away changed the weights");

    // A Euclidean falloff would see arm B's boundary, 0.2 across the gap.
    let boundary = |positions: &[DVec3]| -> Vec<DVec3> {
        weights.iter().filter(|w| w.weight == 0.0).map(|w| positions[w.vertex as usize]).collect()
    };
    let (near, far) = (boundary(&positions), boundary(&folded_positions));
    let worst = (0..positions.len() as u32)
        .filter(|&v| on_arm_a(v) && owners[v as usize] == 0)
        .map(|v| {
            let p = positions[v as usize];
            (euclidean_weight(p, &near, width) - euclidean_weight(p, &far, width)).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst > 0.1, "a Euclidean weight changes by only {worst}");
}

#[test]
fn weights_are_zero_at_a_rest_boundary_and_grow_with_distance_to_one() {
    let n = 41;
    let (faces, positions) = grid(n, n, 0.1, |_, _| true);
    let owners = grid_owners(n, n, |i, j| if i + j <= 40 { 0 } else { UNOWNED });
    let width = 1.0;
    let weights = band_weights(&faces, &positions, &owners, &[width]);
    let reached = band_distances(&faces, &positions, &owners, &[width]);
    assert_eq!(weights.len(), reached.len());
    let mut by_distance: Vec<(f64, f64)> = reached
        .iter()
        .zip(&weights)
        .map(|(r, w)| {
            assert_eq!(r.vertex, w.vertex);
            assert!(w.fades_to_rest());
            if r.distance == 0.0 {
                assert_eq!(w.weight, 0.0, "boundary vertex {}", w.vertex);
            }
            assert!((w.weight - smoothstep(r.distance / width)).abs() < 1e-15);
            (r.distance, w.weight)
        })
        .collect();
    by_distance.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Non-decreasing up to the rounding of 3x² − 2x³ (an ulp where g differs by an ulp).
    let decreasing: Vec<_> = by_distance.windows(2).filter(|p| p[0].1 > p[1].1 + 2.0 * f64::EPSILON).collect();
    assert!(decreasing.is_empty(), "w decreases as g grows: {decreasing:?}");
    assert!(by_distance.last().is_some_and(|&(g, w)| g > 0.95 && w > 0.99 && w < 1.0));
    // Owned vertices from g ≥ W on (40 − i − j ≥ 15) have no entry: w = 1.
    assert!(weights.iter().all(|w| 40 - w.vertex % n - w.vertex / n <= 14));
    assert!(weights.windows(2).all(|p| p[0].vertex < p[1].vertex), "sorted by vertex, once each");
}

#[test]
fn falloff_weight_is_c1() {
    let h = 1e-6;
    for meets_half in [false, true] {
        let w = |x: f64| falloff_weight(x, meets_half);
        let scale = if meets_half { 0.5 } else { 1.0 };
        assert_eq!(w(0.0), 1.0 - scale);
        assert_eq!(w(1.0), 1.0);
        assert_eq!(w(1.5), 1.0);
        for k in 1..20 {
            let x = k as f64 / 20.0;
            let numeric = (w(x + h) - w(x - h)) / (2.0 * h);
            let exact = scale * 6.0 * x * (1.0 - x);
            assert!((numeric - exact).abs() < 1e-6, "w'({x}) = {numeric}, expected {exact}");
        }
        // The slope is 0 on both sides of x = 1 and right of x = 0.
        let left_of_one = (w(1.0) - w(1.0 - h)) / h;
        let right_of_one = (w(1.0 + h) - w(1.0)) / h;
        let right_of_zero = (w(h) - w(0.0)) / h;
        for slope in [left_of_one, right_of_one, right_of_zero] {
            assert!(slope.abs() < 1e-5, "slope {slope} at a knot");
        }
    }
}

#[test]
fn seam_between_two_banded_sweeps_meets_at_half() {
    // Sweep 0 owns i ≤ 20, sweep 1 the rest.
    let (nx, ny) = (41, 11);
    let (faces, positions) = grid(nx, ny, 0.1, |_, _| true);
    let owners = grid_owners(nx, ny, |i, _| if i <= 20 { 0 } else { 1 });
    let weights = band_weights(&faces, &positions, &owners, &[1.05, 0.55]);
    let column = |w: &BandWeight| w.vertex % nx;
    for w in &weights {
        let owner = owners[w.vertex as usize];
        assert_eq!(w.neighbour, 1 - owner, "vertex {} faces its own sweep", w.vertex);
        if column(w) == 20 || column(w) == 21 {
            assert_eq!(w.weight, 0.5, "seam vertex {}", w.vertex);
        } else {
            assert!(w.weight > 0.5 && w.weight < 1.0);
        }
    }
    let columns = |sweep| {
        let mut columns: Vec<u32> = weights.iter().filter(|w| owners[w.vertex as usize] == sweep).map(column).collect();
        columns.sort_unstable();
        columns.dedup();
        columns
    };
    assert_eq!(columns(0), (10..=20).collect::<Vec<_>>());
    assert_eq!(columns(1), (21..=26).collect::<Vec<_>>());

    // With sweep 1 hard (W = 0), sweep 0 fades fully into it and sweep 1 has no band.
    let hard = band_weights(&faces, &positions, &owners, &[1.05, 0.0]);
    assert!(!hard.is_empty());
    for w in &hard {
        assert_eq!((owners[w.vertex as usize], w.neighbour), (0, 1));
        assert!(w.weight < 1.0);
        if column(w) == 20 {
            assert_eq!(w.weight, 0.0);
        }
    }
}

#[test]
fn boundary_label_prefers_rest_then_majority_then_lower_index() {
    assert_eq!(boundary_label(&[1, 2, 2, UNOWNED]), UNOWNED);
    assert_eq!(boundary_label(&[1, 2, 2]), 2);
    assert_eq!(boundary_label(&[1, 1, 2, 2]), 1);
    assert_eq!(boundary_label(&[3]), 3);

    // Vertex 0 at the centre of a hexagon fan 1..=6, with three fins 7, 8, 9 on edge 0–2: vertex
    // 2 (sweep 1) shares five triangles with 0 but one edge; vertices 1 and 4 (sweep 2) two edges.
    let ring = |k: u32| {
        let angle = std::f64::consts::TAU * k as f64 / 6.0;
        DVec3::new(angle.cos(), angle.sin(), 0.0)
    };
    let mut positions: Vec<DVec3> = std::iter::once(DVec3::ZERO).chain((0..6).map(ring)).collect();
    positions.extend([DVec3::Z, -DVec3::Z, DVec3::new(0.0, 0.0, 2.0)]);
    let mut faces = Faces::new();
    for k in 1..=6 {
        faces.push(&[0, k, k % 6 + 1]);
    }
    for fin in 7..=9 {
        faces.push(&[0, 2, fin]);
    }
    let mut owners = vec![0, 2, 1, 0, 2, 0, 0, 0, 0, 0];
    let active: Vec<bool> = owners.iter().map(|&o| o == 0).collect();
    let label_of_centre = |owners: &[u32]| {
        let found = sources(&Corners::new(&faces, &active), owners, &active, &HashMap::new());
        found.iter().find(|s| s.vertex == 0).map(|s| s.label)
    };
    assert_eq!(label_of_centre(&owners), Some(2));
    owners[4] = 1;
    owners[2] = 0;
    assert_eq!(label_of_centre(&owners), Some(1), "a tie of sweeps 1 and 2");
    owners[5] = UNOWNED;
    assert_eq!(label_of_centre(&owners), Some(UNOWNED));
}

#[test]
fn a_part_without_boundary_or_falloff_has_no_band() {
    // Two grids side by side, not connected: the left all sweep 0's, the right half sweep 1's.
    let n = 11;
    let (left_faces, left) = grid(n, n, 0.1, |_, _| true);
    let (right_faces, mut right) = grid(n, n, 0.1, |_, _| true);
    right.iter_mut().for_each(|p| p.x += 5.0);
    let mut positions = left;
    positions.extend(right);
    let mut faces = left_faces.clone();
    for face in right_faces.iter() {
        faces.push(&face.iter().map(|&v| v + n * n).collect::<Vec<_>>());
    }
    let mut owners = vec![0; (n * n) as usize];
    owners.extend(grid_owners(n, n, |i, _| if i <= 5 { 1 } else { UNOWNED }));

    let weights = band_weights(&faces, &positions, &owners, &[1.0, 1.0]);
    assert!(!weights.is_empty(), "sweep 1 has a boundary");
    assert!(weights.iter().all(|w| owners[w.vertex as usize] == 1), "sweep 0 has no boundary");
    assert!(band_weights(&faces, &positions, &owners, &[1.0, 0.0]).is_empty(), "W = 0: a hard boundary");
    assert!(band_weights(&faces, &positions, &owners, &[]).is_empty(), "no falloff listed");
}

#[test]
fn degenerate_faces_and_polygons_give_finite_weights() {
    let mut positions: Vec<DVec3> = (0..6).map(|k| DVec3::new(k as f64, 0.0, 0.0)).collect();
    positions.extend([DVec3::Y, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(2.0, 1.5, 0.0), DVec3::Z]);
    let mut faces = Faces::new();
    faces.push(&[0, 1, 2]); // collinear: zero area
    faces.push(&[6, 7, 8]); // 6 and 7 coincide
    faces.push(&[1, 1, 8]); // a repeated corner
    faces.push(&[3, 3, 3]);
    faces.push(&[0, 6, 8, 9, 2]); // a pentagon
    faces.push(&[1, 2, 9, 8]); // a quad
    for fin in [10, 4, 5] {
        faces.push(&[8, 9, fin]); // three triangles on edge 8–9: non-manifold
    }
    faces.push(&[4, 5]); // too short for a triangle
    faces.push(&[5]);
    faces.push(&[2, 9, 99]); // an index past the positions
    let owners = vec![0, 0, 0, 0, UNOWNED, 1, 0, 0, 0, 1, 0];
    let weights = band_weights(&faces, &positions, &owners, &[2.0, 1.5]);
    assert!(weights.len() >= 4, "{weights:?}");
    assert!(weights.iter().all(|w| w.weight.is_finite() && (0.0..1.0).contains(&w.weight)), "{weights:?}");
    assert!(weights.windows(2).all(|p| p[0].vertex < p[1].vertex));
    // Fewer owners than positions: the rest count as absent.
    let short = band_weights(&faces, &positions, &owners[..8], &[2.0, 1.5]);
    assert!(short.iter().all(|w| w.vertex < 8 && w.weight.is_finite()));
}

#[test]
fn triangle_update_is_exact_for_a_plane_wave_from_inside_the_angle() {
    // A triangle in a tilted plane, the wave arriving at c from between a and b.
    let frame = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
    let origin = DVec3::new(1.0, -2.0, 0.5);
    let place = |x: f64, y: f64| origin + frame * DVec3::new(x, y, 0.0);
    let (c, a, b) = (place(0.0, 0.0), place(1.0, 0.2), place(0.3, 0.9));
    let g_c = 5.0;
    let wave = |toward_c: DVec3| {
        let n = toward_c.normalize();
        move |p: DVec3| g_c + n.dot(p - c)
    };
    let inside = wave(-((a - c).normalize() + (b - c).normalize()));
    let update = triangle_update(c, a, inside(a), b, inside(b));
    assert!(update.is_some_and(|g| (g - g_c).abs() < 1e-12), "{update:?}");
    // The same wave with a and b swapped.
    assert!(triangle_update(c, b, inside(b), a, inside(a)).is_some_and(|g| (g - g_c).abs() < 1e-12));
    // A wave arriving from outside the angle at c gives no update: the edges take over.
    let outside = wave(-((a - c).normalize() - 2.0 * (b - c).normalize()));
    assert_eq!(triangle_update(c, a, outside(a), b, outside(b)), None);
    // Degenerate triangles: collinear corners, a corner on c.
    assert_eq!(triangle_update(c, a, 1.0, c + 2.0 * (a - c), 2.0), None);
    assert_eq!(triangle_update(c, c, 1.0, b, 1.0), None);
    // Values too far apart for one wave over the triangle.
    assert_eq!(triangle_update(c, a, 0.0, b, 10.0), None);
}

/// The weight of every vertex (1 for those in no band).
fn weights_of(bands: &[BandWeight], count: usize) -> Vec<f64> {
    let mut weights = vec![1.0; count];
    for band in bands {
        weights[band.vertex as usize] = band.weight;
    }
    weights
}

/// A 12 × 9 grid whose vertex (i, j) `owner(i, j)` owns, cut along row 4 into two patches
/// that do not share its vertices (an unwelded seam: the upper patch uses copies, appended
/// after the grid, owned by `copy_owner(i)`); `offset` moves the copies off their twins.
fn seamed_grid(
    offset: f64,
    owner: impl Fn(u32, u32) -> u32,
    copy_owner: impl Fn(u32) -> u32,
) -> (Faces, Vec<DVec3>, Vec<u32>, Vec<u32>) {
    let (nx, ny, seam) = (12, 9, 4);
    let (_, mut positions) = grid(nx, ny, 1.0, |_, _| true);
    let owners_grid = grid_owners(nx, ny, owner);
    let twin_of: Vec<u32> = (0..nx).map(|i| at(nx, i, seam)).collect();
    let copy = |v: u32| -> u32 { twin_of.iter().position(|&t| t == v).map_or(v, |i| nx * ny + i as u32) };
    let copies: Vec<DVec3> = twin_of.iter().map(|&t| positions[t as usize] + DVec3::X * offset).collect();
    positions.extend(copies);
    let mut owners = owners_grid;
    let copy_owners: Vec<u32> = (0..nx).map(copy_owner).collect();
    owners.extend(copy_owners);
    let mut faces = Faces::new();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let c = |i: u32, jj: u32| if j >= seam { copy(at(nx, i, jj)) } else { at(nx, i, jj) };
            faces.push(&[c(i, j), c(i + 1, j), c(i, j + 1)]);
            faces.push(&[c(i + 1, j), c(i + 1, j + 1), c(i, j + 1)]);
        }
    }
    (faces, positions, owners, twin_of)
}

#[test]
fn the_copies_along_an_unwelded_seam_get_one_weight() {
    let width = [4.0];
    let owner = |i: u32, j: u32| if i < 3 && j < 4 { UNOWNED } else { 0 };
    let copy_owner = |i: u32| owner(i, 4);
    let (faces, positions, owners, twins) = seamed_grid(0.0, owner, copy_owner);
    let (welded_faces, welded_positions) = grid(12, 9, 1.0, |_, _| true);
    let welded = weights_of(
        &band_weights(&welded_faces, &welded_positions, &owners[..welded_positions.len()], &width),
        welded_positions.len(),
    );
    let seamed = weights_of(&band_weights(&faces, &positions, &owners, &width), positions.len());
    // Each vertex's weight is the welded mesh's, the copies' their twins'.
    assert_eq!(seamed[..welded.len()], welded[..]);
    for (i, &twin) in twins.iter().enumerate() {
        assert_eq!(seamed[welded.len() + i], welded[twin as usize], "copy of vertex {twin}");
    }
    assert!(twins.iter().any(|&t| welded[t as usize] < 0.9), "the seam crosses the band");
    // Marched apart (the copies a hair off their twins, so not joined), the upper patch has no
    // boundary of its own and its copies keep weight 1 where their twins fade.
    let (faces, positions, owners, twins) = seamed_grid(1e-9, owner, copy_owner);
    let apart = weights_of(&band_weights(&faces, &positions, &owners, &width), positions.len());
    let parted =
        twins.iter().enumerate().map(|(i, &t)| (apart[t as usize] - apart[welded.len() + i]).abs()).fold(0.0, f64::max);
    assert!(parted > 0.1, "copies marched apart differ by {parted}");
}

/// A part whose selection ends along an unwelded seam (its copies on the other side unowned)
/// fades to the rest position there, as the welded grid with the same part does.
#[test]
fn a_part_ending_along_an_unwelded_seam_fades_there() {
    let width = [3.0];
    let owner = |_: u32, j: u32| if j <= 4 { 0 } else { UNOWNED };
    let (faces, positions, owners, twins) = seamed_grid(0.0, owner, |_| UNOWNED);
    let (welded_faces, welded_positions) = grid(12, 9, 1.0, |_, _| true);
    let count = welded_positions.len();
    let welded = weights_of(&band_weights(&welded_faces, &welded_positions, &owners[..count], &width), count);
    let seamed = weights_of(&band_weights(&faces, &positions, &owners, &width), positions.len());
    assert_eq!(seamed[..count], welded[..]);
    assert!(twins.iter().all(|&t| welded[t as usize] == 0.0), "the seam is the part's boundary");
    // Marched apart, the part has no boundary at all and keeps weight 1 at the seam, where
    // its unowned twins stay put.
    let (faces, positions, owners, twins) = seamed_grid(1e-9, owner, |_| UNOWNED);
    let apart = weights_of(&band_weights(&faces, &positions, &owners, &width), positions.len());
    assert!(twins.iter().all(|&t| apart[t as usize] == 1.0));
}
