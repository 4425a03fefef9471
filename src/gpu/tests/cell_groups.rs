//! The deform kernel over cell groups (`shaders/deform_groups.wgsl`, `src/gpu/deformer/cell_groups.rs`):
//! the GPU's counting sort makes the twin's groups (`src/cpu/cell_order.rs`) up to the order of
//! each cell's vertices, and the positions equal the per-vertex kernel's to the bit, for one
//! instance and for several, with falloff bands, after the bands change, with a rig too large
//! for the uniform cell records, and with precomputed bindings.

use crate::common;

use common::falloff_tubes::{attached_arm, split_tube};
use sweepffd::coeffs::{CELL_GROUP, SweepCoefficients, UNOWNED};
use sweepffd::cpu::cell_order::{cell_groups, grouped_cell};
use sweepffd::gpu::{BindingSource, DeformOrder, DeformerDescriptor, GpuContext, GpuDeformer, rest_positions};
use sweepffd::mesh::Mesh;
use sweepffd::rig::Rig;
use sweepffd::sweep::Sweep;
use sweepffd::synthetic::{BendTwistTaper, Tube, tube_rig};

/// Pose `i` of `n`: bend, twist and taper each different.
fn pose(rig: &Rig, i: usize, n: usize) -> Vec<Sweep> {
    let f = (i + 1) as f64 / n as f64;
    rig.pose(&BendTwistTaper { bend: 1.6 * f - 0.5, twist: 2.0 * f, taper: 0.6 + 0.5 * f }.keys(rig)).unwrap()
}

/// A deformer of `mesh` bound to `rig` (its falloff bands included) in `order`.
fn deformer(
    context: &GpuContext,
    mesh: &Mesh,
    rig: &Rig,
    instances: u32,
    order: DeformOrder,
) -> (GpuDeformer, Vec<[f32; 3]>) {
    let owners = rig.owners(mesh, "tube").unwrap();
    let bands = rig.band_weights(mesh, &owners);
    let positions = rest_positions(&mesh.positions);
    let source = BindingSource::Bind { owners: &owners, bands: &bands };
    let descriptor =
        DeformerDescriptor::new(rig.rest(), &positions, source).with_instances(instances).with_deform_order(order);
    (GpuDeformer::new(context, &descriptor).unwrap(), positions)
}

/// Every instance's positions after one encode of `poses`.
fn deformed(context: &GpuContext, deformer: &mut GpuDeformer, poses: &[Vec<Sweep>]) -> Vec<f32> {
    for (i, posed) in poses.iter().enumerate() {
        deformer.set_pose(i as u32, posed).unwrap();
    }
    let mut encoder = context.device.create_command_encoder(&Default::default());
    deformer.encode(&mut encoder);
    context.queue.submit([encoder.finish()]);
    let n = deformer.instance_count();
    let size = deformer.instance_offset(n - 1) + deformer.vertex_count() as u64 * 12;
    bytemuck::pod_collect_to_vec(&sweepffd::gpu::read_bytes(context, deformer.positions(), 0, size).unwrap())
}

/// Asserts that `grouped`'s groups are the twin's for its bindings, up to the order of each
/// cell's vertices: the same groups free, each group's vertices of the twin's group's cell, and
/// each cell's run of groups holding the same vertices. Returns the number of groups in use.
fn assert_groups_match_the_twin(name: &str, grouped: &GpuDeformer, cells: u32) -> usize {
    let bindings = grouped.read_bindings().unwrap();
    let chunks = grouped.read_cell_groups().unwrap().expect("the deformer runs over cell groups");
    let group = CELL_GROUP as usize;
    let mut used = 0;
    for (first, gpu) in chunks {
        let chunk = &bindings[first as usize..];
        let twin = cell_groups(chunk, cells);
        assert_eq!(gpu.len(), twin.len(), "{name}: slots");
        // The cell of each slot's vertex, None for a free slot.
        let cell_of = |v: u32| if v == UNOWNED { None } else { grouped_cell(&chunk[v as usize], cells) };
        for (g, (ours, theirs)) in gpu.chunks(group).zip(twin.chunks(group)).enumerate() {
            let cell = cell_of(theirs[0]);
            assert!(ours.iter().all(|&v| cell_of(v) == cell), "{name}: group {g} is not all of cell {cell:?}");
            used += cell.is_some() as usize;
        }
        // Each cell's groups are consecutive: the same vertices in them.
        let mut start = 0;
        while start < twin.len() {
            let cell = cell_of(twin[start]);
            let end = (start..twin.len()).step_by(group).find(|&at| cell_of(twin[at]) != cell).unwrap_or(twin.len());
            let set = |slots: &[u32]| {
                let mut set: Vec<u32> = slots.iter().copied().filter(|&v| v != UNOWNED).collect();
                set.sort_unstable();
                set.dedup();
                set
            };
            assert_eq!(set(&gpu[start..end]), set(&twin[start..end]), "{name}: the vertices of cell {cell:?}");
            start = end;
        }
    }
    used
}

/// Asserts that the grouped and per-vertex deformers' positions are equal to the bit.
fn assert_same_positions(name: &str, grouped: &[f32], by_vertex: &[f32]) {
    assert_eq!(grouped.len(), by_vertex.len());
    let differing = grouped.iter().zip(by_vertex).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
    let (error, ulps, at) = common::worst_f32(grouped, by_vertex);
    eprintln!(
        "{name}: {differing} of {} coordinates differ, max |Δ| {error:e}, {ulps} ULP (vertex {})",
        grouped.len(),
        at / 3
    );
    assert_eq!(differing, 0, "{name}: vertex {} differs by {error:e}", at / 3);
}

#[test]
fn groups_and_positions_match_the_per_vertex_kernel() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube { rings: 40, around: 24, length: 4.0, radius: 0.5 };
    let cases: Vec<(&str, Mesh, Rig, u32)> = vec![
        ("one instance", tube.mesh(), tube_rig(&tube, 8, 16), 1),
        // Seven instances: the flat kernel's last invocation holds three of its four.
        ("seven instances", tube.mesh(), tube_rig(&tube, 8, 16), 7),
        // 29 intervals × 16 samples = 464 cells: the storage variant's records.
        ("storage cell records", tube.mesh(), tube_rig(&tube, 30, 16), 1),
        ("arm with a band to rest", attached_arm(1.2).0, attached_arm(1.2).1, 3),
        ("split tube with bands", split_tube(0.8).0, split_tube(0.8).1, 1),
        // Unbound vertices and a band, one instance: the staged kernel reads both back.
        ("arm, one instance", attached_arm(1.2).0, attached_arm(1.2).1, 1),
    ];
    for (name, mesh, rig, instances) in cases {
        let (mut grouped, _) = deformer(context, &mesh, &rig, instances, DeformOrder::CellGroups);
        let (mut by_vertex, _) = deformer(context, &mesh, &rig, instances, DeformOrder::Vertices);
        let (mut staged, _) = deformer(context, &mesh, &rig, instances, DeformOrder::StagedVertices);
        let staged_order = if instances == 1 { DeformOrder::StagedVertices } else { DeformOrder::Vertices };
        assert_eq!(staged.deform_order(), staged_order, "{name}");
        assert_eq!(by_vertex.read_cell_groups().unwrap(), None);
        let cells = SweepCoefficients::new(rig.rest()).cells.len() as u32;
        let used = assert_groups_match_the_twin(name, &grouped, cells);
        let bound = grouped.read_bindings().unwrap().iter().filter(|b| grouped_cell(b, cells).is_some()).count();
        eprintln!("{name}: {bound} vertices deformed in {used} groups of {CELL_GROUP} over {cells} cells");
        assert!(used * CELL_GROUP as usize >= bound && used < bound, "{name}: {used} groups for {bound} vertices");
        let poses: Vec<Vec<Sweep>> = (0..instances as usize).map(|i| pose(&rig, i, instances as usize)).collect();
        let (ours, theirs) = (deformed(context, &mut grouped, &poses), deformed(context, &mut by_vertex, &poses));
        assert_same_positions(name, &ours, &theirs);
        // Positions stored whole by the workgroup equal those stored vertex by vertex.
        assert_same_positions(name, &deformed(context, &mut staged, &poses), &theirs);
        let rest = sweepffd::cpu::packed(&mesh.positions);
        let moved = (0..mesh.positions.len()).filter(|&v| ours[3 * v..3 * v + 3] != rest[3 * v..3 * v + 3]).count();
        // Both deformed (a vertex at the sweep's fixed root may stay).
        assert!(moved * 100 >= bound * 99, "{name}: {moved} vertices moved, {bound} bound");
    }
}

#[test]
fn new_bands_regroup_the_vertices() {
    let Some(context) = common::gpu() else { return };
    for (name, (mesh, before), (_, after)) in [
        ("arm 0 → 1.5", attached_arm(0.0), attached_arm(1.5)),
        ("arm 1.5 → 0.4", attached_arm(1.5), attached_arm(0.4)),
        ("split tube 1.0 → 0", split_tube(1.0), split_tube(0.0)),
    ] {
        let (mut grouped, rest) = deformer(context, &mesh, &before, 1, DeformOrder::CellGroups);
        let (mut by_vertex, _) = deformer(context, &mesh, &before, 1, DeformOrder::Vertices);
        let cells = SweepCoefficients::new(before.rest()).cells.len() as u32;
        let groups_before = grouped.read_cell_groups().unwrap();
        let owners = after.owners(&mesh, "tube").unwrap();
        let weights = after.band_weights(&mesh, &owners);
        for deformer in [&mut grouped, &mut by_vertex] {
            deformer.set_bands(&rest, &weights).unwrap();
        }
        // The groups follow the new band flags: without the new sort they would be the old ones.
        assert_ne!(grouped.read_cell_groups().unwrap(), groups_before, "{name}: the groups did not change");
        assert_groups_match_the_twin(name, &grouped, cells);
        let posed = [pose(&after, 1, 2)];
        let (ours, theirs) = (deformed(context, &mut grouped, &posed), deformed(context, &mut by_vertex, &posed));
        assert_same_positions(name, &ours, &theirs);
    }
}

#[test]
fn precomputed_bindings_deform_over_groups_too() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube { rings: 30, around: 20, length: 4.0, radius: 0.5 };
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 6, 12));
    let (bound, positions) = deformer(context, &mesh, &rig, 1, DeformOrder::Vertices);
    let bindings = bound.read_bindings().unwrap();
    let source = BindingSource::Precomputed { bindings: &bindings, bands: &[] };
    let make = |order| {
        GpuDeformer::new(context, &DeformerDescriptor::new(rig.rest(), &positions, source).with_deform_order(order))
            .unwrap()
    };
    let (mut grouped, mut by_vertex) = (make(DeformOrder::CellGroups), make(DeformOrder::Vertices));
    assert_groups_match_the_twin("precomputed", &grouped, SweepCoefficients::new(rig.rest()).cells.len() as u32);
    let posed = [pose(&rig, 0, 1)];
    let (ours, theirs) = (deformed(context, &mut grouped, &posed), deformed(context, &mut by_vertex, &posed));
    assert_same_positions("precomputed", &ours, &theirs);
}

#[test]
fn auto_groups_on_cpu_adapters_only_and_stages_stores_elsewhere() {
    let Some(context) = common::gpu() else { return };
    let mut info = context.info.clone();
    for (device_type, groups) in [
        (wgpu::DeviceType::Cpu, true),
        (wgpu::DeviceType::DiscreteGpu, false),
        (wgpu::DeviceType::IntegratedGpu, false),
    ] {
        info.device_type = device_type;
        assert_eq!(DeformOrder::Auto.groups_on(&info), groups, "{device_type:?}");
        let auto = if groups { DeformOrder::CellGroups } else { DeformOrder::StagedVertices };
        assert_eq!(DeformOrder::Auto.on_type(device_type), auto);
        assert!(DeformOrder::CellGroups.groups_on(&info));
        assert!(!DeformOrder::Vertices.groups_on(&info));
    }
}

#[test]
fn jacobian_normals_over_groups_equal_the_per_vertex_fused_kernel() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube { rings: 40, around: 24, length: 4.0, radius: 0.5 };
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let owners = rig.owners(&mesh, "tube").unwrap();
    let positions = rest_positions(&mesh.positions);
    let triangles: Vec<u32> = mesh.faces.triangles().flatten().collect();
    for instances in [1, 3] {
        let make = |order| {
            let source = BindingSource::Bind { owners: &owners, bands: &[] };
            let descriptor = DeformerDescriptor::new(rig.rest(), &positions, source)
                .with_triangles(&triangles)
                .with_jacobian_normals()
                .with_instances(instances)
                .with_deform_order(order);
            GpuDeformer::new(context, &descriptor).unwrap()
        };
        let (mut grouped, mut by_vertex) = (make(DeformOrder::CellGroups), make(DeformOrder::Vertices));
        let cells = SweepCoefficients::new(rig.rest()).cells.len() as u32;
        assert!(assert_groups_match_the_twin("fused", &grouped, cells) > 0);
        let poses: Vec<Vec<Sweep>> = (0..instances as usize).map(|i| pose(&rig, i, instances as usize)).collect();
        let name = format!("fused, {instances} instances");
        let (ours, theirs) = (deformed(context, &mut grouped, &poses), deformed(context, &mut by_vertex, &poses));
        assert_same_positions(&name, &ours, &theirs);
        let (ours, theirs) = (grouped.read_normals().unwrap().unwrap(), by_vertex.read_normals().unwrap().unwrap());
        assert_same_positions(&format!("{name}: normals"), &ours, &theirs);
    }
}

/// A 4.2M-vertex tube: 2.3M buckets. A one-workgroup scan looping over them all (the sort's first
/// form) stopped part way on lavapipe, whose invocations end their loops after 65,535 iterations
/// in all, and left the groups past the ones in use unwritten; at 7M vertices it left a third of
/// the mesh at rest. The runs' scan loops a few hundred times an invocation.
#[test]
fn millions_of_buckets_sort_within_the_loop_limits() {
    let Some(context) = common::gpu() else { return };
    let tube = Tube::with_vertex_count(4_200_000, 4.0, 0.5);
    let (mesh, rig) = (tube.mesh(), tube_rig(&tube, 8, 16));
    let (mut grouped, _) = deformer(context, &mesh, &rig, 1, DeformOrder::CellGroups);
    let cells = SweepCoefficients::new(rig.rest()).cells.len() as u32;
    let used = assert_groups_match_the_twin("4.2M tube", &grouped, cells);
    // Each ring is a block and holds 16 vertices of each of 16 cells, give or take the vertices
    // on a cell's edge: few groups are partly free.
    let full = mesh.positions.len() / CELL_GROUP as usize;
    assert!(used >= full && used * 10 <= full * 11, "{used} groups for {} vertices", mesh.positions.len());
    let rest = sweepffd::cpu::packed(&mesh.positions);
    let ours = deformed(context, &mut grouped, &[pose(&rig, 0, 1)]);
    let unmoved = (0..mesh.positions.len()).filter(|&v| ours[3 * v..3 * v + 3] == rest[3 * v..3 * v + 3]).count();
    assert!(unmoved < 100, "{unmoved} vertices at rest");
}
