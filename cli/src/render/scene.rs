//! What a picture shows: triangles with per-vertex normals and colours, in an opaque layer
//! (depth-tested and depth-written) and a translucent one (depth-tested, alpha-blended, drawn
//! after the opaque layer without writing depth).

use bytemuck::{Pod, Zeroable};
use glam::{DVec3, Vec3};

use sweepffd::mesh::Mesh;
use sweepffd::normals::{NormalAdjacency, vertex_normals};

/// Warm clay, the colour of meshes (linear RGBA).
pub const CLAY: [f32; 4] = [0.70, 0.36, 0.20, 1.0];
/// Translucent blue, the colour of control sweep surfaces (linear RGBA).
pub const SWEEP_SURFACE: [f32; 4] = [0.10, 0.30, 0.95, 0.30];
/// Dark blue-grey, the colour of key cross-section rings (linear RGBA).
pub const RING: [f32; 4] = [0.015, 0.025, 0.06, 1.0];

/// One vertex as the render shader reads it (`shaders/shade.wgsl`, `VertexIn`):
/// position, normal (any length; zero lights as facing the eye) and linear RGBA colour.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RenderVertex {
    /// World position.
    pub position: [f32; 3],
    /// Normal; flipped towards the eye when shading (two-sided).
    pub normal: [f32; 3],
    /// Linear RGBA; alpha matters in the translucent layer only.
    pub colour: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<RenderVertex>() == 40);

/// Indexed triangles drawn by one pipeline.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Layer {
    /// The vertices.
    pub vertices: Vec<RenderVertex>,
    /// Three indices into `vertices` per triangle.
    pub indices: Vec<u32>,
}

impl Layer {
    /// Appends triangles over `positions` and `normals` (same length) in one colour; the
    /// indices of `triangles` are into `positions`.
    pub fn push(&mut self, positions: &[Vec3], normals: &[Vec3], triangles: &[[u32; 3]], colour: [f32; 4]) {
        let base = self.vertices.len() as u32;
        self.vertices.extend(positions.iter().zip(normals).map(|(p, n)| RenderVertex {
            position: p.to_array(),
            normal: n.to_array(),
            colour,
        }));
        self.indices.extend(triangles.iter().flatten().map(|&i| base + i));
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Axis-aligned bounds of the vertices, or `None` if there is none.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = Vec3::from_array(self.vertices.first()?.position);
        Some(self.vertices.iter().fold((first, first), |(lo, hi), v| {
            let p = Vec3::from_array(v.position);
            (lo.min(p), hi.max(p))
        }))
    }
}

/// Everything one picture (or one panel of a side-by-side picture) shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// Depth-tested, depth-written triangles: meshes and rings.
    pub opaque: Layer,
    /// Alpha-blended triangles over the opaque layer: sweep surfaces.
    pub translucent: Layer,
}

impl Scene {
    /// An empty scene.
    pub fn new() -> Scene {
        Scene::default()
    }

    /// Adds `mesh` (its faces fan-triangulated) at `positions` (one per mesh vertex, e.g. the
    /// deformed ones) with smooth area-weighted vertex normals ([`vertex_normals`]) in `colour`.
    pub fn add_mesh(&mut self, mesh: &Mesh, positions: &[DVec3], colour: [f32; 4]) {
        let adjacency = NormalAdjacency::new(&mesh.faces, positions.len());
        let normals: Vec<Vec3> = vertex_normals(positions, &adjacency).iter().map(|n| n.as_vec3()).collect();
        let points: Vec<Vec3> = positions.iter().map(|p| p.as_vec3()).collect();
        let triangles: Vec<[u32; 3]> = mesh.faces.triangles().collect();
        self.opaque.push(&points, &normals, &triangles, colour);
    }

    /// Bounds of both layers, or `None` for an empty scene.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        match (self.opaque.bounds(), self.translucent.bounds()) {
            (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
            (a, b) => a.or(b),
        }
    }

    /// Whether any position is NaN or infinite.
    pub fn has_non_finite(&self) -> bool {
        let layers = [&self.opaque, &self.translucent];
        layers.iter().flat_map(|l| &l.vertices).any(|v| !Vec3::from_array(v.position).is_finite())
    }
}

/// Bounds of several scenes together (to frame them with one camera), or `None` if all are
/// empty.
pub fn union_bounds(scenes: &[Scene]) -> Option<(Vec3, Vec3)> {
    scenes.iter().filter_map(Scene::bounds).reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use sweepffd::synthetic::Tube;

    #[test]
    fn mesh_of_quads_becomes_two_triangles_each() {
        let tube = Tube { rings: 4, around: 8, length: 1.0, radius: 0.5 };
        let mesh = tube.mesh();
        let mut scene = Scene::new();
        scene.add_mesh(&mesh, &mesh.positions, CLAY);
        assert_eq!(scene.opaque.triangle_count(), mesh.faces.triangles().count());
        assert_eq!(scene.opaque.vertices.len(), mesh.positions.len());
        let (lo, hi) = scene.bounds().unwrap();
        assert!((hi.z - lo.z - 1.0).abs() < 1e-6 && (hi.x - 0.5).abs() < 1e-6);
    }

    #[test]
    fn empty_scene_has_no_bounds() {
        assert_eq!(Scene::new().bounds(), None);
        assert_eq!(union_bounds(&[Scene::new(), Scene::new()]), None);
    }
}
