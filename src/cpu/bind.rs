//! Twin of `shaders/bind.wgsl`: binding (§3) of every owned vertex in f32 — the root t of
//! ⟨v − C(t), N(t)⟩ nearest to v (every root certified by Bernstein sign variations), or the
//! nearer end when there is none; then θ, d = |v̂_xy| − r(θ, t) and h = v̂_z with
//! v̂ = R(t)ᵀ·(v − C(t)).

use std::f32::consts::TAU;

use crate::parallel::prelude::*;
use glam::{Vec3, Vec4, Vec4Swizzles};

use super::angle::angle_of;
use super::position;
use super::sweep_eval::{curve_at, quat_at, radius_at, rotate_inverse};
use crate::coeffs::{
    BAND_FLAG, BindSegment, CellCoeffs, GpuBinding, SweepCoefficients, SweepInfo, UNOWNED, bind_segments,
};
use crate::sweep::Sweep;

/// Dyadic subdivision depth: intervals of width 2⁻¹² that still show several sign variations
/// hold a (near-)double root and report their midpoint.
const MAX_LEVEL: u32 = 12;
/// Refinement stops when the bracket or the Newton step is below this width in s.
const S_TOLERANCE: f32 = 1e-7;
const MAX_REFINE_STEPS: u32 = 32;

/// The kernel's read-only inputs, as bound to it.
#[derive(Clone, Copy, Debug)]
pub struct BindInputs<'a> {
    /// The rest rig's cell records.
    pub cells: &'a [CellCoeffs],
    /// Rest binding polynomials.
    pub bind_segments: &'a [BindSegment],
    /// Where each sweep starts.
    pub sweeps: &'a [SweepInfo],
}

/// The nearest root found so far: the first cell of its knot interval (which holds the
/// interval's curve and orientation), its local parameter and squared distance.
#[derive(Clone, Copy, Debug)]
struct Nearest {
    cell: u32,
    s: f32,
    distance2: f32,
    found: bool,
}

/// The plane polynomial g(s) = ⟨v − C(s), n(s)⟩ of a knot interval: power coefficients
/// `g[0..=degree]`, degree 5 (linear rotation interpolation) or 9 (cubic).
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    /// a0 … a9; those past the degree are 0.
    pub g: [f32; 10],
    /// 5 or 9.
    pub degree: usize,
}

/// The plane polynomial of knot interval `b` for vertex v.
pub fn plane_polynomial(b: &BindSegment, v: Vec3) -> Plane {
    let w = v - Vec4::from_array(b.origin).xyz();
    let dot = |m: usize| w.dot(Vec4::from_array(b.normal[m]).xyz());
    let e = [b.e_low[0], b.e_low[1], b.e_low[2], b.e_low[3], b.e_high[0], b.e_high[1], b.e_high[2], b.e_high[3], b.e9];
    let g = [
        dot(0),
        dot(1) - e[0],
        dot(2) - e[1],
        dot(3) - e[2],
        dot(4) - e[3],
        dot(5) - e[4],
        dot(6) - e[5],
        -e[6],
        -e[7],
        -e[8],
    ];
    Plane { g, degree: b.degree as usize }
}

impl Plane {
    /// g(s) by Horner's rule.
    pub fn at(&self, s: f32) -> f32 {
        let g = &self.g;
        if self.degree == 5 {
            return g[0] + s * (g[1] + s * (g[2] + s * (g[3] + s * (g[4] + s * g[5]))));
        }
        g[0] + s * (g[1] + s * (g[2] + s * (g[3] + s * (g[4] + s * (g[5] + s * (g[6] + s * (g[7] + s * (g[8] + s * g[9]))))))))
    }

    /// g′(s) by Horner's rule.
    pub fn derivative_at(&self, s: f32) -> f32 {
        let g = &self.g;
        if self.degree == 5 {
            return g[1] + s * (2.0 * g[2] + s * (3.0 * g[3] + s * (4.0 * g[4] + s * 5.0 * g[5])));
        }
        g[1] + s
            * (2.0 * g[2]
                + s * (3.0 * g[3]
                    + s * (4.0 * g[4]
                        + s * (5.0 * g[5] + s * (6.0 * g[6] + s * (7.0 * g[7] + s * (8.0 * g[8] + s * 9.0 * g[9])))))))
    }

    /// Bernstein coefficients (the first `degree + 1`) of g on [a, a + w]: a Taylor shift to a,
    /// a scaling by w, then the power-to-Bernstein change of basis.
    #[expect(clippy::needless_range_loop, reason = "mirrors the WGSL")]
    pub fn bernstein_on(&self, a: f32, w: f32) -> [f32; 10] {
        let n = self.degree;
        let mut c = self.g;
        // Most intervals visited are the whole of [0, 1] (a = 0, w = 1), which needs neither step.
        if a != 0.0 {
            for k in 0..n {
                for i in (k..n).rev() {
                    c[i] += a * c[i + 1];
                }
            }
        }
        if w != 1.0 {
            let mut scale = 1.0;
            for k in 0..=n {
                c[k] *= scale;
                scale *= w;
            }
        }
        if n == 5 { quintic_to_bernstein(&c) } else { nonic_to_bernstein(&c) }
    }
}

/// The power-to-Bernstein change of basis for degree 5: b_i = Σ_j C(i, j)/C(5, j)·c_j.
fn quintic_to_bernstein(c: &[f32; 10]) -> [f32; 10] {
    [
        c[0],
        c[0] + 0.2 * c[1],
        c[0] + 0.4 * c[1] + 0.1 * c[2],
        c[0] + 0.6 * c[1] + 0.3 * c[2] + 0.1 * c[3],
        c[0] + 0.8 * c[1] + 0.6 * c[2] + 0.4 * c[3] + 0.2 * c[4],
        c[0] + c[1] + c[2] + c[3] + c[4] + c[5],
        0.0,
        0.0,
        0.0,
        0.0,
    ]
}

/// The power-to-Bernstein change of basis for degree 9: b_i = Σ_j C(i, j)/C(9, j)·c_j.
#[expect(clippy::excessive_precision, reason = "the WGSL twin spells the same literals")]
fn nonic_to_bernstein(c: &[f32; 10]) -> [f32; 10] {
    [
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
    ]
}

/// Sign variations of the first `degree + 1` Bernstein coefficients, counting 0 as positive.
pub fn sign_variations(b: &[f32; 10], degree: usize) -> u32 {
    let mut count = 0;
    for i in 0..degree {
        if (b[i] >= 0.0) != (b[i + 1] >= 0.0) {
            count += 1;
        }
    }
    count
}

/// The root of g in [lo, hi], where g(lo) and g(hi) differ in sign: Newton's method kept inside
/// the shrinking bracket, bisecting when a step would leave it.
fn refine_root(g: &Plane, lo_in: f32, hi_in: f32, positive_at_lo: bool) -> f32 {
    let mut lo = lo_in;
    let mut hi = hi_in;
    let mut s = 0.5 * (lo + hi);
    for _ in 0..MAX_REFINE_STEPS {
        let value = g.at(s);
        if value == 0.0 {
            break;
        }
        if (value >= 0.0) == positive_at_lo {
            lo = s;
        } else {
            hi = s;
        }
        let derivative = g.derivative_at(s);
        let mut next = 0.5 * (lo + hi);
        if derivative != 0.0 {
            let newton = s - value / derivative;
            if newton > lo && newton < hi {
                next = newton;
            }
        }
        let moved = (next - s).abs();
        s = next;
        if moved <= S_TOLERANCE || hi - lo <= S_TOLERANCE {
            break;
        }
    }
    s
}

/// Keeps root s of the knot interval whose first cell is `cell` if it is nearer to v than the
/// nearest so far.
fn consider_root(inputs: &BindInputs, cell: u32, s: f32, v: Vec3, nearest: &mut Nearest) {
    let offset = v - curve_at(&inputs.cells[cell as usize], s);
    let distance2 = offset.dot(offset);
    if !nearest.found || distance2 < nearest.distance2 {
        *nearest = Nearest { cell, s, distance2, found: true };
    }
}

/// Every root on knot interval k (first cell `cell`): visits the dyadic subintervals of [0, 1]
/// depth first without a stack (level, index encode the interval
/// [index/2^level, (index + 1)/2^level]), refining every certified root.
fn roots_on_segment(inputs: &BindInputs, k: u32, cell: u32, v: Vec3, nearest: &mut Nearest) {
    let g = plane_polynomial(&inputs.bind_segments[k as usize], v);
    if g.g[0] == 0.0 {
        consider_root(inputs, cell, 0.0, v, nearest);
    }
    let mut level = 0u32;
    let mut index = 0u32;
    loop {
        let w = 1.0 / (1u32 << level) as f32;
        let a = index as f32 * w;
        let b = g.bernstein_on(a, w);
        let variations = sign_variations(&b, g.degree);
        if variations > 1 && level < MAX_LEVEL {
            level += 1;
            index *= 2;
            continue;
        }
        if variations == 1 || (variations > 1 && (b[0] >= 0.0) != (b[g.degree] >= 0.0)) {
            consider_root(inputs, cell, refine_root(&g, a, a + w, b[0] >= 0.0), v, nearest);
        } else if variations > 1 {
            consider_root(inputs, cell, a + 0.5 * w, v, nearest);
        }
        // Next interval: climb while on a right child, then step to the right sibling.
        while index & 1 == 1 {
            index >>= 1;
            level -= 1;
        }
        if level == 0 {
            break;
        }
        index += 1;
    }
    if g.at(1.0) == 0.0 {
        consider_root(inputs, cell, 1.0, v, nearest);
    }
}

/// One invocation of the kernel: the binding of vertex `v` owned by sweep `flagged_owner` (or
/// [`UNOWNED`]); a [`BAND_FLAG`] on the owner (a vertex in a falloff band) is kept in the cell.
pub fn bind_vertex(inputs: &BindInputs, flagged_owner: u32, v: Vec3) -> GpuBinding {
    if flagged_owner == UNOWNED {
        return GpuBinding { cell: UNOWNED, s: 0.0, phi: 0.0, d: 0.0, h: 0.0 };
    }
    let band = flagged_owner & BAND_FLAG;
    let owner = flagged_owner & !BAND_FLAG;
    let sweep = inputs.sweeps[owner as usize];
    let mut nearest = Nearest { cell: sweep.first_cell, s: 0.0, distance2: 0.0, found: false };
    for k in 0..sweep.segment_count {
        roots_on_segment(inputs, sweep.first_segment + k, sweep.first_cell + k * sweep.samples, v, &mut nearest);
    }
    binding_at(inputs, sweep, nearest.found.then_some((nearest.cell, nearest.s)), v, band)
}

/// The end of [`bind_vertex`] for vertex `v` of sweep `sweep` once its nearest root is known:
/// `nearest` is the first cell of the root's knot interval and its local s, or `None` when there
/// is no root (beyond an end: the nearer of C(0) and C(1)); then θ, the cell and φ,
/// d = |v̂_xy| − r(θ, t) and h = v̂_z with v̂ = R(t)ᵀ·(v − C(t)). `band` is the owner's
/// [`BAND_FLAG`], kept in the cell.
pub fn binding_at(
    inputs: &BindInputs,
    sweep: SweepInfo,
    nearest: Option<(u32, f32)>,
    v: Vec3,
    band: u32,
) -> GpuBinding {
    let (cell, s) = nearest.unwrap_or_else(|| {
        let last = sweep.first_cell + (sweep.segment_count - 1) * sweep.samples;
        let to_start = v - curve_at(&inputs.cells[sweep.first_cell as usize], 0.0);
        let to_end = v - curve_at(&inputs.cells[last as usize], 1.0);
        if to_end.dot(to_end) < to_start.dot(to_start) { (last, 1.0) } else { (sweep.first_cell, 0.0) }
    });
    let interval = &inputs.cells[cell as usize];
    let local = rotate_inverse(quat_at(interval, s), v - curve_at(interval, s));
    // The interval's first cell is turned by its middle angle π/M. On the axis θ is arbitrary:
    // every path pins it to 0.
    let mut theta = 0.0;
    if local.x != 0.0 || local.y != 0.0 {
        theta = interval.curve[0][3] + angle_of(local.x, local.y);
    }
    if theta < 0.0 {
        theta += TAU;
    }
    if theta >= TAU {
        theta -= TAU;
    }
    let x = theta * (sweep.samples as f32 / TAU);
    let j = (x as u32).min(sweep.samples - 1);
    let phi = (x - j as f32).clamp(0.0, 1.0);
    let r = radius_at(&inputs.cells[(cell + j) as usize], s, phi);
    GpuBinding { cell: (cell + j) | band, s, phi, d: local.truncate().length() - r, h: local.z }
}

/// The bindings of `positions` (tightly packed xyz) owned by `owners[i]` to the rest sweeps
/// `rest`: builds the kernel's tables from the sweeps, then runs [`bind`].
pub fn bind_to(rest: &[Sweep], owners: &[u32], positions: &[f32]) -> Vec<GpuBinding> {
    let coefficients = SweepCoefficients::new(rest);
    let tables = bind_segments(rest);
    let inputs = BindInputs { cells: &coefficients.cells, bind_segments: &tables, sweeps: &coefficients.sweeps };
    bind(&inputs, owners, positions)
}

/// Every invocation of the kernel: the binding of each vertex of `positions` (tightly packed
/// xyz) owned by `owners[i]`, in parallel.
pub fn bind(inputs: &BindInputs, owners: &[u32], positions: &[f32]) -> Vec<GpuBinding> {
    (0..owners.len()).into_par_iter().map(|i| bind_vertex(inputs, owners[i], position(positions, i))).collect()
}
