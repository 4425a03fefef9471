//! The fused deform kernel with Jacobian normals on eight vertices at once (AVX2 + FMA): the
//! statements of [`crate::cpu::deform::deform_vertex_with_normal`] (`shaders/deform_normals.wgsl`)
//! with each f32 a register of eight vertices, on the cell machinery of the plain deform
//! ([`super::deform_avx2`]: one cell broadcast to a batch that shares it, else each lane's record
//! transposed).
//!
//! With c = R(s)·(cos δ, sin δ, 0), e = R(s)·e_z and ρ = r(s, φ) + d, the parameter Jacobian's
//! columns are ∂/∂φ = r_φ·c + ρ·(2π/M)·e × c, ∂/∂s = C′(s) + r_s·c + ω × (ρ·c + h·e) (∂/∂h = e
//! beyond an end) and ∂/∂d = c ([`crate::cpu::jacobian::point_frame`]), and the deformed normal
//! is cof(A)·m normalized (Nanson's formula, [`crate::deform::jacobian`]). R(s)'s columns are
//! formed once from the quaternion, so c, e and e × c = cos δ·R e_y − sin δ·R e_x cost no
//! rotation each: the results equal the twin's to rounding, not bit for bit.

use std::arch::x86_64::*;

use glam::Vec4;

use super::deform_avx2::{
    Batch, CellCache, Coefficients, LANES, Picked, cos_sin_small, load4, quat_at, quat_derivative_at, store_lanes,
};
use super::lanes8::{F8, add, cross, cubic, fma, mul, splat, sub};
use crate::coeffs::{CellCoeffs, GpuBinding};
use crate::cpu::jacobian::{NORMAL_BEYOND_END, NORMAL_FRAME};

/// A batch's normal coordinates records (m, mode), one field per register.
struct Records {
    m: [F8; 3],
    mode: F8,
}

impl Records {
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn load(records: &[Vec4; LANES]) -> Records {
        let rows = std::array::from_fn(|i| &records[i] as *const Vec4 as *const f32);
        // SAFETY: each record is four f32.
        let [x, y, z, mode] = unsafe { load4(rows) };
        Records { m: [x, y, z], mode }
    }
}

/// a·x + b·y for vectors held as three lanes of components.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn combine(a: F8, x: &[F8; 3], b: F8, y: &[F8; 3]) -> [F8; 3] {
    [fma(a, x[0], mul(b, y[0])), fma(a, x[1], mul(b, y[1])), fma(a, x[2], mul(b, y[2]))]
}

/// x + a·y.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn plus_scaled(x: [F8; 3], a: F8, y: &[F8; 3]) -> [F8; 3] {
    [fma(a, y[0], x[0]), fma(a, y[1], x[1]), fma(a, y[2], x[2])]
}

#[target_feature(enable = "avx2,fma")]
#[inline]
fn add3(a: [F8; 3], b: [F8; 3]) -> [F8; 3] {
    [add(a[0], b[0]), add(a[1], b[1]), add(a[2], b[2])]
}

/// `b` where `mask`, else `a`.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn select3(mask: F8, b: &[F8; 3], a: &[F8; 3]) -> [F8; 3] {
    [_mm256_blendv_ps(a[0], b[0], mask), _mm256_blendv_ps(a[1], b[1], mask), _mm256_blendv_ps(a[2], b[2], mask)]
}

/// The columns of the rotation by q/|q|: R e_x, R e_y, R e_z.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn rotation_columns(q: &[F8; 4]) -> [[F8; 3]; 3] {
    let [x, y, z, w] = *q;
    let k = _mm256_div_ps(splat(2.0), fma(x, x, fma(y, y, fma(z, z, mul(w, w)))));
    let (kx, ky, kz) = (mul(k, x), mul(k, y), mul(k, z));
    let (xx, yy, zz) = (mul(kx, x), mul(ky, y), mul(kz, z));
    let (xy, xz, yz) = (mul(kx, y), mul(kx, z), mul(ky, z));
    let (wx, wy, wz) = (mul(kx, w), mul(ky, w), mul(kz, w));
    let one = splat(1.0);
    [
        [sub(one, add(yy, zz)), add(xy, wz), sub(xz, wy)],
        [sub(xy, wz), sub(one, add(xx, zz)), add(yz, wx)],
        [add(xz, wy), sub(yz, wx), sub(one, add(xx, yy))],
    ]
}

/// v/|v|, zero where 1/|v| is not finite and positive (glam's `normalize_or_zero`).
#[target_feature(enable = "avx2,fma")]
#[inline]
fn normalize_or_zero(v: [F8; 3]) -> [F8; 3] {
    let length2 = fma(v[0], v[0], fma(v[1], v[1], mul(v[2], v[2])));
    let recip = _mm256_div_ps(splat(1.0), _mm256_sqrt_ps(length2));
    let ok = _mm256_and_ps(
        _mm256_cmp_ps::<_CMP_GT_OQ>(recip, _mm256_setzero_ps()),
        _mm256_cmp_ps::<_CMP_LT_OQ>(recip, splat(f32::INFINITY)),
    );
    [_mm256_and_ps(ok, mul(v[0], recip)), _mm256_and_ps(ok, mul(v[1], recip)), _mm256_and_ps(ok, mul(v[2], recip))]
}

/// Eq. 2 (+h) and the deformed normal in every lane: the twin's point_frame and
/// deformed_normal.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn evaluate(c: &Coefficients, b: &Batch, records: &Records) -> ([F8; 3], [F8; 3]) {
    let (s, phi) = (b.s, b.phi);
    let (two, three) = (splat(2.0), splat(3.0));
    // r(s, φ) and its partial derivatives: Horner in φ for each power of s, then in s.
    let in_phi = |p: usize| cubic([c.radius[0][p], c.radius[1][p], c.radius[2][p], c.radius[3][p]], phi);
    let along_s = [in_phi(0), in_phi(1), in_phi(2), in_phi(3)];
    let d_phi = |p: usize| fma(phi, fma(phi, mul(three, c.radius[3][p]), mul(two, c.radius[2][p])), c.radius[1][p]);
    let rho = add(cubic(along_s, s), b.d);
    let r_s = fma(s, fma(s, mul(three, along_s[3]), mul(two, along_s[2])), along_s[1]);
    let r_phi = cubic([d_phi(0), d_phi(1), d_phi(2), d_phi(3)], s);
    let (cos, sin) = cos_sin_small(mul(_mm256_fmsub_ps(two, phi, splat(1.0)), c.half_step));
    let q = quat_at(c, s);
    let dq = quat_derivative_at(c, s);
    let columns = rotation_columns(&q);
    let direction = combine(cos, &columns[0], sin, &columns[1]);
    let normal = columns[2];
    let offset = plus_scaled([mul(rho, direction[0]), mul(rho, direction[1]), mul(rho, direction[2])], b.h, &normal);
    let curve = |axis: usize| cubic([c.curve[0][axis], c.curve[1][axis], c.curve[2][axis], c.curve[3][axis]], s);
    let position = add3([curve(0), curve(1), curve(2)], offset);

    // ∂/∂φ = r_φ·c + ρ·(2π/M)·e × c, with e × c = cos δ·R e_y − sin δ·R e_x.
    let around = combine(cos, &columns[1], _mm256_xor_ps(sin, splat(-0.0)), &columns[0]);
    let along_phi = combine(r_phi, &direction, mul(mul(two, c.half_step), rho), &around);
    // ∂/∂s = C′(s) + r_s·c + ω × (ρ·c + h·e), ω = (2/|q|²)(w·dq.xyz − dq.w·q.xyz − dq.xyz × q.xyz);
    // ∂/∂h = e beyond an end.
    let velocity =
        |axis: usize| fma(s, fma(s, mul(three, c.curve[3][axis]), mul(two, c.curve[2][axis])), c.curve[1][axis]);
    let (u, du) = ([q[0], q[1], q[2]], [dq[0], dq[1], dq[2]]);
    let k = _mm256_div_ps(two, fma(q[0], q[0], fma(q[1], q[1], fma(q[2], q[2], mul(q[3], q[3])))));
    let twist = cross(du, u);
    let spin = |i: usize| mul(k, sub(_mm256_fmsub_ps(q[3], du[i], mul(dq[3], u[i])), twist[i]));
    let swirl = cross([spin(0), spin(1), spin(2)], offset);
    let along_s_axis = add3(plus_scaled([velocity(0), velocity(1), velocity(2)], r_s, &direction), swirl);
    let beyond = _mm256_cmp_ps::<_CMP_EQ_OQ>(records.mode, splat(NORMAL_BEYOND_END));
    let along_axis = select3(beyond, &normal, &along_s_axis);

    // cof(A)·m = m₁ b × c + m₂ c × a + m₃ a × b; R·m for a vertex on the axis.
    let (a, bb, cc) = (&along_phi, &along_axis, &direction);
    let m = &records.m;
    let (bc, ca, ab) = (cross(*bb, *cc), cross(*cc, *a), cross(*a, *bb));
    let mut n = plus_scaled(combine(m[0], &bc, m[1], &ca), m[2], &ab);
    let frame = _mm256_cmp_ps::<_CMP_EQ_OQ>(records.mode, splat(NORMAL_FRAME));
    if _mm256_movemask_ps(frame) != 0 {
        let rotated = plus_scaled(combine(m[0], &columns[0], m[1], &columns[1]), m[2], &columns[2]);
        n = select3(frame, &rotated, &n);
    }
    (position, normalize_or_zero(n))
}

/// Deforms the bound vertices of `bindings` (a multiple of [`LANES`]) outside falloff bands
/// into `positions` and `normals` (three floats each) from their normal coordinates `records`,
/// leaving the others alone.
///
/// # Panics
///
/// If a binding that is neither unbound nor in a band names a cell past `cells`.
#[target_feature(enable = "avx2,fma")]
pub fn deform_normals_batches(
    cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    records: &[Vec4],
    positions: &mut [f32],
    normals: &mut [f32],
) {
    let (batches, _) = bindings.as_chunks::<LANES>();
    let (records, _) = records.as_chunks::<LANES>();
    let (positions, _) = positions.as_chunks_mut::<{ 3 * LANES }>();
    let (normals, _) = normals.as_chunks_mut::<{ 3 * LANES }>();
    let mut cache = CellCache::new(cells);
    for (((batch, records), p), n) in batches.iter().zip(records).zip(positions).zip(normals) {
        let b = Batch::load(batch);
        let own;
        let (c, moved) = match cache.pick(batch) {
            Picked::Still => continue,
            Picked::Shared(c) => (c, 0xff),
            Picked::Own(index, moved) => {
                own = Coefficients::transposed(cells, index);
                (&own, moved)
            }
        };
        let (position, normal) = evaluate(c, &b, &Records::load(records));
        store_lanes(position, moved, p);
        store_lanes(normal, moved, n);
    }
}
