// The cell groups of one chunk's vertices (src/gpu/deformer/cell_groups.rs): a counting sort of
// its deformed vertices by (block, cell), where a block is params.block_size consecutive
// vertices, so that the groups follow the mesh's vertex order from block to block and the deform
// kernel reads the bindings and writes the positions near where it did a moment before. Made at
// creation after binding and again when the falloff bands change, in seven passes:
// cell_order_clear_main frees every slot, cell_order_count_main counts the vertices of each
// bucket (a block's cell), cell_order_sums_main, cell_order_scan_main and
// cell_order_offsets_main turn the counts (each rounded up to a multiple of CELL_GROUP) into
// where each bucket's slots start (a scan of runs of SCAN_RUN buckets, then of the runs' sums),
// cell_order_scatter_main writes every vertex into a slot of its bucket, and cell_order_fill_main
// fills a group's free slots with its first vertex (deformed again, to the same position), so
// that the deform kernel tests no slot. Vertices in falloff bands (the band kernel moves them)
// and unbound ones are in no group; the groups past the last bucket's are free (UNOWNED) and the
// deform dispatches, indirect, stop short of them. No invocation loops more than a few thousand
// times: llvmpipe ends an invocation's loops after 65,535 iterations in all.
// Composed after layout.wgsl. Twin: src/cpu/cell_order.rs.

@group(0) @binding(0) var<uniform> params: CellOrderParams;
@group(0) @binding(1) var<storage, read> bindings: array<vec4<u32>>;
// Per bucket: its vertex count (count pass), then the next free slot of its range (scan and
// scatter passes).
@group(0) @binding(2) var<storage, read_write> cursors: array<atomic<u32>>;
// params.slot_count entries: CELL_GROUP per group.
@group(0) @binding(3) var<storage, read_write> groups_order: array<u32>;
// Written by the scan pass: [0] the groups in use G (copied into the deform dispatches' params,
// InstanceParams.vertex_count), then for deform dispatch k the workgroups (x, y, z) of its
// indirect dispatch, G * shapes[k].x invocations in each of z = shapes[k].y layers. A CPU
// adapter runs every invocation of a workgroup, returned or not: the dispatches cover only the
// groups in use.
@group(0) @binding(4) var<storage, read_write> dispatch_args: array<u32>;
// Per deform dispatch: its invocations per group in use in one layer (1, or the flat instanced
// kernel's instance layers) and its workgroup layers (its instances, or 1 when numbered flat).
@group(0) @binding(5) var<storage, read> shapes: array<vec2<u32>>;
// Per run of SCAN_RUN buckets: the sum of its rounded-up counts (sums pass), then the slot its
// first bucket starts at (scan pass).
@group(0) @binding(6) var<storage, read_write> run_starts: array<u32>;

// Buckets a run of the scan.
const SCAN_RUN: u32 = 64u;

// Lanes of the scan's one workgroup, each summing a run of consecutive buckets.
const SCAN_LANES: u32 = WORKGROUP_SIZE;
var<workgroup> run_totals: array<u32, SCAN_LANES>;

// The bucket of vertex i, or UNOWNED if it is in no group (unbound, in a band, or past the cells).
fn bucket_of(i: u32) -> u32 {
    let x = bindings[i].x;
    if (!is_plain(x) || plain_cell(x) >= params.cell_count) {
        return UNOWNED;
    }
    let cell = plain_cell(x);
    return i / params.block_size * params.cell_count + cell;
}

fn bucket_count() -> u32 {
    return (params.vertex_count + params.block_size - 1u) / params.block_size * params.cell_count;
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
    let bucket = bucket_of(i);
    if (bucket != UNOWNED) {
        atomicAdd(&cursors[bucket], 1u);
    }
}

fn run_count() -> u32 {
    return (bucket_count() + SCAN_RUN - 1u) / SCAN_RUN;
}

// One invocation a slot.
@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_clear_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let slot = invocation_index(group, groups, lane);
    if (slot < params.slot_count) {
        groups_order[slot] = UNOWNED;
    }
}

// One invocation a run of buckets: its sum.
@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_sums_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let run = invocation_index(group, groups, lane);
    if (run >= run_count()) {
        return;
    }
    let end = min((run + 1u) * SCAN_RUN, bucket_count());
    var total = 0u;
    for (var b = run * SCAN_RUN; b < end; b++) {
        total += round_up_to_group(atomicLoad(&cursors[b]));
    }
    run_starts[run] = total;
}

// One workgroup: lane l takes a share of the runs, sums them, the lanes' sums are scanned in
// workgroup memory, and each lane then writes where each of its runs starts; lane 0 writes the
// groups in use and the deform dispatches' arguments.
@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_scan_main(@builtin(local_invocation_index) lane: u32) {
    let runs = run_count();
    let share = (runs + SCAN_LANES - 1u) / SCAN_LANES;
    let start = min(lane * share, runs);
    let end = min(start + share, runs);
    var total = 0u;
    for (var r = start; r < end; r++) {
        total += run_starts[r];
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
    for (var r = start; r < end; r++) {
        let sum = run_starts[r];
        run_starts[r] = slot;
        slot += sum;
    }
    if (lane == 0u) {
        let groups = run_totals[SCAN_LANES - 1u] / CELL_GROUP;
        dispatch_args[0] = groups;
        for (var k = 0u; k < params.dispatch_count; k++) {
            let workgroups = max((groups * shapes[k].x + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE, 1u);
            let x = min(workgroups, params.max_workgroups);
            dispatch_args[1u + 3u * k] = x;
            dispatch_args[2u + 3u * k] = (workgroups + x - 1u) / x;
            dispatch_args[3u + 3u * k] = shapes[k].y;
        }
    }
}

// One invocation a run of buckets: each bucket's first slot into its cursor.
@compute @workgroup_size(WORKGROUP_SIZE)
fn cell_order_offsets_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let run = invocation_index(group, groups, lane);
    if (run >= run_count()) {
        return;
    }
    let end = min((run + 1u) * SCAN_RUN, bucket_count());
    var slot = run_starts[run];
    for (var b = run * SCAN_RUN; b < end; b++) {
        let count = atomicLoad(&cursors[b]);
        atomicStore(&cursors[b], slot);
        slot += round_up_to_group(count);
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
    let bucket = bucket_of(i);
    if (bucket != UNOWNED) {
        groups_order[atomicAdd(&cursors[bucket], 1u)] = i;
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
