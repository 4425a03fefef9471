//! The bind kernel's root finding on eight vertices at once (AVX2): for eight vertices owned by
//! one sweep, each knot interval's binding quintic g(s) = ⟨v − C(s), n(s)⟩, its Bernstein
//! coefficients on [0, 1] and their sign variations, and the bracketed Newton refinement of an
//! interval's single root, in registers of eight vertices, with the statements (and the
//! rounding: no fused multiply-adds, so s is the twin's bit for bit) of [`crate::cpu::bind`];
//! then each vertex's θ, cell, φ, d and h from its nearest root, in registers when the eight roots
//! lie on one knot interval (to rounding), else one by one by [`crate::cpu::bind::binding_at`].
//!
//! A vertex whose interval needs subdivision (more than one sign variation), or whose quintic
//! vanishes exactly at an end of an interval, is bound again by the twin alone
//! ([`crate::cpu::bind::bind_vertex`]): such vertices are few.

use std::arch::x86_64::*;

use super::lanes8::{F8, add, cubic, mul, splat, sub, to_array};
use crate::coeffs::{BAND_FLAG, BindSegment, GpuBinding, SweepInfo, UNOWNED};
use crate::cpu::bind::{BindInputs, bind_vertex, binding_at};
use crate::cpu::position;
use crate::cpu::sweep_eval::radius_at;

/// Vertices per batch.
pub const LANES: usize = 8;

/// The twin's refinement limits ([`crate::cpu::bind`]).
const S_TOLERANCE: f32 = 1e-7;
const MAX_REFINE_STEPS: u32 = 32;

/// Lane masks as the comparisons give them: all ones where true.
type Mask = F8;

#[target_feature(enable = "avx2,fma")]
#[inline]
fn and(a: Mask, b: Mask) -> Mask {
    _mm256_and_ps(a, b)
}

#[target_feature(enable = "avx2,fma")]
#[inline]
fn or(a: Mask, b: Mask) -> Mask {
    _mm256_or_ps(a, b)
}

#[target_feature(enable = "avx2,fma")]
#[inline]
fn and_not(a: Mask, b: Mask) -> Mask {
    // a & !b.
    _mm256_andnot_ps(b, a)
}

/// `b` where `mask`, else `a`.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn select(mask: Mask, b: F8, a: F8) -> F8 {
    _mm256_blendv_ps(a, b, mask)
}

#[target_feature(enable = "avx2,fma")]
#[inline]
fn bits(mask: Mask) -> u32 {
    _mm256_movemask_ps(mask) as u32
}

/// x ≥ 0 (ordered: false for NaN, as `>=` in the twin).
#[target_feature(enable = "avx2,fma")]
#[inline]
fn non_negative(x: F8) -> Mask {
    _mm256_cmp_ps::<_CMP_GE_OQ>(x, _mm256_setzero_ps())
}

#[target_feature(enable = "avx2,fma")]
#[inline]
fn equal(a: F8, b: F8) -> Mask {
    _mm256_cmp_ps::<_CMP_EQ_OQ>(a, b)
}

#[target_feature(enable = "avx2,fma")]
#[inline]
fn less(a: F8, b: F8) -> Mask {
    _mm256_cmp_ps::<_CMP_LT_OQ>(a, b)
}

/// A knot interval's g(s) in every lane: g0..g2 per vertex, g3..g5 shared.
struct Quintic {
    g: [F8; 6],
}

impl Quintic {
    /// [`crate::cpu::bind`]'s plane_quintic for the eight vertices `v`.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn new(b: &BindSegment, v: &[F8; 3]) -> Quintic {
        let w = [sub(v[0], splat(b.origin[0])), sub(v[1], splat(b.origin[1])), sub(v[2], splat(b.origin[2]))];
        let dot = |n: &[f32; 4]| add(add(mul(w[0], splat(n[0])), mul(w[1], splat(n[1]))), mul(w[2], splat(n[2])));
        Quintic {
            g: [
                dot(&b.normal[0]),
                sub(dot(&b.normal[1]), splat(b.e_low[0])),
                sub(dot(&b.normal[2]), splat(b.e_low[1])),
                splat(-b.e_low[2]),
                splat(-b.e_low[3]),
                splat(-b.e_high[0]),
            ],
        }
    }

    /// g(s), by Horner's rule.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn at(&self, s: F8) -> F8 {
        let g = &self.g;
        add(g[0], mul(s, add(g[1], mul(s, add(g[2], mul(s, add(g[3], mul(s, add(g[4], mul(s, g[5]))))))))))
    }

    /// g′(s), as the twin spells it.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn derivative_at(&self, s: F8) -> F8 {
        let g = &self.g;
        let k = |c: f32, x: F8| mul(splat(c), x);
        let inner = add(k(4.0, g[4]), mul(mul(s, splat(5.0)), g[5]));
        add(g[1], mul(s, add(k(2.0, g[2]), mul(s, add(k(3.0, g[3]), mul(s, inner))))))
    }

    /// Bernstein coefficients on [0, 1], sums in the twin's order.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn bernstein(&self) -> [F8; 6] {
        let c = &self.g;
        let k = |x: f32, c: F8| mul(splat(x), c);
        [
            c[0],
            add(c[0], k(0.2, c[1])),
            add(add(c[0], k(0.4, c[1])), k(0.1, c[2])),
            add(add(add(c[0], k(0.6, c[1])), k(0.3, c[2])), k(0.1, c[3])),
            add(add(add(add(c[0], k(0.8, c[1])), k(0.6, c[2])), k(0.4, c[3])), k(0.2, c[4])),
            add(add(add(add(add(c[0], c[1]), c[2]), c[3]), c[4]), c[5]),
        ]
    }

    /// The twin's refine_root on [0, 1] in the lanes of `active`: Newton's method kept inside
    /// the shrinking bracket, bisecting when a step would leave it; each lane stops where the
    /// twin's loop would.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn refine(&self, positive_at_lo: Mask, mut active: Mask) -> F8 {
        let (half, zero, tolerance) = (splat(0.5), _mm256_setzero_ps(), splat(S_TOLERANCE));
        let abs = |x: F8| _mm256_andnot_ps(splat(-0.0), x);
        let (mut lo, mut hi) = (zero, splat(1.0));
        let mut s = mul(half, add(lo, hi));
        for _ in 0..MAX_REFINE_STEPS {
            if bits(active) == 0 {
                break;
            }
            let value = self.at(s);
            active = and_not(active, equal(value, zero));
            // The twin moves lo where g(s) has the sign of g(lo), hi elsewhere.
            let differs = _mm256_xor_ps(non_negative(value), positive_at_lo);
            lo = select(and_not(active, differs), s, lo);
            hi = select(and(active, differs), s, hi);
            let derivative = self.derivative_at(s);
            let newton = sub(s, _mm256_div_ps(value, derivative));
            let inside = and(and(less(lo, newton), less(newton, hi)), _mm256_cmp_ps::<_CMP_NEQ_UQ>(derivative, zero));
            let next = select(inside, newton, mul(half, add(lo, hi)));
            let moved = abs(sub(next, s));
            s = select(active, next, s);
            let done =
                or(_mm256_cmp_ps::<_CMP_LE_OQ>(moved, tolerance), _mm256_cmp_ps::<_CMP_LE_OQ>(sub(hi, lo), tolerance));
            active = and_not(active, done);
        }
        s
    }
}

/// C(s) of a cell's curve in every lane, as [`crate::cpu::sweep_eval::curve_at`] rounds it.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn curve_at(curve: &[[f32; 4]; 4], s: F8) -> [F8; 3] {
    let axis = |a: usize| {
        let c = |i: usize| splat(curve[i][a]);
        add(c(0), mul(s, add(c(1), mul(s, add(c(2), mul(s, c(3)))))))
    };
    [axis(0), axis(1), axis(2)]
}

/// |v − p|², as the twin rounds it.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn distance2(v: &[F8; 3], p: &[F8; 3]) -> F8 {
    let d = [sub(v[0], p[0]), sub(v[1], p[1]), sub(v[2], p[2])];
    add(add(mul(d[0], d[0]), mul(d[1], d[1])), mul(d[2], d[2]))
}

/// Binds eight vertices `v` owned by sweep `sweep` whose flagged owners are `owners`; writes
/// each binding into `out`.
#[target_feature(enable = "avx2,fma")]
fn bind_batch(inputs: &BindInputs, sweep: SweepInfo, owners: &[u32; LANES], v: [F8; 3], out: &mut [GpuBinding]) {
    let zero = _mm256_setzero_ps();
    let (mut found, mut best_d2, mut best_s) = (zero, zero, zero);
    let mut best_k = _mm256_setzero_si256();
    // Lanes the twin binds alone.
    let mut alone = zero;
    for k in 0..sweep.segment_count {
        let quintic = Quintic::new(&inputs.bind_segments[(sweep.first_segment + k) as usize], &v);
        let b = quintic.bernstein();
        // Sign variations, 0 counted as positive; the masks are −1 where a sign changes.
        let signs = b.map(|x| _mm256_castps_si256(non_negative(x)));
        let mut variations = _mm256_setzero_si256();
        for pair in signs.windows(2) {
            variations = _mm256_sub_epi32(variations, _mm256_xor_si256(pair[0], pair[1]));
        }
        let one = _mm256_castsi256_ps(_mm256_cmpeq_epi32(variations, _mm256_set1_epi32(1)));
        let several = _mm256_castsi256_ps(_mm256_cmpgt_epi32(variations, _mm256_set1_epi32(1)));
        let vanishes = or(equal(quintic.g[0], zero), equal(quintic.at(splat(1.0)), zero));
        alone = or(alone, or(several, vanishes));
        if bits(one) == 0 {
            continue;
        }
        let s = quintic.refine(non_negative(b[0]), one);
        let cell = &inputs.cells[(sweep.first_cell + k * sweep.samples) as usize];
        let d2 = distance2(&v, &curve_at(&cell.curve, s));
        let nearer = and(one, or(_mm256_xor_ps(found, _mm256_castsi256_ps(_mm256_set1_epi32(-1))), less(d2, best_d2)));
        found = or(found, one);
        best_d2 = select(nearer, d2, best_d2);
        best_s = select(nearer, s, best_s);
        best_k = _mm256_castps_si256(select(
            nearer,
            _mm256_castsi256_ps(_mm256_set1_epi32(k as i32)),
            _mm256_castsi256_ps(best_k),
        ));
    }
    let (alone, found) = (bits(alone), bits(found));
    let k0 = _mm256_cvtsi256_si32(best_k);
    let same_k = bits(_mm256_castsi256_ps(_mm256_cmpeq_epi32(best_k, _mm256_set1_epi32(k0)))) == 0xff;
    if found == 0xff && same_k {
        finish_batch(inputs, sweep, sweep.first_cell + k0 as u32 * sweep.samples, best_s, &v, owners, out);
        for lane in (0..LANES).filter(|lane| alone & (1 << lane) != 0) {
            out[lane] = bind_vertex(inputs, owners[lane], lane_position(&v, lane));
        }
        return;
    }
    let s = to_array(best_s);
    let mut k = [0i32; LANES];
    // SAFETY: `k` is eight i32.
    unsafe { _mm256_storeu_si256(k.as_mut_ptr() as *mut __m256i, best_k) };
    let xyz = [to_array(v[0]), to_array(v[1]), to_array(v[2])];
    for lane in 0..LANES {
        let p = glam::Vec3::new(xyz[0][lane], xyz[1][lane], xyz[2][lane]);
        out[lane] = if alone & (1 << lane) != 0 {
            bind_vertex(inputs, owners[lane], p)
        } else {
            let nearest =
                (found & (1 << lane) != 0).then(|| (sweep.first_cell + k[lane] as u32 * sweep.samples, s[lane]));
            binding_at(inputs, sweep, nearest, p, owners[lane] & BAND_FLAG)
        };
    }
}

/// Vertex `lane` of `v`.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn lane_position(v: &[F8; 3], lane: usize) -> glam::Vec3 {
    glam::Vec3::new(to_array(v[0])[lane], to_array(v[1])[lane], to_array(v[2])[lane])
}

/// [`binding_at`] for eight vertices whose nearest roots lie on one knot interval (first cell
/// `interval`), at local parameters `s`: the same statements in registers (rounded
/// differently: this part of the binding is the twin's to rounding, not bit for bit), the
/// radius of each vertex's cell broadcast when the eight share it and read lane by lane when not.
#[target_feature(enable = "avx2,fma")]
fn finish_batch(
    inputs: &BindInputs,
    sweep: SweepInfo,
    interval: u32,
    s: F8,
    v: &[F8; 3],
    owners: &[u32; LANES],
    out: &mut [GpuBinding],
) {
    let cell = &inputs.cells[interval as usize];
    let c = curve_at(&cell.curve, s);
    // The batch's sweep interpolates its rotations linearly (`bind_batches`): a2 = a3 = 0.
    let q = |k: usize| add(splat(cell.rotation[0][k]), mul(s, splat(cell.rotation[1][k])));
    // R(t)ᵀ·(v − C(t)): the inverse rotation, by the conjugate quaternion.
    let inverse =
        [sub(_mm256_setzero_ps(), q(0)), sub(_mm256_setzero_ps(), q(1)), sub(_mm256_setzero_ps(), q(2)), q(3)];
    let local = super::deform_avx2::rotate(inverse, [sub(v[0], c[0]), sub(v[1], c[1]), sub(v[2], c[2])]);
    let zero = _mm256_setzero_ps();
    let off_axis = or(_mm256_cmp_ps::<_CMP_NEQ_UQ>(local[0], zero), _mm256_cmp_ps::<_CMP_NEQ_UQ>(local[1], zero));
    let tau = splat(std::f32::consts::TAU);
    let mut theta = and(off_axis, add(splat(cell.curve[0][3]), angle_of(local[0], local[1])));
    theta = select(less(theta, zero), add(theta, tau), theta);
    theta = select(_mm256_cmp_ps::<_CMP_GE_OQ>(theta, tau), sub(theta, tau), theta);
    let x = mul(theta, splat(sweep.samples as f32 / std::f32::consts::TAU));
    let j = _mm256_min_epi32(_mm256_cvttps_epi32(x), _mm256_set1_epi32(sweep.samples as i32 - 1));
    let j = _mm256_max_epi32(j, _mm256_setzero_si256());
    let phi = _mm256_min_ps(_mm256_max_ps(sub(x, _mm256_cvtepi32_ps(j)), zero), splat(1.0));
    let j0 = _mm256_cvtsi256_si32(j);
    let same_j = bits(_mm256_castsi256_ps(_mm256_cmpeq_epi32(j, _mm256_set1_epi32(j0)))) == 0xff;
    let mut j_lanes = [0i32; LANES];
    // SAFETY: `j_lanes` is eight i32.
    unsafe { _mm256_storeu_si256(j_lanes.as_mut_ptr() as *mut __m256i, j) };
    let (s_lanes, phi_lanes) = (to_array(s), to_array(phi));
    let r = if same_j {
        let radius = &inputs.cells[(interval + j0 as u32) as usize].radius;
        let row = |q: usize| [splat(radius[q][0]), splat(radius[q][1]), splat(radius[q][2]), splat(radius[q][3])];
        let rows = [row(0), row(1), row(2), row(3)];
        let in_phi = |p: usize| cubic([rows[0][p], rows[1][p], rows[2][p], rows[3][p]], phi);
        to_array(cubic([in_phi(0), in_phi(1), in_phi(2), in_phi(3)], s))
    } else {
        std::array::from_fn(|lane| {
            let cell = &inputs.cells[(interval + j_lanes[lane] as u32) as usize];
            radius_at(cell, s_lanes[lane], phi_lanes[lane])
        })
    };
    let radial = _mm256_sqrt_ps(add(mul(local[0], local[0]), mul(local[1], local[1])));
    let (radial, h) = (to_array(radial), to_array(local[2]));
    for lane in 0..LANES {
        out[lane] = GpuBinding {
            cell: (interval + j_lanes[lane] as u32) | (owners[lane] & BAND_FLAG),
            s: s_lanes[lane],
            phi: phi_lanes[lane],
            d: radial[lane] - r[lane],
            h: h[lane],
        };
    }
}

/// [`crate::cpu::angle::angle_of`] in every lane: the angle of (x, y) in [−π, π] by octant
/// reduction and the odd series to z¹⁵; meaningless where x = y = 0.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn angle_of(x: F8, y: F8) -> F8 {
    use std::f32::consts::PI;
    let abs = |x: F8| _mm256_andnot_ps(splat(-0.0), x);
    let (ax, ay) = (abs(x), abs(y));
    let a = _mm256_div_ps(_mm256_min_ps(ax, ay), _mm256_max_ps(ax, ay));
    let far = _mm256_cmp_ps::<_CMP_GT_OQ>(a, splat(0.41421356));
    let a = select(far, _mm256_div_ps(sub(a, splat(1.0)), add(a, splat(1.0))), a);
    let base = and(far, splat(0.25 * PI));
    let z2 = mul(a, a);
    let mut series = splat(1.0 / 15.0);
    for k in [13.0, 11.0, 9.0, 7.0, 5.0, 3.0] {
        series = sub(splat(1.0 / k), mul(z2, series));
    }
    let series = mul(a, sub(splat(1.0), mul(z2, series)));
    let mut angle = add(base, series);
    angle = select(_mm256_cmp_ps::<_CMP_GT_OQ>(ay, ax), sub(splat(0.5 * PI), angle), angle);
    angle = select(less(x, _mm256_setzero_ps()), sub(splat(PI), angle), angle);
    select(less(y, _mm256_setzero_ps()), sub(_mm256_setzero_ps(), angle), angle)
}

/// Whether sweep `owner` interpolates its rotations linearly, so that its plane polynomials are
/// quintics: the batches bind those in registers, the nonics of the cubic interpolation are
/// left to the twin.
fn quintic_sweep(inputs: &BindInputs, owner: u32) -> bool {
    let info = inputs.sweeps[owner as usize];
    inputs.bind_segments[info.first_segment as usize].degree == 5
}

/// Binds the vertices of `positions` (tightly packed xyz) owned by `owners` into `out`: batches
/// of eight with one owning sweep (whose rotations are linear) in registers, the others (and the
/// tail) one by one by the twin.
#[target_feature(enable = "avx2,fma")]
pub fn bind_batches(inputs: &BindInputs, owners: &[u32], positions: &[f32], out: &mut [GpuBinding]) {
    let (batches, _) = owners.as_chunks::<LANES>();
    let whole = LANES * batches.len();
    for ((i, batch), out) in batches.iter().enumerate().zip(out.chunks_exact_mut(LANES)) {
        let owner = batch[0] & !BAND_FLAG;
        let shared = batch[0] != UNOWNED
            && batch.iter().all(|&o| o != UNOWNED && o & !BAND_FLAG == owner)
            && quintic_sweep(inputs, owner);
        let first = LANES * i;
        if !shared {
            for (lane, binding) in out.iter_mut().enumerate() {
                *binding = bind_vertex(inputs, batch[lane], position(positions, first + lane));
            }
            continue;
        }
        let p = &positions[3 * first..3 * first + 3 * LANES];
        let axis =
            |a: usize| _mm256_setr_ps(p[a], p[3 + a], p[6 + a], p[9 + a], p[12 + a], p[15 + a], p[18 + a], p[21 + a]);
        bind_batch(inputs, inputs.sweeps[owner as usize], batch, [axis(0), axis(1), axis(2)], out);
    }
    for i in whole..owners.len() {
        out[i] = bind_vertex(inputs, owners[i], position(positions, i));
    }
}
