//! Fans and normals on closed, open and non-manifold meshes.

use glam::DVec3;

use super::*;

/// A unit cube of outward quads.
fn cube() -> (Vec<DVec3>, Faces) {
    let positions: Vec<DVec3> =
        (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64)).collect();
    let mut faces = Faces::new();
    for quad in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        faces.push(&quad);
    }
    (positions, faces)
}

/// A regular octahedron, outward triangles: by symmetry each vertex normal is its axis.
fn octahedron() -> (Vec<DVec3>, Faces) {
    let positions = vec![DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z];
    let mut faces = Faces::new();
    for [a, b, c] in [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]] {
        faces.push(&[a, b, c]);
    }
    (positions, faces)
}

/// The area-weighted normal sums computed triangle by triangle, to check the fans against.
fn direct_sums(positions: &[DVec3], faces: &Faces) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for [a, b, c] in faces.triangles() {
        let (pa, pb, pc) = (positions[a as usize], positions[b as usize], positions[c as usize]);
        let n = (pb - pa).cross(pc - pa);
        for v in [a, b, c] {
            sums[v as usize] += n;
        }
    }
    sums
}

/// The triangles (i, j, k) the fans of vertex i stand for, with k and j rotated so that the
/// smallest index comes first. Checks that only the row's last entry carries [`FAN_END`].
fn fan_triangles(adjacency: &NormalAdjacency, i: u32) -> Vec<[u32; 3]> {
    let mut triangles = Vec::new();
    let (mut previous, mut first) = (0, 0);
    let row = adjacency.fans_of(i as usize);
    for (c, &entry) in row.iter().enumerate() {
        let j = entry & FAN_INDEX;
        if entry & FAN_START == 0 {
            triangles.push(canonical([i, previous, j]));
        } else {
            first = j;
        }
        if entry & FAN_CLOSE != 0 {
            triangles.push(canonical([i, j, first]));
        }
        assert_eq!(entry & FAN_END != 0, c + 1 == row.len(), "vertex {i} entry {c}");
        previous = j;
    }
    triangles.sort_unstable();
    triangles
}

fn canonical(t: [u32; 3]) -> [u32; 3] {
    let m = (0..3).min_by_key(|&r| t[r]).unwrap();
    [t[m], t[(m + 1) % 3], t[(m + 2) % 3]]
}

fn check_every_triangle_once(faces: &Faces, vertex_count: usize) {
    let adjacency = NormalAdjacency::new(faces, vertex_count);
    for i in 0..vertex_count as u32 {
        let mut expected: Vec<[u32; 3]> = faces.triangles().filter(|t| t.contains(&i)).map(canonical).collect();
        expected.sort_unstable();
        assert_eq!(fan_triangles(&adjacency, i), expected, "vertex {i}");
    }
}

#[test]
fn octahedron_vertex_normals_are_its_axes() {
    let (positions, faces) = octahedron();
    let normals = vertex_normals(&positions, &NormalAdjacency::new(&faces, positions.len()));
    for (p, n) in positions.iter().zip(&normals) {
        assert!((*n - *p).length() < 1e-15, "{p}: {n}");
    }
}

#[test]
fn closed_vertex_is_one_fan_that_closes_without_repeating_its_first_neighbour() {
    let (positions, faces) = octahedron();
    let adjacency = NormalAdjacency::new(&faces, positions.len());
    for i in 0..positions.len() {
        let fans = adjacency.fans_of(i);
        assert_eq!(fans.len(), 4, "four triangles, one fan of four neighbours");
        assert_eq!(fans.iter().filter(|&&e| e & FAN_START != 0).count(), 1);
        assert_eq!(fans[0] & FAN_START, FAN_START);
        assert_eq!(fans[3] & (FAN_CLOSE | FAN_END), FAN_CLOSE | FAN_END);
        assert!(fans[..3].iter().all(|&e| e & (FAN_CLOSE | FAN_END) == 0));
        let mut neighbours: Vec<u32> = fans.iter().map(|&e| e & FAN_INDEX).collect();
        neighbours.sort_unstable();
        neighbours.dedup();
        assert_eq!(neighbours.len(), 4, "each neighbour once");
    }
}

#[test]
fn boundary_fans_do_not_close_and_a_degenerate_fan_keeps_its_repeat() {
    // An open strip: every fan ends at a boundary neighbour, none closes.
    let mut strip = Faces::new();
    for i in 0..6u32 {
        strip.push(&[i, i + 1, i + 2]);
    }
    let adjacency = NormalAdjacency::new(&strip, 8);
    assert!(adjacency.fans.iter().all(|&e| e & FAN_CLOSE == 0));
    // The triangle (0, 1, 1): vertex 0's one fan is 1 → 1, two entries, kept as they are.
    let mut degenerate = Faces::new();
    degenerate.push(&[0, 1, 1]);
    let adjacency = NormalAdjacency::new(&degenerate, 2);
    assert_eq!(adjacency.fans_of(0), [1 | FAN_START, 1 | FAN_END]);
}

#[test]
fn cube_corner_normals_point_outward() {
    let (positions, faces) = cube();
    let normals = vertex_normals(&positions, &NormalAdjacency::new(&faces, positions.len()));
    for (p, n) in positions.iter().zip(&normals) {
        let diagonal = (*p - DVec3::splat(0.5)).normalize();
        // Fan-triangulated quads weight a corner's faces 1 or ½: within 0.35 rad of the diagonal.
        assert!(n.angle_between(diagonal) < 0.35, "{p}: {n}");
        assert!((n.length() - 1.0).abs() < 1e-15);
    }
}

#[test]
fn fans_count_every_triangle_once_on_closed_open_and_non_manifold_meshes() {
    let (positions, faces) = cube();
    check_every_triangle_once(&faces, positions.len());
    // An open strip: every vertex is on the boundary.
    let mut strip = Faces::new();
    for i in 0..6u32 {
        strip.push(&[i, i + 1, i + 2]);
    }
    check_every_triangle_once(&strip, 8);
    // Three triangles sharing the edge (0, 1), and one wound against the others.
    let mut fin = Faces::new();
    for face in [[0, 1, 2], [1, 0, 3], [0, 1, 4], [2, 3, 4]] {
        fin.push(&face);
    }
    check_every_triangle_once(&fin, 5);
}

#[test]
fn fan_sums_equal_the_triangle_by_triangle_sums() {
    let (positions, faces) = cube();
    let adjacency = NormalAdjacency::new(&faces, positions.len());
    let normals = vertex_normals(&positions, &adjacency);
    for (n, sum) in normals.iter().zip(direct_sums(&positions, &faces)) {
        assert!((*n - sum.normalize()).length() < 1e-15);
    }
}

#[test]
fn isolated_vertex_has_zero_normal() {
    let (mut positions, faces) = cube();
    positions.push(DVec3::splat(9.0));
    let normals = vertex_normals(&positions, &NormalAdjacency::new(&faces, positions.len()));
    assert_eq!(normals[8], DVec3::ZERO);
}

/// The f32 normal of vertex `i` as the kernel summed it when a closed fan repeated its first
/// neighbour at its end, each cross product taken from positions read afresh.
fn normal_with_repeated_first_neighbour(positions: &[f32], row: &[u32], i: usize) -> glam::Vec3 {
    let position = |v: u32| glam::Vec3::from_slice(&positions[3 * v as usize..3 * v as usize + 3]);
    let mut expanded = Vec::new();
    let mut first = 0;
    for &entry in row {
        if entry & FAN_START != 0 {
            first = entry & FAN_INDEX;
        }
        expanded.push(entry & (FAN_START | FAN_INDEX));
        if entry & FAN_CLOSE != 0 {
            expanded.push(first);
        }
    }
    let p = position(i as u32);
    let (mut sum, mut previous) = (glam::Vec3::ZERO, glam::Vec3::ZERO);
    for entry in expanded {
        let q = position(entry & FAN_INDEX) - p;
        if entry & FAN_START == 0 {
            sum += previous.cross(q);
        }
        previous = q;
    }
    let length2 = sum.dot(sum);
    if length2 > 0.0 { sum * length2.sqrt().recip() } else { glam::Vec3::ZERO }
}

#[test]
fn closing_a_fan_from_a_register_changes_no_bit_of_the_twin() {
    let mesh = crate::synthetic::Tube { rings: 9, around: 13, length: 2.0, radius: 0.5 }.mesh();
    let adjacency = NormalAdjacency::new(&mesh.faces, mesh.positions.len());
    let positions: Vec<f32> = mesh
        .positions
        .iter()
        .flat_map(|p| [(p.x + 0.3 * p.z.sin()) as f32, (p.y * (1.0 + 0.2 * p.z)) as f32, (p.z + 0.1 * p.x) as f32])
        .collect();
    let mut closed = 0;
    for i in 0..mesh.positions.len() {
        let row = adjacency.fans_of(i);
        closed += row.iter().filter(|&&e| e & FAN_CLOSE != 0).count();
        let twin = crate::cpu::normals::vertex_normal(&positions, &adjacency.offsets, &adjacency.fans, i);
        let repeated = normal_with_repeated_first_neighbour(&positions, row, i);
        assert_eq!(twin.to_array().map(f32::to_bits), repeated.to_array().map(f32::to_bits), "vertex {i}");
    }
    assert_eq!(closed, mesh.positions.len(), "every vertex of a closed tube closes one fan");
}
