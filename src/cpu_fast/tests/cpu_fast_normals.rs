//! The fast fused deform with Jacobian normals (`sweepffd::cpu_fast::deform::deform_with_normals`,
//! `FastMesh::deform_with_normals`) against the f32 twin of `shaders/deform_normals.wgsl`
//! (`sweepffd::cpu::deform::deform_with_normals`), on every instruction set this CPU runs (the
//! detected one and the scalar fallback): positions within 1e-5 × the bounding-box diagonal (the
//! plain fast deform's tolerance, tests/cpu_fast.rs), normals within [`NORMAL_TOLERANCE`] of the
//! twin's. Each check prints the worst vertex, and that the rest normals would fail it.

use crate::common;

use common::isas::isas;
use common::normal_angles::{at, worst_angle};
use glam::{Vec3, Vec4};
use sweepffd::coeffs::{BAND_FLAG, GpuBinding, SweepCoefficients, UNOWNED, bind_segments};
use sweepffd::cpu;
use sweepffd::cpu::bind::BindInputs;
use sweepffd::cpu::jacobian::{NORMAL_BEYOND_END, NORMAL_FRAME, NORMAL_JACOBIAN};
use sweepffd::cpu_fast::{self, FastMesh, Isa};
use sweepffd::mesh::Mesh;
use sweepffd::normals::NormalAdjacency;
use sweepffd::rig::Rig;
use sweepffd::synthetic::{BendTwistTaper, Tube, attached_tube_rig, tube_rig};

const POSITION_TOLERANCE: f64 = 1e-5;
/// The angle between the fast and the twin's normals, radians: about the GPU's measured worst
/// against the same twin (1.1e-5 rad, tests/gpu_jacobian_normals.rs); the fast path's measured
/// worst is 1.35e-5 rad (the armadillo), where rest frames are nearly singular.
const NORMAL_TOLERANCE: f64 = 2e-5;

const POSE: BendTwistTaper = BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 };

/// The rest normals of `mesh` (the normals kernel's twin), tightly packed.
fn rest_normals(mesh: &Mesh) -> Vec<f32> {
    let positions = cpu::packed(&mesh.positions);
    let mut normals = vec![0.0; positions.len()];
    cpu::normals::normals(&positions, &NormalAdjacency::new(&mesh.faces, mesh.positions.len()), &mut normals);
    normals
}

/// The fast fused deform of `bindings` with `records` on each instruction set against the twin's,
/// from the rest positions and normals `rest`; `diagonal` scales the position tolerance. Also checks
/// that the rest normals are off the twin's by far more than the tolerance wherever `moves` (so
/// the check can fail).
fn check_records(
    name: &str,
    cells: &[sweepffd::coeffs::CellCoeffs],
    bindings: &[GpuBinding],
    records: &[Vec4],
    (positions, normals): (&[f32], &[f32]),
    diagonal: f64,
    moves: bool,
) {
    let (mut twin, mut twin_normals) = (positions.to_vec(), normals.to_vec());
    cpu::deform::deform_with_normals(cells, bindings, records, &mut twin, &mut twin_normals);
    if moves {
        let (rest, at) = worst_angle(normals, &twin_normals);
        println!("{name}: rest normals vs twin, worst angle {rest:.2e} rad at vertex {at}");
        assert!(rest > 100.0 * NORMAL_TOLERANCE, "{name}: the pose barely turns the normals ({rest:e} rad)");
    }
    for isa in isas() {
        let (mut fast, mut fast_normals) = (positions.to_vec(), normals.to_vec());
        cpu_fast::deform::deform_with_normals_with(isa, cells, bindings, records, &mut fast, &mut fast_normals);
        let (error, ulps, worst) = common::worst_f32(&fast, &twin);
        let (turn, turn_at) = worst_angle(&fast_normals, &twin_normals);
        let unit = (0..bindings.len())
            .filter(|&i| bindings[i].cell < BAND_FLAG)
            .map(|i| (at(&fast_normals, i).length() - at(&twin_normals, i).length()).abs())
            .fold(0.0, f64::max);
        println!(
            "{name} ({}): positions max |Δ| {error:.3e} ({:.2e} × diagonal, {ulps} ULP) at vertex {}; \
             normals worst angle {turn:.2e} rad at vertex {turn_at}, max ||n| − |n_twin|| {unit:.1e}",
            isa.name(),
            error as f64 / diagonal.max(f64::MIN_POSITIVE),
            worst / 3
        );
        assert!(
            error as f64 <= POSITION_TOLERANCE * diagonal,
            "{name} ({}): max |Δposition| {error:e} at vertex {}",
            isa.name(),
            worst / 3
        );
        assert!(
            turn <= NORMAL_TOLERANCE,
            "{name} ({}): normal off the twin's by {turn:e} rad at vertex {turn_at}: fast {:?}, twin {:?}, binding {:?}, \
             record {:?}",
            isa.name(),
            at(&fast_normals, turn_at),
            at(&twin_normals, turn_at),
            bindings[turn_at],
            records[turn_at]
        );
        assert!(unit <= 1e-5, "{name} ({}): normal lengths differ by {unit:e}", isa.name());
    }
}

/// Binds `mesh` (owners `owners`, band vertices `bands` flagged) to `rig` on the twin, makes the
/// records from the rest normals and checks the fused deform under [`POSE`].
fn check_raw(name: &str, mesh: &Mesh, rig: &Rig, owners: &[u32], normals: &[f32], n: usize) {
    let rest = rig.rest();
    let coefficients = SweepCoefficients::new(rest);
    let tables = bind_segments(rest);
    let inputs = BindInputs { cells: &coefficients.cells, bind_segments: &tables, sweeps: &coefficients.sweeps };
    let positions = &cpu::packed(&mesh.positions)[..3 * n];
    let bindings = cpu::bind::bind(&inputs, &owners[..n], positions);
    let records = cpu::jacobian::coordinates(&coefficients.cells, &bindings, &normals[..3 * n]);
    let modes = [NORMAL_JACOBIAN, NORMAL_BEYOND_END, NORMAL_FRAME]
        .map(|mode| records.iter().zip(&bindings).filter(|(r, b)| b.cell < BAND_FLAG && r.w == mode).count());
    println!("{name}: {n} vertices, records through (φ, s, d) / (φ, h, d) / the frame: {modes:?}");
    let mut posed = SweepCoefficients::new(rest);
    posed.update(&rig.pose(&POSE.keys(rig)).unwrap()).unwrap();
    let rest = (positions, &normals[..3 * n]);
    check_records(name, &posed.cells, &bindings, &records, rest, mesh.diagonal(), n > 100);
}

fn check(name: &str, mesh: &Mesh, rig: &Rig) {
    let owners = rig.owners(mesh, name).unwrap();
    let weights = rig.band_weights(mesh, &owners);
    let mut flagged = owners.clone();
    for weight in &weights {
        flagged[weight.vertex as usize] |= BAND_FLAG;
    }
    check_raw(name, mesh, rig, &flagged, &rest_normals(mesh), mesh.positions.len());
}

fn check_shared(file: &str) {
    let Some(path) = common::shared_mesh(file) else { return };
    let mesh = Mesh::load(&path).unwrap();
    check(file, &mesh, &common::axis_rig(&mesh, 9, 16));
}

#[test]
fn bunny_normals_on_the_fast_path_match_the_twin() {
    check_shared("bunny_stanford_zipper.obj");
}

#[test]
fn newell_teapot_normals_on_the_fast_path_match_the_twin() {
    check_shared("teapot_newell.obj");
}

#[test]
fn armadillo_normals_on_the_fast_path_match_the_twin() {
    check_shared("armadillo_50k.obj");
}

#[test]
fn tube_normals_on_the_fast_path_match_the_twin() {
    let tube = Tube::with_vertex_count(300_000, 4.0, 0.5);
    check("tube 300k", &tube.mesh(), &tube_rig(&tube, 8, 16));
}

#[test]
fn tube_with_a_falloff_band_leaves_the_band_normals_alone() {
    let tube = Tube::with_vertex_count(50_000, 4.0, 0.5);
    let mesh = tube.mesh();
    assert_ne!(mesh.positions.len() % 8, 0);
    check("tube fading to rest", &mesh, &attached_tube_rig(&tube, 8, 16, 1.0));
}

#[test]
fn empty_and_tiny_meshes_and_ragged_tails_match_the_twin() {
    let tube = Tube { rings: 40, around: 32, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let rig = tube_rig(&tube, 8, 16);
    let normals = rest_normals(&mesh);
    let owners = vec![0; mesh.positions.len()];
    for n in (0..=23).chain([31, 1003]) {
        check_raw(&format!("{n} vertices"), &mesh, &rig, &owners, &normals, n);
    }
}

#[test]
fn batches_mixing_cells_modes_unowned_and_band_vertices_match_the_twin() {
    // Every third vertex unowned, every fifth flagged as in a band, every seventh's record
    // through the frame alone, every eleventh's beyond an end: no batch of eight is uniform in
    // cell or mode, and the tails are ragged.
    let tube = Tube { rings: 70, around: 20, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let rig = tube_rig(&tube, 6, 7);
    let rest = rig.rest();
    let coefficients = SweepCoefficients::new(rest);
    let tables = bind_segments(rest);
    let inputs = BindInputs { cells: &coefficients.cells, bind_segments: &tables, sweeps: &coefficients.sweeps };
    let n = mesh.positions.len();
    let owners: Vec<u32> = (0..n)
        .map(|i| match (i % 3, i % 5) {
            (0, _) => UNOWNED,
            (_, 1) => BAND_FLAG,
            _ => 0,
        })
        .collect();
    let positions = cpu::packed(&mesh.positions);
    let normals = rest_normals(&mesh);
    let bindings = cpu::bind::bind(&inputs, &owners, &positions);
    let mut records = cpu::jacobian::coordinates(&coefficients.cells, &bindings, &normals);
    for (i, record) in records.iter_mut().enumerate() {
        if i % 7 == 2 {
            *record = Vec3::from_slice(&normals[3 * i..3 * i + 3]).extend(NORMAL_FRAME);
        } else if i % 11 == 4 {
            record.w = NORMAL_BEYOND_END;
        }
    }
    let mut posed = SweepCoefficients::new(rest);
    posed.update(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let rest = (&positions[..], &normals[..]);
    check_records("mixed batches", &posed.cells, &bindings, &records, rest, mesh.diagonal(), true);
}

#[test]
fn the_fused_deform_leaves_unbound_and_band_vertices_alone() {
    let tube = Tube { rings: 10, around: 16, length: 2.0, radius: 0.5 };
    let rig = tube_rig(&tube, 4, 8);
    let mut posed = SweepCoefficients::new(rig.rest());
    posed.update(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let bound = GpuBinding { cell: 3, s: 0.4, phi: 0.6, d: 0.1, h: 0.0 };
    let left = [GpuBinding { cell: UNOWNED, ..bound }, GpuBinding { cell: 3 | BAND_FLAG, ..bound }];
    let records = vec![Vec4::new(0.0, 0.0, 1.0, NORMAL_JACOBIAN); 24];
    for isa in isas() {
        let bindings: Vec<GpuBinding> = (0..24).map(|i| if i % 4 == 1 { left[i % 2] } else { bound }).collect();
        let (mut positions, mut normals) = (vec![f32::NAN; 72], vec![f32::NAN; 72]);
        cpu_fast::deform::deform_with_normals_with(
            isa,
            &posed.cells,
            &bindings,
            &records,
            &mut positions,
            &mut normals,
        );
        for (i, binding) in bindings.iter().enumerate() {
            let moved = binding.cell == 3;
            for (what, values) in [("position", &positions), ("normal", &normals)] {
                let xyz = &values[3 * i..3 * i + 3];
                assert_eq!(xyz.iter().all(|x| x.is_finite()), moved, "{}: vertex {i}'s {what}: {xyz:?}", isa.name());
            }
        }
    }
}

#[test]
#[should_panic(expected = "cell")]
fn a_binding_past_the_cells_panics() {
    let tube = Tube { rings: 10, around: 16, length: 2.0, radius: 0.5 };
    let coefficients = SweepCoefficients::new(tube_rig(&tube, 4, 8).rest());
    let bindings = vec![GpuBinding { cell: coefficients.cells.len() as u32, s: 0.5, phi: 0.5, d: 0.0, h: 0.0 }; 16];
    let records = vec![Vec4::ZERO; 16];
    cpu_fast::deform::deform_with_normals(&coefficients.cells, &bindings, &records, &mut [0.0; 48], &mut [0.0; 48]);
}

#[test]
fn fast_mesh_keeps_jacobian_normals() {
    // The whole fast path: bind with a falloff band, deform with normals; the positions are the
    // plain deform's, the normals the twin's from the same bindings, the band's normals kept.
    let tube = Tube::with_vertex_count(20_000, 4.0, 0.5);
    let mesh = tube.mesh();
    let rig = attached_tube_rig(&tube, 8, 16, 1.0);
    let owners = rig.owners(&mesh, "tube").unwrap();
    let weights = rig.band_weights(&mesh, &owners);
    let positions = cpu::packed(&mesh.positions);
    let normals = rest_normals(&mesh);
    let posed = rig.pose(&POSE.keys(&rig)).unwrap();

    let mut plain = FastMesh::bind(rig.rest(), &owners, &weights, &positions);
    let mut plain_positions = positions.clone();
    plain.deform(&posed, &mut plain_positions).unwrap();
    let mut fast = FastMesh::bind(rig.rest(), &owners, &weights, &positions).with_rest_normals(&normals);
    let (mut fast_positions, mut fast_normals) = (positions.clone(), normals.clone());
    fast.deform_with_normals(&posed, &mut fast_positions, &mut fast_normals).unwrap();

    let (error, ulps, worst) = common::worst_f32(&fast_positions, &plain_positions);
    println!("FastMesh: positions vs plain deform, max |Δ| {error:.2e} ({ulps} ULP) at vertex {}", worst / 3);
    assert!(error as f64 <= POSITION_TOLERANCE * mesh.diagonal());

    let rest_cells = SweepCoefficients::new(rig.rest());
    let records = cpu::jacobian::coordinates(&rest_cells.cells, &fast.bindings, &normals);
    let mut posed_cells = SweepCoefficients::new(rig.rest());
    posed_cells.update(&posed).unwrap();
    let (mut twin_positions, mut twin_normals) = (positions.clone(), normals.clone());
    cpu::deform::deform_with_normals(
        &posed_cells.cells,
        &fast.bindings,
        &records,
        &mut twin_positions,
        &mut twin_normals,
    );
    let (turn, at_vertex) = worst_angle(&fast_normals, &twin_normals);
    let (rest_turn, _) = worst_angle(&normals, &twin_normals);
    println!("FastMesh: normals vs twin worst {turn:.2e} rad at vertex {at_vertex}; rest normals {rest_turn:.2e} rad");
    assert!(turn <= NORMAL_TOLERANCE && rest_turn > 100.0 * NORMAL_TOLERANCE);
    let band: Vec<usize> = weights.iter().map(|w| w.vertex as usize).collect();
    assert!(!band.is_empty());
    assert!(band.iter().all(|&i| at(&fast_normals, i) == at(&normals, i)), "a band vertex's normal changed");
}

#[test]
#[ignore = "a timing, not a check: cargo test --release --test cpu_fast_normals -- --ignored --nocapture"]
fn fused_throughput_on_a_million_vertex_tube() {
    // The fused fast deform against the plain fast deform and the twin's fused deform, rounds
    // alternating, medians of 15.
    let tube = Tube::with_vertex_count(1_000_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let n = mesh.positions.len();
    let positions = cpu::packed(&mesh.positions);
    let normals = rest_normals(&mesh);
    let bindings = cpu::bind::bind_to(rig.rest(), &vec![0; n], &positions);
    let records = cpu::jacobian::coordinates(&SweepCoefficients::new(rig.rest()).cells, &bindings, &normals);
    let mut posed = SweepCoefficients::new(rig.rest());
    posed.update(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let cells = &posed.cells;
    let (mut out, mut out_normals) = (positions.clone(), normals.clone());
    let mut samples = [Vec::new(), Vec::new(), Vec::new()];
    for _ in 0..15 {
        for (k, samples) in samples.iter_mut().enumerate() {
            let start = std::time::Instant::now();
            match k {
                0 => cpu_fast::deform::deform(cells, &bindings, &mut out),
                1 => cpu_fast::deform::deform_with_normals(cells, &bindings, &records, &mut out, &mut out_normals),
                _ => cpu::deform::deform_with_normals(cells, &bindings, &records, &mut out, &mut out_normals),
            }
            samples.push(start.elapsed().as_secs_f64());
        }
    }
    let [plain, fused, twin] = samples.map(|mut s| {
        s.sort_by(f64::total_cmp);
        n as f64 / s[s.len() / 2] / 1e6
    });
    println!(
        "1M tube ({}): fast deform {plain:.1} M vertices/s, fast deform + normals {fused:.1} ({:.2} × the plain \
         deform's time), twin deform + normals {twin:.1} (fast fused {:.2} × its speed)",
        Isa::detect().name(),
        plain / fused,
        fused / twin
    );
}
