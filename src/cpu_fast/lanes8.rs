//! Eight f32 lanes in one AVX2 register: the few helpers the eight-vertex kernels share
//! (fused multiply-add, Horner steps, cross products, loads and stores of tightly packed xyz).
//! Every function needs AVX2 and FMA, which its callers have checked ([`super::Isa`]).

use std::arch::x86_64::*;

/// Eight f32 lanes.
pub type F8 = __m256;

/// a·b + c in every lane, rounded once.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn fma(a: F8, b: F8, c: F8) -> F8 {
    _mm256_fmadd_ps(a, b, c)
}

/// x in every lane.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn splat(x: f32) -> F8 {
    _mm256_set1_ps(x)
}

/// a + b.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn add(a: F8, b: F8) -> F8 {
    _mm256_add_ps(a, b)
}

/// a − b.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn sub(a: F8, b: F8) -> F8 {
    _mm256_sub_ps(a, b)
}

/// a·b.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn mul(a: F8, b: F8) -> F8 {
    _mm256_mul_ps(a, b)
}

/// c[0] + x·(c[1] + x·(c[2] + x·c[3])), a cubic by Horner's rule.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn cubic(c: [F8; 4], x: F8) -> F8 {
    fma(x, fma(x, fma(x, c[3], c[2]), c[1]), c[0])
}

/// a × b for vectors held as three lanes of components.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn cross(a: [F8; 3], b: [F8; 3]) -> [F8; 3] {
    [
        _mm256_fmsub_ps(a[1], b[2], mul(a[2], b[1])),
        _mm256_fmsub_ps(a[2], b[0], mul(a[0], b[2])),
        _mm256_fmsub_ps(a[0], b[1], mul(a[1], b[0])),
    ]
}

/// Writes eight xyz triples (x, y, z in lanes) to `out` (24 floats), tightly packed.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn store_xyz(xyz: [F8; 3], out: &mut [f32; 24]) {
    // Each output register takes its floats from the same lanes of x, y and z, and blends them:
    // register 0 holds x0 y0 z0 x1 y1 z1 x2 y2, register 1 z2 x3 y3 z3 x4 y4 z4 x5, register 2
    // y5 z5 x6 y6 z6 x7 y7 z7.
    let part = |lanes: __m256i, x_at: i32, y_at: i32| {
        let (x, y, z) = (
            _mm256_permutevar8x32_ps(xyz[0], lanes),
            _mm256_permutevar8x32_ps(xyz[1], lanes),
            _mm256_permutevar8x32_ps(xyz[2], lanes),
        );
        (x, y, z, x_at, y_at)
    };
    let registers = [
        part(_mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2), 0b0100_1001, 0b1001_0010),
        part(_mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5), 0b1001_0010, 0b0010_0100),
        part(_mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7), 0b0010_0100, 0b0100_1001),
    ];
    for (chunk, (x, y, z, x_at, y_at)) in out.chunks_exact_mut(8).zip(registers) {
        let v = blend(blend(z, x, x_at), y, y_at);
        // SAFETY: `chunk` is 8 floats, the width of an unaligned 256-bit store.
        unsafe { _mm256_storeu_ps(chunk.as_mut_ptr(), v) };
    }
}

/// The lanes of `b` where bit i of `mask` is set, of `a` elsewhere.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn blend(a: F8, b: F8, mask: i32) -> F8 {
    let bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    let select = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(mask), bits), bits);
    _mm256_blendv_ps(a, b, _mm256_castsi256_ps(select))
}

/// The lanes as an array.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub fn to_array(v: F8) -> [f32; 8] {
    let mut out = [0.0; 8];
    // SAFETY: `out` is 8 floats.
    unsafe { _mm256_storeu_ps(out.as_mut_ptr(), v) };
    out
}
