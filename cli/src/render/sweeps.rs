//! Control sweeps as pictures: each sweep's surface S(θ, t) tessellated over a θ × t grid (the
//! translucent layer) and each key cross-section X_i as a thin dark tube around the ring
//! S(θ, u_i) (the opaque layer), both from the f64 sweep model ([`Sweep::point`]).
//!
//! A sweep fitted to a mesh lies on the mesh's surface, where a surface drawn exactly would
//! fight it for depth; both are therefore drawn a small distance `offset` outside the sweep,
//! the point at binding parameters (θ, t, d = offset, h = 0) of Eq. 2; the ring tubes run at
//! d = offset + ring radius, so they sit on the translucent surface instead of inside it.

use std::f64::consts::TAU;

use glam::{DVec3, Vec3};

use super::scene::{RING, SWEEP_SURFACE, Scene};
use sweepffd::sweep::Sweep;

/// How sweeps are tessellated and drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepStyle {
    /// Distance outside r(θ, t) at which surfaces and rings are drawn (world units).
    pub offset: f64,
    /// Radius of the tube drawn around each key ring (world units).
    pub ring_radius: f64,
    /// Samples around θ ∈ [0, 2π), at least 3.
    pub around: usize,
    /// Samples per knot interval along t, at least 1.
    pub per_interval: usize,
}

impl SweepStyle {
    /// The style for a scene whose bounding-box diagonal is `diagonal`: offset 0.4% and ring
    /// tubes 0.5% of it, 72 samples around, 12 per knot interval.
    pub fn for_diagonal(diagonal: f64) -> SweepStyle {
        SweepStyle { offset: 0.004 * diagonal, ring_radius: 0.005 * diagonal, around: 72, per_interval: 12 }
    }
}

/// Adds every sweep's surface and key rings to `scene`.
pub fn add_sweeps(scene: &mut Scene, sweeps: &[Sweep], style: &SweepStyle) {
    for sweep in sweeps {
        add_sweep_surface(scene, sweep, style);
        for &u in sweep.knots() {
            add_key_ring(scene, sweep, u, style, RING);
        }
    }
}

/// The θ samples θ_j = 2πj / around.
fn thetas(around: usize) -> impl Iterator<Item = f64> {
    (0..around).map(move |j| TAU * j as f64 / around as f64)
}

/// The t samples: `per_interval` steps across each knot interval, knots included.
fn ts(sweep: &Sweep, per_interval: usize) -> Vec<f64> {
    let knots = sweep.knots();
    let mut ts: Vec<f64> = knots
        .windows(2)
        .flat_map(|w| (0..per_interval).map(move |k| w[0] + (w[1] - w[0]) * k as f64 / per_interval as f64))
        .collect();
    ts.extend(knots.last());
    ts
}

/// Adds the sweep surface over the θ × t grid (closed in θ), normals by central differences, to
/// the translucent layer.
pub fn add_sweep_surface(scene: &mut Scene, sweep: &Sweep, style: &SweepStyle) {
    let around = style.around.max(3);
    let ts = ts(sweep, style.per_interval.max(1));
    let grid: Vec<DVec3> =
        ts.iter().flat_map(|&t| thetas(around).map(move |theta| sweep.point(theta, t, style.offset, 0.0))).collect();
    let at = |row: usize, j: usize| grid[row * around + j % around];
    let rows = ts.len();
    let mut normals = Vec::with_capacity(grid.len());
    for row in 0..rows {
        for j in 0..around {
            let along_theta = at(row, j + 1) - at(row, j + around - 1);
            let along_t = at((row + 1).min(rows - 1), j) - at(row.saturating_sub(1), j);
            normals.push(along_theta.cross(along_t).normalize_or_zero().as_vec3());
        }
    }
    let index = |row: usize, j: usize| (row * around + j % around) as u32;
    let mut triangles = Vec::with_capacity(2 * (rows - 1) * around);
    for row in 0..rows - 1 {
        for j in 0..around {
            let (a, b, c, d) = (index(row, j), index(row, j + 1), index(row + 1, j + 1), index(row + 1, j));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    let positions: Vec<Vec3> = grid.iter().map(|p| p.as_vec3()).collect();
    scene.translucent.push(&positions, &normals, &triangles, SWEEP_SURFACE);
}

/// Sides of the tube drawn around a ring.
const TUBE_SIDES: usize = 8;

/// Adds a thin tube in `colour` around the closed ring at d = offset + ring radius in the
/// cross-section at u (a key's ring at its knot) to the opaque layer: at each ring point a
/// circle in the plane spanned by the cross-section normal N(u) and the ring's outward side.
pub fn add_key_ring(scene: &mut Scene, sweep: &Sweep, u: f64, style: &SweepStyle, colour: [f32; 4]) {
    let around = style.around.max(3);
    let d = style.offset + style.ring_radius;
    let ring: Vec<DVec3> = thetas(around).map(|theta| sweep.point(theta, u, d, 0.0)).collect();
    let axis = sweep.normal(u);
    let mut positions = Vec::with_capacity(around * TUBE_SIDES);
    let mut normals = Vec::with_capacity(around * TUBE_SIDES);
    for j in 0..around {
        let tangent = ring[(j + 1) % around] - ring[(j + around - 1) % around];
        let side = tangent.cross(axis).normalize_or_zero();
        for k in 0..TUBE_SIDES {
            let (sin, cos) = (TAU * k as f64 / TUBE_SIDES as f64).sin_cos();
            let direction = cos * side + sin * axis;
            positions.push((ring[j] + style.ring_radius * direction).as_vec3());
            normals.push(direction.as_vec3());
        }
    }
    let index = |j: usize, k: usize| ((j % around) * TUBE_SIDES + k % TUBE_SIDES) as u32;
    let mut triangles = Vec::with_capacity(2 * around * TUBE_SIDES);
    for j in 0..around {
        for k in 0..TUBE_SIDES {
            let (a, b, c, d) = (index(j, k), index(j + 1, k), index(j + 1, k + 1), index(j, k + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    scene.opaque.push(&positions, &normals, &triangles, colour);
}

#[cfg(test)]
mod tests {
    use super::*;
    use sweepffd::synthetic::{Tube, tube_rig};

    #[test]
    fn straight_tube_sweep_surface_lies_at_radius_plus_offset() {
        let tube = Tube { rings: 4, around: 8, length: 2.0, radius: 0.5 };
        let rig = tube_rig(&tube, 3, 8);
        let style = SweepStyle { offset: 0.01, ring_radius: 0.005, around: 16, per_interval: 4 };
        let mut scene = Scene::new();
        add_sweeps(&mut scene, rig.rest(), &style);
        assert_eq!(scene.translucent.vertices.len(), 16 * (2 * 4 + 1));
        for v in &scene.translucent.vertices {
            let p = Vec3::from_array(v.position);
            assert!((p.truncate().length() - 0.51).abs() < 1e-5, "{p}");
            let n = Vec3::from_array(v.normal);
            assert!(n.z.abs() < 1e-4 && (n.length() - 1.0).abs() < 1e-4, "normal {n} at {p}");
        }
        // Three keys, each a tube of 16 × TUBE_SIDES vertices around z = 0, 1, 2, just outside
        // the surface.
        assert_eq!(scene.opaque.vertices.len(), 3 * 16 * TUBE_SIDES);
        let (lo, hi) = scene.opaque.bounds().unwrap();
        assert!((lo.z + 0.005).abs() < 1e-5 && (hi.z - 2.005).abs() < 1e-5, "{lo} {hi}");
        for v in &scene.opaque.vertices {
            let radial = Vec3::from_array(v.position).truncate().length();
            assert!(radial > 0.51 - 1e-5 && radial < 0.525 + 1e-5, "ring vertex at radius {radial}");
        }
    }
}
