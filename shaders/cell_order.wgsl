// The cell groups of one chunk's vertices (src/gpu/deformer/cell_groups.rs), a counting sort of
// its bound vertices by cell, made at creation after binding and again when the falloff bands
// change, in four passes: cell_order_count_main counts the vertices of each cell,
// cell_order_scan_main turns the counts (each rounded up to a multiple of CELL_GROUP) into where
// each cell's slots start, cell_order_scatter_main writes every vertex into a slot of its cell,
// and cell_order_fill_main fills a group's free slots with its first vertex (deformed again,
// to the same position), so that the deform kernel tests no slot. Vertices in falloff bands
// (the band kernel moves them) and unbound ones are in no group; the groups past the last
// cell's are free (UNOWNED) and the deform kernel skips them.
// Composed after layout.wgsl. Twin: src/cpu/cell_order.rs.

@group(0) @binding(0) var<uniform> params: CellOrderParams;
@group(0) @binding(1) var<storage, read> bindings: array<GpuBinding>;
// Per cell: its vertex count (count pass), then the next free slot of its range (scan and
// scatter passes).
@group(0) @binding(2) var<storage, read_write> cursors: array<atomic<u32>>;
// params.slot_count entries: CELL_GROUP per group.
@group(0) @binding(3) var<storage, read_write> groups_order: array<u32>;

// Lanes of the scan's one workgroup, each summing a run of consecutive cells.
const SCAN_LANES: u32 = WORKGROUP_SIZE;
var<workgroup> run_totals: array<u32, SCAN_LANES>;

// The cell of vertex i, or UNOWNED if it is in no group (unbound, in a band, or past the cells).
fn grouped_cell(i: u32) -> u32 {
    let cell = bindings[i].cell;
    return select(UNOWNED, cell, cell < params.cell_count);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_count_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let cell = grouped_cell(i);
    if (cell != UNOWNED) {
        atomicAdd(&cursors[cell], 1u);
    }
}

// One workgroup: lane l takes cells [l * run, (l + 1) * run), sums their rounded-up counts, the
// lanes' sums are scanned in workgroup memory, and each lane then walks its cells again, writing
// each cell's first slot into its cursor and UNOWNED into its free slots (the fill pass replaces
// them); the slots past the last cell's are free too.
@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_scan_main(@builtin(local_invocation_index) lane: u32) {
    let run = (params.cell_count + SCAN_LANES - 1u) / SCAN_LANES;
    let start = min(lane * run, params.cell_count);
    let end = min(start + run, params.cell_count);
    var total = 0u;
    for (var c = start; c < end; c++) {
        total += round_up_to_group(atomicLoad(&cursors[c]));
    }
    run_totals[lane] = total;
    workgroupBarrier();
    // Inclusive Hillis-Steele scan of the lanes' totals.
    for (var step = 1u; step < SCAN_LANES; step *= 2u) {
        var before = 0u;
        if (lane >= step) {
            before = run_totals[lane - step];
        }
        workgroupBarrier();
        run_totals[lane] += before;
        workgroupBarrier();
    }
    var slot = run_totals[lane] - total;
    for (var c = start; c < end; c++) {
        let count = atomicLoad(&cursors[c]);
        atomicStore(&cursors[c], slot);
        for (var free = slot + count; free < slot + round_up_to_group(count); free++) {
            groups_order[free] = UNOWNED;
        }
        slot += round_up_to_group(count);
    }
    for (var free = run_totals[SCAN_LANES - 1u] + lane; free < params.slot_count; free += SCAN_LANES) {
        groups_order[free] = UNOWNED;
    }
}

fn round_up_to_group(count: u32) -> u32 {
    return (count + CELL_GROUP - 1u) / CELL_GROUP * CELL_GROUP;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_scatter_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let i = invocation_index(group, groups, lane);
    if (i >= params.vertex_count) {
        return;
    }
    let cell = grouped_cell(i);
    if (cell != UNOWNED) {
        groups_order[atomicAdd(&cursors[cell], 1u)] = i;
    }
}

// One invocation a group.
@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_fill_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let g = invocation_index(group, groups, lane);
    if (g >= params.slot_count / CELL_GROUP) {
        return;
    }
    let first = groups_order[CELL_GROUP * g];
    if (first == UNOWNED) {
        return;
    }
    for (var k = 1u; k < CELL_GROUP; k++) {
        if (groups_order[CELL_GROUP * g + k] == UNOWNED) {
            groups_order[CELL_GROUP * g + k] = first;
        }
    }
}
