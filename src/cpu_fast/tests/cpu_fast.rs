//! The fast CPU path (`sweepffd::cpu_fast`, `--backend cpu`) against the f32 twins of the GPU
//! kernels, on every instruction set this CPU runs (the detected one and the scalar fallback):
//! binding within |Δt| ≤ 1e-5 (and s in fact bit for bit), positions within 1e-5 × the
//! bounding-box diagonal, the tolerances the GPU meets against the same twins
//! (tests/gpu_equivalence.rs). Each check prints the maximum
//! absolute error, the maximum ULP distance and the worst vertex, and fails naming them.

use crate::common;

use common::isas::isas;
use sweepffd::bind::falloff::BandWeight;
use sweepffd::coeffs::{BAND_FLAG, BandRecord, GpuBinding, SweepCoefficients, UNOWNED, bind_segments};
use sweepffd::cpu;
use sweepffd::cpu::bind::BindInputs;
use sweepffd::cpu_fast;
use sweepffd::cpu_fast::bands::flagged_owners;
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Sweep;
use sweepffd::synthetic::{BendTwistTaper, Tube, attached_tube_rig, split_tube_rig, tube_rig};

const T_TOLERANCE: f64 = 1e-5;
const POSITION_TOLERANCE: f64 = 1e-5;

const POSE: BendTwistTaper = BendTwistTaper { bend: 1.2, twist: 1.7, taper: 0.6 };

/// The worst |Δt| between two bindings of the same vertices (which must agree on which are
/// bound, and on the band flag), and its vertex.
fn worst_dt(coefficients: &SweepCoefficients, rest: &[Sweep], a: &[GpuBinding], b: &[GpuBinding]) -> (f64, usize) {
    let mut worst = (0.0, 0);
    for (i, (a, b)) in a.iter().zip(b).enumerate() {
        assert_eq!(a.cell == UNOWNED, b.cell == UNOWNED, "vertex {i} bound on one side only: {a:?}, {b:?}");
        assert_eq!(a.cell & BAND_FLAG, b.cell & BAND_FLAG, "vertex {i} in a band on one side only");
        if a.cell == UNOWNED {
            continue;
        }
        let t = |binding: &GpuBinding| coefficients.reference_binding(rest, binding).params.t;
        let dt = (t(a) - t(b)).abs();
        if dt > worst.0 {
            worst = (dt, i);
        }
    }
    worst
}

/// Binds `positions` (owners `owners`, bands `weights`) to `rig` and deforms them by `POSE` on
/// the twins and on the fast path, and checks each instruction set's bindings and positions
/// against the twins'; `diagonal` scales the position tolerance.
fn check_raw(name: &str, rig: &Rig, owners: &[u32], weights: &[BandWeight], positions: &[f32], diagonal: f64) {
    let rest = rig.rest();
    let coefficients = SweepCoefficients::new(rest);
    let tables = bind_segments(rest);
    let inputs = BindInputs { cells: &coefficients.cells, bind_segments: &tables, sweeps: &coefficients.sweeps };
    let flagged = flagged_owners(owners, weights);
    let mut posed = SweepCoefficients::new(rest);
    posed.update(&rig.pose(&POSE.keys(rig)).unwrap()).unwrap();

    // The twins: bind, band records (the bind and band-pack kernels' twins over the band
    // vertices), deform, band.
    let twin_bindings = cpu::bind::bind(&inputs, &flagged, positions);
    let records: Vec<BandRecord> = weights
        .iter()
        .map(|w| {
            let second = cpu::bind::bind_vertex(&inputs, w.neighbour, position(positions, w.vertex as usize));
            let mut record = BandRecord { vertex: w.vertex, weight: w.weight as f32, cell: 0, s_phi: 0 };
            cpu::band_pack::band_pack_vertex(&second, &mut record);
            record
        })
        .collect();
    let mut twin = positions.to_vec();
    cpu::deform::deform(&posed.cells, &twin_bindings, &mut twin);
    cpu::band::band(&posed.cells, &coefficients.cells, &twin_bindings, &records, &mut twin);

    assert_eq!(cpu_fast::bands::band_records(&inputs, weights, positions), records, "{name}: band records");
    for isa in isas() {
        let mut bindings = vec![GpuBinding::default(); owners.len()];
        cpu_fast::bind::bind_with(isa, &inputs, &flagged, positions, &mut bindings);
        let (dt, at) = worst_dt(&coefficients, rest, &bindings, &twin_bindings);
        // The fast root finding keeps the twin's rounding (no fused multiply-adds), so s is the
        // twin's bit for bit; φ, d and h are the twin's to rounding.
        let other_s = bindings.iter().zip(&twin_bindings).filter(|(a, b)| a.s != b.s).count();
        let other_cell = bindings.iter().zip(&twin_bindings).filter(|(a, b)| a.cell != b.cell).count();
        println!(
            "{name} ({}): bind, worst |Δt| {dt:.2e} at vertex {at}; s differs at {other_s}, the cell at {other_cell}",
            isa.name()
        );
        assert_eq!(other_s, 0, "{name} ({}): s differs from the twin's", isa.name());
        assert!(
            dt <= T_TOLERANCE,
            "{name} ({}): |Δt| {dt:e} at vertex {at}: fast {:?}, twin {:?}",
            isa.name(),
            bindings[at],
            twin_bindings[at]
        );

        // The twins' bindings on the fast deform, then the fast bindings: the one isolates the
        // deform, the other is the whole fast path.
        for (what, bindings) in [("twin bindings", &twin_bindings), ("fast bindings", &bindings)] {
            let mut fast = positions.to_vec();
            cpu_fast::deform::deform_with(isa, &posed.cells, bindings, &mut fast);
            cpu_fast::bands::deform_bands(&posed.cells, &coefficients.cells, bindings, &records, &mut fast);
            let (error, ulps, at) = common::worst_f32(&fast, &twin);
            println!(
                "{name} ({}, {what}): deform, max |Δ| {error:.3e} ({:.2e} × diagonal), max {ulps} ULP, worst vertex {}",
                isa.name(),
                error as f64 / diagonal,
                at / 3
            );
            assert!(
                error as f64 <= POSITION_TOLERANCE * diagonal,
                "{name} ({}, {what}): max |Δposition| {error:e} (> {POSITION_TOLERANCE:e} × diagonal {diagonal}), \
                 max {ulps} ULP, worst vertex {}",
                isa.name(),
                at / 3
            );
        }
    }
}

fn position(positions: &[f32], i: usize) -> glam::Vec3 {
    glam::Vec3::from_slice(&positions[3 * i..3 * i + 3])
}

/// [`check_raw`] on a mesh and its rig, with the rig's falloff bands.
fn check(name: &str, mesh: &Mesh, rig: &Rig) {
    let owners = rig.owners(mesh, name).unwrap();
    let weights = rig.band_weights(mesh, &owners);
    check_raw(name, rig, &owners, &weights, &cpu::packed(&mesh.positions), mesh.diagonal());
}

fn check_shared(file: &str) {
    let Some(path) = common::shared_mesh(file) else { return };
    let mesh = Mesh::load(&path).unwrap();
    check(file, &mesh, &common::axis_rig(&mesh, 9, 16));
}

#[test]
fn bunny_on_the_fast_path_matches_the_twin() {
    check_shared("bunny_stanford_zipper.obj");
}

#[test]
fn newell_teapot_on_the_fast_path_matches_the_twin() {
    check_shared("teapot_newell.obj");
}

#[test]
fn armadillo_on_the_fast_path_matches_the_twin() {
    check_shared("armadillo_50k.obj");
}

#[test]
fn four_million_vertices_on_the_fast_path_match_the_twin() {
    let tube = Tube::with_vertex_count(4_000_000, 4.0, 0.5);
    check("tube 4M", &tube.mesh(), &tube_rig(&tube, 8, 16));
}

#[test]
fn bands_fading_into_the_rest_and_into_a_neighbour_match_the_twin() {
    // 99 842 vertices: not a multiple of the eight lanes.
    let tube = Tube::with_vertex_count(100_000, 4.0, 0.5);
    let mesh = tube.mesh();
    assert_ne!(mesh.positions.len() % 8, 0);
    for (name, rig) in [
        ("tube fading to rest", attached_tube_rig(&tube, 8, 16, 1.0)),
        ("tube of two sweeps", split_tube_rig(&tube, 4, 16, 0.5)),
    ] {
        let owners = rig.owners(&mesh, name).unwrap();
        let weights = rig.band_weights(&mesh, &owners);
        assert!(weights.len() > mesh.positions.len() / 10, "{name}: {} band vertices", weights.len());
        check_raw(name, &rig, &owners, &weights, &cpu::packed(&mesh.positions), mesh.diagonal());
    }
}

#[test]
fn falloff_test_tubes_match_the_twin() {
    for (name, (mesh, rig)) in [
        ("attached arm", common::falloff_tubes::attached_arm(1.5)),
        ("split tube", common::falloff_tubes::split_tube(1.0)),
    ] {
        check(name, &mesh, &rig);
    }
}

#[test]
fn empty_and_tiny_meshes_and_ragged_tails_match_the_twin() {
    let tube = Tube { rings: 40, around: 32, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let rig = tube_rig(&tube, 8, 16);
    let all = cpu::packed(&mesh.positions);
    for n in [0, 1, 2, 7, 8, 9, 15, 16, 17, 23, 1003] {
        let owners = vec![0; n];
        check_raw(&format!("{n} vertices"), &rig, &owners, &[], &all[..3 * n], mesh.diagonal());
    }
}

#[test]
fn batches_mixing_cells_unowned_and_band_vertices_match_the_twin() {
    // Every third vertex unowned, every fifth in a band fading to rest: no batch of eight is
    // uniform, and the tails of chunks are ragged.
    let tube = Tube { rings: 70, around: 20, length: 4.0, radius: 0.5 };
    let mesh = tube.mesh();
    let rig = tube_rig(&tube, 6, 7);
    let n = mesh.positions.len();
    let owners: Vec<u32> = (0..n).map(|i| if i % 3 == 0 { UNOWNED } else { 0 }).collect();
    let weights: Vec<BandWeight> = (0..n as u32)
        .filter(|&v| v % 5 == 1 && owners[v as usize] != UNOWNED)
        .map(|vertex| BandWeight { vertex, weight: (vertex % 7) as f64 / 7.0, neighbour: UNOWNED })
        .collect();
    check_raw("mixed batches", &rig, &owners, &weights, &cpu::packed(&mesh.positions), mesh.diagonal());
}

#[test]
fn the_fast_deform_leaves_unbound_and_band_vertices_alone() {
    let tube = Tube { rings: 10, around: 16, length: 2.0, radius: 0.5 };
    let rig = tube_rig(&tube, 4, 8);
    let mut posed = SweepCoefficients::new(rig.rest());
    posed.update(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let bound = GpuBinding { cell: 3, s: 0.4, phi: 0.6, d: 0.1, h: 0.0 };
    let left = [GpuBinding { cell: UNOWNED, ..bound }, GpuBinding { cell: 3 | BAND_FLAG, ..bound }];
    for isa in isas() {
        let bindings: Vec<GpuBinding> = (0..24).map(|i| if i % 4 == 1 { left[i % 2] } else { bound }).collect();
        let mut positions = vec![f32::NAN; 3 * bindings.len()];
        cpu_fast::deform::deform_with(isa, &posed.cells, &bindings, &mut positions);
        for (i, (xyz, binding)) in positions.chunks_exact(3).zip(&bindings).enumerate() {
            let moved = binding.cell == 3;
            assert_eq!(xyz.iter().all(|x| x.is_finite()), moved, "{}: vertex {i}: {xyz:?}", isa.name());
        }
    }
}

#[test]
#[should_panic(expected = "cell")]
fn a_binding_past_the_cells_panics() {
    let tube = Tube { rings: 10, around: 16, length: 2.0, radius: 0.5 };
    let coefficients = SweepCoefficients::new(tube_rig(&tube, 4, 8).rest());
    let bindings = vec![GpuBinding { cell: coefficients.cells.len() as u32, s: 0.5, phi: 0.5, d: 0.0, h: 0.0 }; 16];
    cpu_fast::deform::deform(&coefficients.cells, &bindings, &mut [0.0; 48]);
}

#[test]
#[ignore = "a timing, not a check: cargo test --release --test cpu_fast -- --ignored --nocapture"]
fn shuffled_vertex_order_throughput() {
    // A tube's vertices in a scrambled order, so that no batch of eight shares a cell: the
    // fast deform's lane-by-lane coefficient path, against the twin.
    let tube = Tube::with_vertex_count(1_000_000, 4.0, 0.5);
    let rig = tube_rig(&tube, 8, 16);
    let mesh = tube.mesh();
    let n = mesh.positions.len();
    let order: Vec<usize> = (0..n).map(|i| (i * 7_919) % n).collect();
    let positions: Vec<f32> = order.iter().flat_map(|&i| mesh.positions[i].as_vec3().to_array()).collect();
    let bindings = cpu::bind::bind_to(rig.rest(), &vec![0; n], &positions);
    let mut posed = SweepCoefficients::new(rig.rest());
    posed.update(&rig.pose(&POSE.keys(&rig)).unwrap()).unwrap();
    let mut out = positions.clone();
    let time = |work: &mut dyn FnMut()| {
        let mut samples: Vec<f64> = (0..7)
            .map(|_| {
                let start = std::time::Instant::now();
                work();
                start.elapsed().as_secs_f64()
            })
            .collect();
        samples.sort_by(f64::total_cmp);
        n as f64 / samples[3] / 1e6
    };
    let fast = time(&mut || cpu_fast::deform::deform(&posed.cells, &bindings, &mut out));
    let twin = time(&mut || cpu::deform::deform(&posed.cells, &bindings, &mut out));
    println!("shuffled 1M tube: fast {fast:.1} M vertices/s, twin {twin:.1} M vertices/s");
}
