//! Shared helpers for the integration tests: locating the test meshes in `../shared/meshes`.

#![allow(dead_code, reason = "each test binary uses a different subset of the helpers")]

use std::path::PathBuf;

/// The folder of shared test meshes, `../shared/meshes` relative to the workspace root (the
/// folder holding `Cargo.lock`, above the command line's package).
pub fn shared_meshes_dir() -> PathBuf {
    let package = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = package.ancestors().find(|dir| dir.join("Cargo.lock").is_file()).unwrap_or(package);
    root.join("../shared/meshes")
}

/// The path of a shared test mesh, or `None` (with a notice on stderr) when `../shared` is
/// missing. Under `CI=true` a missing mesh fails the test instead of skipping it.
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    let path = shared_meshes_dir().join(name);
    if path.is_file() {
        return Some(path);
    }
    if std::env::var("CI").is_ok_and(|v| v == "true" || v == "1") {
        panic!("CI=true but the shared test mesh {} is missing", path.display());
    }
    eprintln!(
        "skipping: shared test mesh {} not found (the ../shared folder is not beside this clone)",
        path.display()
    );
    None
}

/// A test mesh kept with the code, `tests/meshes/{name}` at the workspace root (every clone has
/// it), loaded.
pub fn kept_mesh(name: &str) -> Mesh {
    let package = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = package.ancestors().find(|dir| dir.join("Cargo.lock").is_file()).unwrap_or(package);
    Mesh::load(&root.join("tests/meshes").join(name)).unwrap()
}

use glam::{DMat3, DQuat, DVec3};
use sweepffd::mesh::{Faces, Mesh};
use sweepffd::rig::{Rig, RigSweep, VertexSelection};
use sweepffd::sweep::Key;

/// The unit principal axis (largest variance) of `points`, by power iteration on the
/// covariance matrix.
pub fn principal_axis(points: &[DVec3]) -> (DVec3, DVec3) {
    let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let mut covariance = DMat3::ZERO;
    for p in points {
        let d = *p - centroid;
        covariance += DMat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    let mut axis = DVec3::new(1.0, 0.7, 0.3).normalize();
    for _ in 0..200 {
        axis = (covariance * axis).normalize();
    }
    (centroid, axis)
}

/// A rest rig with one sweep, `body`, owning every vertex of `mesh`: `keys` keys spread over
/// the middle 70% of the mesh's principal axis (so vertices lie beyond both ends), each
/// centered on the vertices of its slab, oriented along the resulting center curve, with
/// `samples` radii measured from those vertices. The center curve bends wherever the mesh
/// does, so binding meets several roots.
pub fn axis_rig(mesh: &Mesh, keys: usize, samples: usize) -> Rig {
    let (centroid, axis) = principal_axis(&mesh.positions);
    let along: Vec<f64> = mesh.positions.iter().map(|p| (*p - centroid).dot(axis)).collect();
    let (lo, hi) = along.iter().fold((f64::MAX, f64::MIN), |(lo, hi), &a| (lo.min(a), hi.max(a)));
    let span = hi - lo;
    let slab = 0.7 * span / (keys - 1) as f64;
    let stations: Vec<f64> = (0..keys).map(|i| lo + span * (0.15 + 0.7 * i as f64 / (keys - 1) as f64)).collect();
    let slab_members = |station: f64| -> Vec<DVec3> {
        mesh.positions
            .iter()
            .zip(&along)
            .filter(|(_, a)| (**a - station).abs() <= 0.5 * slab)
            .map(|(p, _)| *p)
            .collect()
    };
    let centers: Vec<DVec3> = stations
        .iter()
        .map(|&station| {
            let members = slab_members(station);
            let on_axis = centroid + axis * station;
            if members.is_empty() { on_axis } else { members.iter().copied().sum::<DVec3>() / members.len() as f64 }
        })
        .collect();
    // Frames by parallel transport of the tangent of the center polyline.
    let mut rotations = Vec::with_capacity(keys);
    let mut previous = DQuat::from_rotation_arc(DVec3::Z, (centers[1] - centers[0]).normalize());
    for i in 0..keys {
        let tangent = (centers[(i + 1).min(keys - 1)] - centers[i.saturating_sub(1)]).normalize();
        let current_z = previous * DVec3::Z;
        previous = (DQuat::from_rotation_arc(current_z, tangent) * previous).normalize();
        rotations.push(previous);
    }
    let rig_keys = (0..keys)
        .map(|i| {
            let members = slab_members(stations[i]);
            let mut sums = vec![(0.0, 0usize); samples];
            let mut overall = (0.0, 0usize);
            for p in &members {
                let local = rotations[i].inverse() * (*p - centers[i]);
                let radius = local.truncate().length();
                let theta = local.y.atan2(local.x).rem_euclid(std::f64::consts::TAU);
                let j = ((theta / std::f64::consts::TAU * samples as f64) as usize).min(samples - 1);
                sums[j].0 += radius;
                sums[j].1 += 1;
                overall.0 += radius;
                overall.1 += 1;
            }
            let mean = if overall.1 > 0 { overall.0 / overall.1 as f64 } else { 0.1 * span };
            let radii = sums.iter().map(|&(sum, n)| if n > 0 { sum / n as f64 } else { mean }).collect();
            Key { center: centers[i], rotation: rotations[i], radii }
        })
        .collect();
    let sweep = RigSweep {
        name: "body".to_string(),
        vertices: Some(VertexSelection::All),
        keys: rig_keys,
        knots: None,
        parent: None,
        falloff: 0.0,
        rotation: Default::default(),
    };
    Rig::new(vec![sweep]).expect("the axis rig is valid")
}

/// Set to `1` (CI does) to make a missing GPU adapter fail the GPU tests instead of skipping.
pub const REQUIRE_GPU: &str = "SWEEPFFD_REQUIRE_GPU";

/// The device shared by this test binary's GPU tests, or `None` with a notice on stderr when
/// no adapter exists (a failure instead when `SWEEPFFD_REQUIRE_GPU=1`).
pub fn gpu() -> Option<&'static sweepffd::gpu::GpuContext> {
    use std::sync::OnceLock;
    static CONTEXT: OnceLock<Result<sweepffd::gpu::GpuContext, String>> = OnceLock::new();
    match CONTEXT.get_or_init(|| sweepffd::gpu::GpuContext::new().map_err(|e| e.to_string())) {
        Ok(context) => Some(context),
        Err(reason) if std::env::var(REQUIRE_GPU).is_ok_and(|v| v == "1") => {
            panic!("{REQUIRE_GPU}=1 but no GPU device could be created: {reason}")
        }
        Err(reason) => {
            eprintln!("skipping GPU test: {reason}");
            None
        }
    }
}

/// The largest difference between two f32 arrays: (absolute error, ULP distance, index of the
/// element with the largest absolute error).
pub fn worst_f32(a: &[f32], b: &[f32]) -> (f32, u32, usize) {
    let ordered = |x: f32| {
        let bits = x.to_bits() as i32;
        if bits < 0 { i32::MIN - bits } else { bits }
    };
    let mut worst = (0.0f32, 0u32, 0usize);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let error = (x - y).abs();
        let ulps = ordered(*x).abs_diff(ordered(*y));
        if error > worst.0 {
            worst.0 = error;
            worst.2 = i;
        }
        worst.1 = worst.1.max(ulps);
    }
    worst
}

/// A UV sphere of radius 1: `rings` − 1 latitude rings of `around` vertices and two poles.
pub fn sphere(rings: u32, around: u32) -> Mesh {
    let mut positions = vec![DVec3::Y];
    for r in 1..rings {
        let phi = std::f64::consts::PI * r as f64 / rings as f64;
        for a in 0..around {
            let theta = std::f64::consts::TAU * a as f64 / around as f64;
            positions.push(DVec3::new(phi.sin() * theta.cos(), phi.cos(), phi.sin() * theta.sin()));
        }
    }
    positions.push(-DVec3::Y);
    let ring = |r: u32, a: u32| 1 + (r - 1) * around + a % around;
    let south = positions.len() as u32 - 1;
    let mut faces = Faces::new();
    for a in 0..around {
        faces.push(&[0, ring(1, a + 1), ring(1, a)]);
        faces.push(&[south, ring(rings - 1, a), ring(rings - 1, a + 1)]);
    }
    for r in 1..rings - 1 {
        for a in 0..around {
            faces.push(&[ring(r, a), ring(r, a + 1), ring(r + 1, a + 1), ring(r + 1, a)]);
        }
    }
    Mesh::from_parts(positions, faces, Vec::new()).unwrap()
}

pub mod app_buffer;
pub mod autorig_report;
pub mod bends;
pub mod falloff_tubes;
pub mod isas;
pub mod normal_angles;
pub mod sampled_roots;
pub mod star;
mod teapot;

#[allow(unused_imports, reason = "each test binary uses a different subset of the helpers")]
pub use teapot::{keys_through, teapot_rig};

/// A GPU deformer of f64 `positions` (converted to f32) with the normals of `faces` if given.
pub fn deformer(
    context: &sweepffd::gpu::GpuContext,
    rest: &[sweepffd::sweep::Sweep],
    positions: &[DVec3],
    bindings: sweepffd::gpu::BindingSource,
    faces: Option<&sweepffd::mesh::Faces>,
) -> Result<sweepffd::gpu::GpuDeformer, sweepffd::gpu::GpuError> {
    let positions = sweepffd::gpu::rest_positions(positions);
    let triangles: Option<Vec<u32>> = faces.map(|faces| faces.triangles().flatten().collect());
    let mut descriptor = sweepffd::gpu::DeformerDescriptor::new(rest, &positions, bindings);
    if let Some(triangles) = &triangles {
        descriptor = descriptor.with_triangles(triangles);
    }
    sweepffd::gpu::GpuDeformer::new(context, &descriptor)
}

/// The vertex of `mesh` that maximizes `score`, among those that `inside` accepts (a limb's
/// tip: the lowest vertex on one side); panics where `inside` accepts none.
pub fn extreme_vertex(
    mesh: &sweepffd::mesh::Mesh,
    inside: impl Fn(glam::DVec3) -> bool,
    score: impl Fn(glam::DVec3) -> f64,
) -> u32 {
    (0..mesh.positions.len() as u32)
        .filter(|&v| inside(mesh.positions[v as usize]))
        .max_by(|&a, &b| score(mesh.positions[a as usize]).total_cmp(&score(mesh.positions[b as usize])))
        .expect("a vertex inside")
}
