// Area-weighted vertex normals of the deformed mesh: for vertex i, the normalized sum of
// (p_j - p_i) x (p_k - p_i) over its incident triangles (i, j, k), gathered per vertex from its
// precomputed fans of one-ring neighbours (consecutive entries make a triangle; an entry with
// FAN_START begins a new fan; one with FAN_CLOSE also makes the triangle back to its fan's
// first neighbour, kept in a register rather than read twice; FAN_END marks the row's last
// entry, so a row needs only its start), so no atomics are needed. Every read at a varying
// index is a gather, the cost that matters on a CPU device, so the kernel reads each neighbour
// once and no row end. Only the listed vertices (each with at least one entry) are computed:
// all of them once at rest, then per frame those with a moving vertex in their one-ring
// (src/normals/dirty.rs); the others keep their rest normal.
// Composed after layout.wgsl and positions_one_window.wgsl or positions_two_windows.wgsl (which
// define position(v)). Twin: src/cpu/normals.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
// All positions through two windows, each within the storage binding limit: vertices below
// params.window_split are read from the first, the others from the second (a mesh whose
// positions fit one binding binds the same window twice and reads only the first).
@group(0) @binding(1) var<storage, read> positions_low: array<f32>;
@group(0) @binding(2) var<storage, read> positions_high: array<f32>;
// This chunk's vertices (global indices, ascending) and their rows: vertices[l] has fan
// entries from offsets[l] to the first with FAN_END.
@group(0) @binding(3) var<storage, read> vertices: array<u32>;
@group(0) @binding(4) var<storage, read> offsets: array<u32>;
@group(0) @binding(5) var<storage, read> fans: array<u32>;

const FAN_START: u32 = 0x80000000u;
const FAN_CLOSE: u32 = 0x40000000u;
const FAN_END: u32 = 0x20000000u;
const FAN_INDEX: u32 = 0x1fffffffu;
// This chunk's window of the normals buffer, tightly packed xyz, from vertex
// params.first_vertex.
@group(0) @binding(6) var<storage, read_write> normals: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn normals_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let l = invocation_index(group, groups, lane);
    if (l >= params.vertex_count) {
        return;
    }
    let v = vertices[l];
    let p = position(v);
    var sum = vec3<f32>(0.0);
    var previous = vec3<f32>(0.0);
    var first = vec3<f32>(0.0);
    // Every listed row ends with FAN_END; the bound (about 1% of the pass on a CPU device) only
    // keeps a malformed row from hanging the device.
    for (var c = offsets[l]; c < arrayLength(&fans); c++) {
        let entry = fans[c];
        let q = position(entry & FAN_INDEX) - p;
        if ((entry & FAN_START) == 0u) {
            sum += cross(previous, q);
        } else {
            first = q;
        }
        if ((entry & FAN_CLOSE) != 0u) {
            sum += cross(q, first);
        }
        previous = q;
        if ((entry & FAN_END) != 0u) {
            break;
        }
    }
    var n = vec3<f32>(0.0);
    let length2 = dot(sum, sum);
    if (length2 > 0.0) {
        n = sum * inverseSqrt(length2);
    }
    let o = v - params.first_vertex;
    normals[3u * o] = n.x;
    normals[3u * o + 1u] = n.y;
    normals[3u * o + 2u] = n.z;
}
