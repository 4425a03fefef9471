//! What the examples share: where their files go, the shared test meshes, deforming a mesh by
//! a pose, and pictures.

#![allow(dead_code, reason = "each example uses a different subset")]

use std::path::{Path, PathBuf};

use glam::DVec3;
use sweepffd::deform::deform_vertices;
use sweepffd::formats::LoadedMesh;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Sweep;
use sweepffd_cli::render::{CLAY, Renderer, Scene, SweepStyle, ViewAngles, add_sweeps, save_png, union_bounds};

/// Where an example writes: the folder given as its first argument, or
/// `sweepffd-examples/NAME`; and the renderer for its pictures, if there is a GPU adapter.
pub struct Output {
    pub dir: PathBuf,
    renderer: Option<Renderer>,
}

impl Output {
    /// Creates the output folder of example `name`.
    pub fn new(name: &str) -> Output {
        let dir = std::env::args_os().nth(1).map_or_else(|| Path::new("sweepffd-examples").join(name), PathBuf::from);
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
        let renderer = match Renderer::new() {
            Ok(renderer) => Some(renderer),
            Err(e) => {
                eprintln!("no pictures: {e}");
                None
            }
        };
        println!("writing into {}", dir.display());
        Output { dir, renderer }
    }

    /// Writes `mesh` at `positions` as `file` (format by extension).
    pub fn mesh(&self, file: &str, mesh: &LoadedMesh, positions: &[DVec3]) {
        let path = self.dir.join(file);
        mesh.save(&path, positions).unwrap_or_else(|e| panic!("{e}"));
        println!("  wrote {}", path.display());
    }

    /// Writes `rig` as `file`.
    pub fn rig(&self, file: &str, rig: &Rig, keys: &[Vec<sweepffd::sweep::Key>]) {
        let path = self.dir.join(file);
        std::fs::write(&path, rig.pose_document(keys).to_json()).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        println!("  wrote {}", path.display());
    }

    /// Draws the panels side by side, each a mesh at some positions with some sweeps, seen
    /// from `view` (azimuth, elevation in degrees), into `file` (PNG).
    pub fn picture(&self, file: &str, mesh: &Mesh, panels: &[(&[DVec3], &[Sweep])], view: (f32, f32)) {
        let Some(renderer) = &self.renderer else { return };
        let mut scenes: Vec<Scene> = panels
            .iter()
            .map(|(positions, _)| {
                let mut scene = Scene::new();
                scene.add_mesh(mesh, positions, CLAY);
                scene
            })
            .collect();
        let diagonal = union_bounds(&scenes).map_or(1.0, |(lo, hi)| f64::from((hi - lo).length()));
        let style = SweepStyle::for_diagonal(diagonal);
        for (scene, (_, sweeps)) in scenes.iter_mut().zip(panels) {
            add_sweeps(scene, sweeps, &style);
        }
        let angles = ViewAngles::try_new(view.0, view.1).expect("the examples' views are valid");
        let picture = renderer.render_panels(&scenes, angles, 480, 480).unwrap_or_else(|e| panic!("{e}"));
        let path = self.dir.join(file);
        save_png(&picture, &path).unwrap_or_else(|e| panic!("{e}"));
        println!("  wrote {}", path.display());
    }
}

/// The path of a test mesh in `../shared/meshes`, or `None` after saying that it is missing.
/// Under `CI=true` a missing mesh is a failure, as in the tests.
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/meshes").join(name);
    if path.is_file() {
        return Some(path);
    }
    if std::env::var("CI").is_ok_and(|v| v == "true" || v == "1") {
        panic!("CI=true but the shared test mesh {} is missing", path.display());
    }
    println!("{} is missing (the ../shared folder is not beside this clone)", path.display());
    None
}

/// The mesh's positions deformed from `rest` bindings to the `posed` sweeps (Eq. 2).
pub fn deform(rig: &Rig, mesh: &Mesh, posed: &[Sweep]) -> Vec<DVec3> {
    let owners = rig.owners(mesh, "mesh").unwrap_or_else(|e| panic!("{e}"));
    let bindings = rig.bind_mesh(mesh, &owners, &|_| {});
    let mut out = vec![DVec3::ZERO; mesh.positions.len()];
    deform_vertices(rig.rest(), posed, &bindings, &mesh.positions, &mut out);
    out
}

/// The largest distance any vertex moved.
pub fn largest_move(before: &[DVec3], after: &[DVec3]) -> f64 {
    before.iter().zip(after).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max)
}

/// The largest deformed / rest length over the mesh's edges: 1 for a rigid motion, large
/// where the surface tears.
pub fn largest_edge_stretch(mesh: &Mesh, positions: &[DVec3]) -> f64 {
    let rest = &mesh.positions;
    mesh.faces
        .triangles()
        .flat_map(|[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(a, b)| (a as usize, b as usize))
        .filter(|&(a, b)| rest[a] != rest[b])
        .map(|(a, b)| positions[a].distance(positions[b]) / rest[a].distance(rest[b]))
        .fold(0.0, f64::max)
}
