#![allow(dead_code, reason = "each test binary uses a different subset of the star's helpers")]

//! A procedural "star": a ball of radius 1 with five round-ended tubes of radius
//! [`TUBE_RADIUS`] along known axes from its center, blended into it by a smooth minimum, as
//! one closed, connected, consistently oriented triangle mesh.
//!
//! The surface is the zero set of a signed distance (the ball's and each capsule's, joined by
//! the polynomial smooth minimum of Quílez, "Smooth minimum", 2013, with blend width
//! [`BLEND`]), meshed by marching tetrahedra over the six-tetrahedra (Freudenthal) split of a
//! grid of cubes, which shares each tetrahedron face between its two cubes, so the mesh is
//! watertight and manifold wherever no grid value is exactly 0 (zeros are moved off). Every
//! vertex is then relaxed towards its neighbours' mean and projected back onto the zero set,
//! which evens the triangles without changing the connectivity. Beyond the blend each tube
//! is a cylinder about its axis, and the blend is symmetric about it, so the part's true
//! axis is the axis line.

use std::collections::HashMap;

use glam::DVec3;
use sweepffd::mesh::{Faces, Mesh};

/// The tubes' radius (the ball's is 1).
pub const TUBE_RADIUS: f64 = 0.25;
/// The width of the smooth minimum joining each tube to the ball.
pub const BLEND: f64 = 0.2;

/// One tube: its unit axis from the ball's center and the distance of its end sphere's
/// center along it.
#[derive(Clone, Copy, Debug)]
pub struct Tube {
    pub axis: DVec3,
    pub reach: f64,
}

/// The five tubes, in directions at least 50° apart, of reaches 1.9 … 2.3.
pub fn tubes() -> [Tube; 5] {
    let tube = |x: f64, y: f64, z: f64, reach: f64| Tube { axis: DVec3::new(x, y, z).normalize(), reach };
    [
        tube(0.0, 1.0, 0.0, 2.3),
        tube(0.95, -0.25, 0.2, 2.2),
        tube(-0.7, -0.35, 0.6, 2.1),
        tube(0.15, -0.45, -0.9, 2.0),
        tube(-0.8, 0.3, -0.5, 1.9),
    ]
}

/// The signed distance (approximately, inside the blends) to the star's surface.
pub fn distance(p: DVec3) -> f64 {
    tubes().iter().fold(p.length() - 1.0, |d, tube| {
        let along = p.dot(tube.axis).clamp(0.0, tube.reach);
        smooth_min(d, p.distance(tube.axis * along) - TUBE_RADIUS)
    })
}

/// The polynomial smooth minimum of `a` and `b` over width [`BLEND`].
pub fn smooth_min(a: f64, b: f64) -> f64 {
    let h = (0.5 + 0.5 * (b - a) / BLEND).clamp(0.0, 1.0);
    b + (a - b) * h - BLEND * h * (1.0 - h)
}

/// The distance of `p` from the line of `tube`'s axis.
pub fn off_axis(tube: &Tube, p: DVec3) -> f64 {
    (p - tube.axis * p.dot(tube.axis)).length()
}

/// The star meshed on a grid of spacing `step` (0.04 gives about 25k vertices).
pub fn star_mesh(step: f64) -> Mesh {
    implicit_mesh(&distance, 2.7, step)
}

/// The zero set of the signed distance `distance` within the cube of half-width `bound`,
/// meshed on a grid of spacing `step` as the star is.
pub fn implicit_mesh(distance: &dyn Fn(DVec3) -> f64, bound: f64, step: f64) -> Mesh {
    let n = (2.0 * bound / step).ceil() as usize + 1;
    let point = |i: usize, j: usize, k: usize| DVec3::new(i as f64, j as f64, k as f64) * step - DVec3::splat(bound);
    let index = |i: usize, j: usize, k: usize| (i * n + j) * n + k;
    let mut value = vec![0.0; n * n * n];
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let d = distance(point(i, j, k));
                // No grid value exactly on the surface: the mesh stays manifold.
                value[index(i, j, k)] = if d.abs() < 1e-12 { 1e-12 } else { d };
            }
        }
    }
    let mut positions: Vec<DVec3> = Vec::new();
    let mut on_edge: HashMap<(usize, usize), u32> = HashMap::new();
    let mut faces = Faces::new();
    // The six tetrahedra of a cube, each a path 0 → a → a + b → 7 over its corners
    // (corner bits: 1 = +i, 2 = +j, 4 = +k).
    const PATHS: [[usize; 4]; 6] = [[0, 1, 3, 7], [0, 1, 5, 7], [0, 2, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 4, 6, 7]];
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            for k in 0..n - 1 {
                let corner = |c: usize| (i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
                let corners: [(usize, usize, usize); 8] = std::array::from_fn(corner);
                let ids = corners.map(|(a, b, c)| index(a, b, c));
                if ids.iter().all(|&g| value[g] < 0.0) || ids.iter().all(|&g| value[g] > 0.0) {
                    continue;
                }
                for path in PATHS {
                    let tet = path.map(|c| (ids[c], point(corners[c].0, corners[c].1, corners[c].2)));
                    tetrahedron(&tet, &value, &mut positions, &mut on_edge, &mut faces);
                }
            }
        }
    }
    let mut mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
    relax(&mut mesh, distance, step);
    mesh
}

/// The surface's triangles in one tetrahedron of (grid index, position) corners.
fn tetrahedron(
    tet: &[(usize, DVec3); 4],
    value: &[f64],
    positions: &mut Vec<DVec3>,
    on_edge: &mut HashMap<(usize, usize), u32>,
    faces: &mut Faces,
) {
    let inside: Vec<usize> = (0..4).filter(|&c| value[tet[c].0] < 0.0).collect();
    let outside: Vec<usize> = (0..4).filter(|&c| value[tet[c].0] > 0.0).collect();
    if inside.is_empty() || outside.is_empty() {
        return;
    }
    let mut vertex = |a: usize, b: usize| {
        let (ga, gb) = (tet[a].0, tet[b].0);
        *on_edge.entry((ga.min(gb), ga.max(gb))).or_insert_with(|| {
            let (fa, fb) = (value[ga], value[gb]);
            positions.push(tet[a].1 + (tet[b].1 - tet[a].1) * (fa / (fa - fb)));
            positions.len() as u32 - 1
        })
    };
    let polygon: Vec<u32> = match (inside.len(), outside.len()) {
        (1, 3) => outside.iter().map(|&o| vertex(inside[0], o)).collect(),
        (3, 1) => inside.iter().map(|&i| vertex(i, outside[0])).collect(),
        _ => {
            let (i, o) = (&inside, &outside);
            vec![vertex(i[0], o[0]), vertex(i[0], o[1]), vertex(i[1], o[1]), vertex(i[1], o[0])]
        }
    };
    // Facing outwards: the normal points from the inside corners to the outside ones.
    let mean = |cs: &[usize]| cs.iter().map(|&c| tet[c].1).sum::<DVec3>() / cs.len() as f64;
    let outwards = mean(&outside) - mean(&inside);
    let p = |v: u32| positions[v as usize];
    for t in 1..polygon.len() - 1 {
        let mut triangle = [polygon[0], polygon[t], polygon[t + 1]];
        if (p(triangle[1]) - p(triangle[0])).cross(p(triangle[2]) - p(triangle[0])).dot(outwards) < 0.0 {
            triangle.swap(1, 2);
        }
        faces.push(&triangle);
    }
}

/// Five passes of: each vertex to its neighbours' mean, then two Newton steps onto the zero set
/// of `distance` (its gradient by central differences of `step` / 100).
fn relax(mesh: &mut Mesh, distance: &dyn Fn(DVec3) -> f64, step: f64) {
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); mesh.positions.len()];
    for [a, b, c] in mesh.faces.triangles() {
        for (x, y) in [(a, b), (b, c), (c, a)] {
            neighbours[x as usize].push(y);
            neighbours[y as usize].push(x);
        }
    }
    let h = step / 100.0;
    let gradient = |p: DVec3| {
        DVec3::new(
            distance(p + DVec3::X * h) - distance(p - DVec3::X * h),
            distance(p + DVec3::Y * h) - distance(p - DVec3::Y * h),
            distance(p + DVec3::Z * h) - distance(p - DVec3::Z * h),
        ) / (2.0 * h)
    };
    for _ in 0..5 {
        let before = mesh.positions.clone();
        for (v, near) in neighbours.iter().enumerate() {
            let mut p = near.iter().map(|&n| before[n as usize]).sum::<DVec3>() / near.len() as f64;
            for _ in 0..2 {
                let g = gradient(p);
                p -= g * (distance(p) / g.length_squared().max(1e-12));
            }
            mesh.positions[v] = p;
        }
    }
}
