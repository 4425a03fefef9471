// Binding (paper section 3) of every owned vertex: the root t of <v - C(t), N(t)> nearest to v
// (every root found: Bernstein sign variations certify each interval), or the nearer end when
// there is none; then theta, d = |v^_xy| - r(theta, t) and h = v^_z with v^ = R(t)^T (v - C(t)).
// Composed after layout.wgsl, cells_storage.wgsl (binding 1: the rest rig's cell records),
// sweep_eval.wgsl and angle.wgsl. Twin: src/cpu/bind.rs.
// A vertex in a falloff band has BAND_FLAG set in its owner; its binding keeps the flag in its
// cell, so that the deform kernel leaves it to the band kernel.

@group(0) @binding(0) var<uniform> params: DispatchParams;
@group(0) @binding(2) var<storage, read> bind_segments: array<BindSegment>;
@group(0) @binding(3) var<storage, read> sweeps: array<SweepInfo>;
// The owning sweep of each vertex, or UNOWNED.
@group(0) @binding(4) var<storage, read> owners: array<u32>;
// Rest positions, tightly packed xyz.
@group(0) @binding(5) var<storage, read> positions: array<f32>;
@group(0) @binding(6) var<storage, read_write> bindings: array<vec4<u32>>;

const TAU: f32 = 6.283185307179586;
// Dyadic subdivision depth: intervals of width 2^-12 that still show several sign variations
// hold a (near-)double root and report their midpoint.
const MAX_LEVEL: u32 = 12u;
// Refinement stops when the bracket or the Newton step is below this width in s.
const S_TOLERANCE: f32 = 1e-7;
const MAX_REFINE_STEPS: u32 = 32u;

// The nearest root found so far: the first cell of its knot interval (which holds the
// interval's curve and orientation), its local parameter and squared distance.
struct Nearest {
    cell: u32,
    s: f32,
    distance2: f32,
    found: bool,
}

// Power coefficients of g(s) = <v - C(s), n(s)> on a knot interval whose rotations are
// linear (degree 5). The cubic interpolation's nonics (degree 9) have functions of their own
// below, named *_nonic, and only the entry point bind_cubic_main reaches them: sharing one
// array of ten coefficients and a degree, or even a branch to the nonic in the same entry
// point, halves the speed of binding a linear rig on lavapipe.
fn plane_quintic(b: BindSegment, v: vec3<f32>) -> array<f32, 6> {
    let w = v - b.origin.xyz;
    return array<f32, 6>(
        dot(w, b.normal[0].xyz),
        dot(w, b.normal[1].xyz) - b.e_low.x,
        dot(w, b.normal[2].xyz) - b.e_low.y,
        -b.e_low.z,
        -b.e_low.w,
        -b.e_high.x,
    );
}

fn eval_quintic(g: array<f32, 6>, s: f32) -> f32 {
    return g[0] + s * (g[1] + s * (g[2] + s * (g[3] + s * (g[4] + s * g[5]))));
}

fn eval_quintic_derivative(g: array<f32, 6>, s: f32) -> f32 {
    return g[1] + s * (2.0 * g[2] + s * (3.0 * g[3] + s * (4.0 * g[4] + s * 5.0 * g[5])));
}

// Bernstein coefficients of g on [a, a + w]: a Taylor shift to a, a scaling by w, then the
// power-to-Bernstein change of basis for degree 5.
fn bernstein_on(g: array<f32, 6>, a: f32, w: f32) -> array<f32, 6> {
    var c = g;
    // Most intervals visited are the whole of [0, 1] (a = 0, w = 1), which needs neither step.
    if (a != 0.0) {
        for (var k = 0; k < 5; k++) {
            for (var i = 4; i >= k; i--) {
                c[i] += a * c[i + 1];
            }
        }
    }
    if (w != 1.0) {
        var scale = 1.0;
        for (var k = 0; k < 6; k++) {
            c[k] *= scale;
            scale *= w;
        }
    }
    return array<f32, 6>(
        c[0],
        c[0] + 0.2 * c[1],
        c[0] + 0.4 * c[1] + 0.1 * c[2],
        c[0] + 0.6 * c[1] + 0.3 * c[2] + 0.1 * c[3],
        c[0] + 0.8 * c[1] + 0.6 * c[2] + 0.4 * c[3] + 0.2 * c[4],
        c[0] + c[1] + c[2] + c[3] + c[4] + c[5],
    );
}

// Sign variations of Bernstein coefficients, counting 0 as positive.
fn sign_variations(b: array<f32, 6>) -> u32 {
    var count = 0u;
    for (var i = 0; i < 5; i++) {
        if ((b[i] >= 0.0) != (b[i + 1] >= 0.0)) {
            count += 1u;
        }
    }
    return count;
}

// The root of g in [lo, hi], where g(lo) and g(hi) differ in sign: Newton's method kept inside
// the shrinking bracket, bisecting when a step would leave it.
fn refine_root(g: array<f32, 6>, lo_in: f32, hi_in: f32, positive_at_lo: bool) -> f32 {
    var lo = lo_in;
    var hi = hi_in;
    var s = 0.5 * (lo + hi);
    for (var step = 0u; step < MAX_REFINE_STEPS; step++) {
        let value = eval_quintic(g, s);
        if (value == 0.0) {
            break;
        }
        if ((value >= 0.0) == positive_at_lo) {
            lo = s;
        } else {
            hi = s;
        }
        let derivative = eval_quintic_derivative(g, s);
        var next = 0.5 * (lo + hi);
        if (derivative != 0.0) {
            let newton = s - value / derivative;
            if (newton > lo && newton < hi) {
                next = newton;
            }
        }
        let moved = abs(next - s);
        s = next;
        if (moved <= S_TOLERANCE || hi - lo <= S_TOLERANCE) {
            break;
        }
    }
    return s;
}

// Keeps root s of the knot interval whose first cell is `cell` if it is nearer to v than the
// nearest so far.
fn consider_root(cell: u32, s: f32, v: vec3<f32>, nearest: ptr<function, Nearest>) {
    let offset = v - curve_at(cells[cell], s);
    let distance2 = dot(offset, offset);
    if (!(*nearest).found || distance2 < (*nearest).distance2) {
        *nearest = Nearest(cell, s, distance2, true);
    }
}

// Every root on knot interval k (first cell `cell`): visits the dyadic subintervals of [0, 1]
// depth first without a stack (level, index encode the interval
// [index / 2^level, (index + 1) / 2^level]), refining every certified root.
fn roots_on_segment(k: u32, cell: u32, v: vec3<f32>, nearest: ptr<function, Nearest>, nonics: bool) {
    if (nonics && bind_segments[k].degree == 9u) {
        roots_on_nonic_segment(k, cell, v, nearest);
        return;
    }
    let g = plane_quintic(bind_segments[k], v);
    if (g[0] == 0.0) {
        consider_root(cell, 0.0, v, nearest);
    }
    var level = 0u;
    var index = 0u;
    loop {
        let w = 1.0 / f32(1u << level);
        let a = f32(index) * w;
        let b = bernstein_on(g, a, w);
        let variations = sign_variations(b);
        if (variations > 1u && level < MAX_LEVEL) {
            level += 1u;
            index *= 2u;
            continue;
        }
        if (variations == 1u || (variations > 1u && (b[0] >= 0.0) != (b[5] >= 0.0))) {
            consider_root(cell, refine_root(g, a, a + w, b[0] >= 0.0), v, nearest);
        } else if (variations > 1u) {
            consider_root(cell, a + 0.5 * w, v, nearest);
        }
        // Next interval: climb while on a right child, then step to the right sibling.
        while ((index & 1u) == 1u) {
            index = index >> 1u;
            level -= 1u;
        }
        if (level == 0u) {
            break;
        }
        index += 1u;
    }
    if (eval_quintic(g, 1.0) == 0.0) {
        consider_root(cell, 1.0, v, nearest);
    }
}

// Power coefficients of the nonic g(s) of a knot interval whose rotations are cubic.
fn plane_nonic(b: BindSegment, v: vec3<f32>) -> array<f32, 10> {
    let w = v - b.origin.xyz;
    return array<f32, 10>(
        dot(w, b.normal[0].xyz),
        dot(w, b.normal[1].xyz) - b.e_low.x,
        dot(w, b.normal[2].xyz) - b.e_low.y,
        dot(w, b.normal[3].xyz) - b.e_low.z,
        dot(w, b.normal[4].xyz) - b.e_low.w,
        dot(w, b.normal[5].xyz) - b.e_high.x,
        dot(w, b.normal[6].xyz) - b.e_high.y,
        -b.e_high.z,
        -b.e_high.w,
        -b.e9,
    );
}

fn eval_nonic(g: array<f32, 10>, s: f32) -> f32 {
    return g[0] + s * (g[1] + s * (g[2] + s * (g[3] + s * (g[4] + s * (g[5] + s * (g[6] + s * (g[7] + s * (g[8] + s * g[9]))))))));
}

fn eval_nonic_derivative(g: array<f32, 10>, s: f32) -> f32 {
    return g[1] + s * (2.0 * g[2] + s * (3.0 * g[3] + s * (4.0 * g[4] + s * (5.0 * g[5] + s * (6.0 * g[6] + s * (7.0 * g[7] + s * (8.0 * g[8] + s * 9.0 * g[9])))))));
}

// Bernstein coefficients of the nonic on [a, a + w], as bernstein_on does for the quintic;
// b_i = sum_j C(i, j) / C(9, j) c_j.
fn bernstein_on_nonic(g: array<f32, 10>, a: f32, w: f32) -> array<f32, 10> {
    var c = g;
    if (a != 0.0) {
        for (var k = 0; k < 9; k++) {
            for (var i = 8; i >= k; i--) {
                c[i] += a * c[i + 1];
            }
        }
    }
    if (w != 1.0) {
        var scale = 1.0;
        for (var k = 0; k < 10; k++) {
            c[k] *= scale;
            scale *= w;
        }
    }
    return array<f32, 10>(
        c[0],
        c[0] + 0.1111111111111111 * c[1],
        c[0] + 0.2222222222222222 * c[1] + 0.027777777777777776 * c[2],
        c[0] + 0.3333333333333333 * c[1] + 0.08333333333333333 * c[2] + 0.011904761904761904 * c[3],
        c[0] + 0.4444444444444444 * c[1] + 0.16666666666666666 * c[2] + 0.047619047619047616 * c[3] + 0.007936507936507936 * c[4],
        c[0] + 0.5555555555555556 * c[1] + 0.2777777777777778 * c[2] + 0.11904761904761904 * c[3] + 0.03968253968253968 * c[4] + 0.007936507936507936 * c[5],
        c[0] + 0.6666666666666666 * c[1] + 0.4166666666666667 * c[2] + 0.23809523809523808 * c[3] + 0.11904761904761904 * c[4] + 0.047619047619047616 * c[5] + 0.011904761904761904 * c[6],
        c[0] + 0.7777777777777778 * c[1] + 0.5833333333333334 * c[2] + 0.4166666666666667 * c[3] + 0.2777777777777778 * c[4] + 0.16666666666666666 * c[5] + 0.08333333333333333 * c[6] + 0.027777777777777776 * c[7],
        c[0] + 0.8888888888888888 * c[1] + 0.7777777777777778 * c[2] + 0.6666666666666666 * c[3] + 0.5555555555555556 * c[4] + 0.4444444444444444 * c[5] + 0.3333333333333333 * c[6] + 0.2222222222222222 * c[7] + 0.1111111111111111 * c[8],
        c[0] + c[1] + c[2] + c[3] + c[4] + c[5] + c[6] + c[7] + c[8] + c[9],
    );
}

fn sign_variations_nonic(b: array<f32, 10>) -> u32 {
    var count = 0u;
    for (var i = 0; i < 9; i++) {
        if ((b[i] >= 0.0) != (b[i + 1] >= 0.0)) {
            count += 1u;
        }
    }
    return count;
}

// refine_root for the nonic.
fn refine_root_nonic(g: array<f32, 10>, lo_in: f32, hi_in: f32, positive_at_lo: bool) -> f32 {
    var lo = lo_in;
    var hi = hi_in;
    var s = 0.5 * (lo + hi);
    for (var step = 0u; step < MAX_REFINE_STEPS; step++) {
        let value = eval_nonic(g, s);
        if (value == 0.0) {
            break;
        }
        if ((value >= 0.0) == positive_at_lo) {
            lo = s;
        } else {
            hi = s;
        }
        let derivative = eval_nonic_derivative(g, s);
        var next = 0.5 * (lo + hi);
        if (derivative != 0.0) {
            let newton = s - value / derivative;
            if (newton > lo && newton < hi) {
                next = newton;
            }
        }
        let moved = abs(next - s);
        s = next;
        if (moved <= S_TOLERANCE || hi - lo <= S_TOLERANCE) {
            break;
        }
    }
    return s;
}

// roots_on_segment for a knot interval whose rotations are cubic.
fn roots_on_nonic_segment(k: u32, cell: u32, v: vec3<f32>, nearest: ptr<function, Nearest>) {
    let g = plane_nonic(bind_segments[k], v);
    if (g[0] == 0.0) {
        consider_root(cell, 0.0, v, nearest);
    }
    var level = 0u;
    var index = 0u;
    loop {
        let w = 1.0 / f32(1u << level);
        let a = f32(index) * w;
        let b = bernstein_on_nonic(g, a, w);
        let variations = sign_variations_nonic(b);
        if (variations > 1u && level < MAX_LEVEL) {
            level += 1u;
            index *= 2u;
            continue;
        }
        if (variations == 1u || (variations > 1u && (b[0] >= 0.0) != (b[9] >= 0.0))) {
            consider_root(cell, refine_root_nonic(g, a, a + w, b[0] >= 0.0), v, nearest);
        } else if (variations > 1u) {
            consider_root(cell, a + 0.5 * w, v, nearest);
        }
        while ((index & 1u) == 1u) {
            index = index >> 1u;
            level -= 1u;
        }
        if (level == 0u) {
            break;
        }
        index += 1u;
    }
    if (eval_nonic(g, 1.0) == 0.0) {
        consider_root(cell, 1.0, v, nearest);
    }
}

// Binds vertices of sweeps whose rotations are linear.
@compute @workgroup_size(WORKGROUP_SIZE)
fn bind_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    bind_invocation(invocation_index(group, groups, lane), false);
}

// Binds vertices of any sweep, those whose rotations are cubic included.
@compute @workgroup_size(WORKGROUP_SIZE)
fn bind_cubic_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    bind_invocation(invocation_index(group, groups, lane), true);
}

// The binding of vertex i; `nonics`: whether some knot interval's polynomial is a nonic.
fn bind_invocation(i: u32, nonics: bool) {
    if (i >= params.vertex_count) {
        return;
    }
    let flagged_owner = owners[i];
    if (flagged_owner == UNOWNED) {
        bindings[i] = vec4<u32>(UNOWNED, 0u, 0u, 0u);
        return;
    }
    let band = flagged_owner & BAND_FLAG;
    let owner = flagged_owner & ~BAND_FLAG;
    let v = vec3<f32>(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]);
    let sweep = sweeps[owner];
    var nearest = Nearest(sweep.first_cell, 0.0, 0.0, false);
    for (var k = 0u; k < sweep.segment_count; k++) {
        roots_on_segment(sweep.first_segment + k, sweep.first_cell + k * sweep.samples, v, &nearest, nonics);
    }
    if (!nearest.found) {
        // Beyond an end: the nearer of C(0) and C(1).
        let last = sweep.first_cell + (sweep.segment_count - 1u) * sweep.samples;
        let to_start = v - curve_at(cells[sweep.first_cell], 0.0);
        let to_end = v - curve_at(cells[last], 1.0);
        if (dot(to_end, to_end) < dot(to_start, to_start)) {
            nearest = Nearest(last, 1.0, 0.0, true);
        }
    }
    let interval = cells[nearest.cell];
    let local = rotate_inverse(quat_at(interval, nearest.s), v - curve_at(interval, nearest.s));
    // The interval's first cell is turned by its middle angle pi / M. On the axis theta is
    // arbitrary: every path pins it to 0.
    var theta = 0.0;
    if (local.x != 0.0 || local.y != 0.0) {
        theta = interval.curve[0].w + angle_of(local.x, local.y);
    }
    if (theta < 0.0) {
        theta += TAU;
    }
    if (theta >= TAU) {
        theta -= TAU;
    }
    let x = theta * (f32(sweep.samples) / TAU);
    let j = min(u32(x), sweep.samples - 1u);
    let phi = clamp(x - f32(j), 0.0, 1.0);
    let cell = nearest.cell + j;
    let r = radius_at(cells[cell], nearest.s, phi);
    bindings[i] = pack_binding(GpuBinding(cell | band, nearest.s, phi, length(local.xy) - r, local.z));
}
