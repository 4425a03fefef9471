//! The deform kernel on eight vertices at once (AVX2 + FMA): the statements of
//! [`crate::cpu::deform::deform_vertex`] (Eq. 2 extended by h,
//! v = C(s) + R(s)·((r(s, φ) + d)·cos δ, (r(s, φ) + d)·sin δ, h)) with each f32 a register of
//! eight vertices. Consecutive vertices mostly lie in one cell, so a batch whose eight share one
//! broadcasts that cell's coefficients; a batch spread over several cells, or with vertices the
//! kernel leaves alone (unbound, or in a falloff band), loads each lane's record and transposes
//! them.

use std::arch::x86_64::*;

use super::lanes8::{F8, add, cross, cubic, fma, mul, splat, store_xyz, to_array};
use crate::coeffs::{CellCoeffs, GpuBinding};

/// Vertices per batch.
pub const LANES: usize = 8;

const _: () = assert!(size_of::<CellCoeffs>() == 192 && size_of::<GpuBinding>() == 20);

/// One cell's coefficients in every lane (the same cell, or each lane's own): the fields of
/// [`CellCoeffs`].
pub(super) struct Coefficients {
    /// `radius[q][p]`: the coefficient of φ^q·s^p.
    pub radius: [[F8; 4]; 4],
    /// `curve[i][axis]`: the coefficient of s^i.
    pub curve: [[F8; 3]; 4],
    /// π/M.
    pub half_step: F8,
    /// `rotation[i][k]`: component k of the coefficient of s^i of the unnormalized quaternion;
    /// `rotation[2]` and `rotation[3]` are zero and unread unless `cubic`.
    pub rotation: [[F8; 4]; 4],
    /// Whether some lane's cell has cubic rotations (`CellCoeffs::curve[2].w`).
    pub cubic: bool,
}

impl Coefficients {
    /// Every lane holds `cell`'s coefficients.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn broadcast(cell: &CellCoeffs) -> Coefficients {
        // Array literals rather than `map`, which LLVM leaves as a call outside the AVX2 code.
        let four = |c: &[f32; 4]| [splat(c[0]), splat(c[1]), splat(c[2]), splat(c[3])];
        let three = |c: &[f32; 4]| [splat(c[0]), splat(c[1]), splat(c[2])];
        let (r, c, q) = (&cell.radius, &cell.curve, &cell.rotation);
        Coefficients {
            radius: [four(&r[0]), four(&r[1]), four(&r[2]), four(&r[3])],
            curve: [three(&c[0]), three(&c[1]), three(&c[2]), three(&c[3])],
            half_step: splat(cell.curve[0][3]),
            rotation: [four(&q[0]), four(&q[1]), four(&q[2]), four(&q[3])],
            cubic: cell.curve[2][3] != 0.0,
        }
    }

    /// Lane i holds the coefficients of cell `index[i]`: each record's 48 floats loaded as six
    /// registers, and each block of eight records' registers transposed (gathers are slow on
    /// many CPUs).
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub(super) fn transposed(cells: &[CellCoeffs], index: [usize; LANES]) -> Coefficients {
        let records = index.map(|i| &cells[i]);
        // Block b of a record holds its floats 8b..8b + 8: radius[0..2], radius[2..4],
        // curve[0..2], curve[2..4], rotation[0..2], rotation[2..4].
        let block = |b: usize| {
            let rows = records.map(|record| {
                let words: &[f32; 48] = bytemuck::cast_ref(record);
                // SAFETY: floats 8b..8b + 8 of a 48-float record, b < 6.
                unsafe { _mm256_loadu_ps(words.as_ptr().add(8 * b)) }
            });
            transpose8(rows)
        };
        let (b0, b1, b2, b3, b4) = (block(0), block(1), block(2), block(3), block(4));
        // Block 5 (a2, a3) only where a lane's rotations are cubic: most rigs have none.
        let cubic = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_NEQ_UQ>(b3[3], _mm256_setzero_ps())) != 0;
        let b5 = if cubic { block(5) } else { [_mm256_setzero_ps(); 8] };
        let four = |b: &[F8; 8], at: usize| [b[at], b[at + 1], b[at + 2], b[at + 3]];
        let three = |b: &[F8; 8], at: usize| [b[at], b[at + 1], b[at + 2]];
        Coefficients {
            radius: [four(&b0, 0), four(&b0, 4), four(&b1, 0), four(&b1, 4)],
            curve: [three(&b2, 0), three(&b2, 4), three(&b3, 0), three(&b3, 4)],
            half_step: b2[3],
            rotation: [four(&b4, 0), four(&b4, 4), four(&b5, 0), four(&b5, 4)],
            cubic,
        }
    }
}

/// The 8 × 8 transpose: lane i of output k is lane k of row i.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn transpose8(r: [F8; 8]) -> [F8; 8] {
    let t = [
        _mm256_unpacklo_ps(r[0], r[1]),
        _mm256_unpackhi_ps(r[0], r[1]),
        _mm256_unpacklo_ps(r[2], r[3]),
        _mm256_unpackhi_ps(r[2], r[3]),
        _mm256_unpacklo_ps(r[4], r[5]),
        _mm256_unpackhi_ps(r[4], r[5]),
        _mm256_unpacklo_ps(r[6], r[7]),
        _mm256_unpackhi_ps(r[6], r[7]),
    ];
    let u = [
        _mm256_shuffle_ps::<0x44>(t[0], t[2]),
        _mm256_shuffle_ps::<0xee>(t[0], t[2]),
        _mm256_shuffle_ps::<0x44>(t[1], t[3]),
        _mm256_shuffle_ps::<0xee>(t[1], t[3]),
        _mm256_shuffle_ps::<0x44>(t[4], t[6]),
        _mm256_shuffle_ps::<0xee>(t[4], t[6]),
        _mm256_shuffle_ps::<0x44>(t[5], t[7]),
        _mm256_shuffle_ps::<0xee>(t[5], t[7]),
    ];
    [
        _mm256_permute2f128_ps::<0x20>(u[0], u[4]),
        _mm256_permute2f128_ps::<0x20>(u[1], u[5]),
        _mm256_permute2f128_ps::<0x20>(u[2], u[6]),
        _mm256_permute2f128_ps::<0x20>(u[3], u[7]),
        _mm256_permute2f128_ps::<0x31>(u[0], u[4]),
        _mm256_permute2f128_ps::<0x31>(u[1], u[5]),
        _mm256_permute2f128_ps::<0x31>(u[2], u[6]),
        _mm256_permute2f128_ps::<0x31>(u[3], u[7]),
    ]
}

/// The bindings of a batch, one field per register.
pub(super) struct Batch {
    pub s: F8,
    pub phi: F8,
    pub d: F8,
    pub h: F8,
}

impl Batch {
    /// (s, φ, d, h) of each binding: [`load4`].
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub(super) fn load(bindings: &[GpuBinding; LANES]) -> Batch {
        let rows = [0, 1, 2, 3, 4, 5, 6, 7].map(|i| &bindings[i].s as *const f32);
        // SAFETY: s, φ, d and h are four consecutive f32 fields of each `#[repr(C)]` binding.
        let [s, phi, d, h] = unsafe { load4(rows) };
        Batch { s, phi, d, h }
    }
}

/// Four consecutive floats from each of eight rows, one register per float: row i beside row
/// i + 4 in one register, each 4 × 4 block transposed (gathers are slow on many CPUs).
///
/// # Safety
///
/// Each pointer reads four floats.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) unsafe fn load4(rows: [*const f32; LANES]) -> [F8; 4] {
    // SAFETY: the caller's.
    let fields = |i: usize| unsafe { _mm256_loadu2_m128(rows[i + 4], rows[i]) };
    let (r0, r1, r2, r3) = (fields(0), fields(1), fields(2), fields(3));
    let (t0, t1) = (_mm256_unpacklo_ps(r0, r1), _mm256_unpackhi_ps(r0, r1));
    let (t2, t3) = (_mm256_unpacklo_ps(r2, r3), _mm256_unpackhi_ps(r2, r3));
    [
        _mm256_shuffle_ps::<0x44>(t0, t2),
        _mm256_shuffle_ps::<0xee>(t0, t2),
        _mm256_shuffle_ps::<0x44>(t1, t3),
        _mm256_shuffle_ps::<0xee>(t1, t3),
    ]
}

/// The coefficients of a batch's cells, as [`CellCache::pick`] finds them.
pub(super) enum Picked<'a> {
    /// No lane moves (unbound or band vertices only).
    Still,
    /// Every lane moves, on one cell.
    Shared(&'a Coefficients),
    /// The lanes of the mask move (bit i: lane i), each on its own cell, whose index it holds
    /// (0 in the lanes left alone): [`Coefficients::transposed`] makes their coefficients, in the
    /// caller's frame, where they stay in registers.
    Own([usize; LANES], u32),
}

/// The cells of the batches of one run of the deform kernels, with the broadcast coefficients
/// of the last uniform batch's cell, which the next batch often shares.
pub(super) struct CellCache<'c> {
    cells: &'c [CellCoeffs],
    count: __m256i,
    last: Option<(u32, Coefficients)>,
}

impl<'c> CellCache<'c> {
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub(super) fn new(cells: &'c [CellCoeffs]) -> CellCache<'c> {
        CellCache { cells, count: _mm256_set1_epi32(cells.len().min(i32::MAX as usize) as i32), last: None }
    }

    /// Which lanes of `batch` the kernel moves (neither unbound nor in a band), and their cells'
    /// coefficients.
    ///
    /// # Panics
    ///
    /// If a lane that moves names a cell past the cells.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub(super) fn pick(&mut self, batch: &[GpuBinding; LANES]) -> Picked<'_> {
        let cells = self.cells;
        let first = batch[0].cell;
        if (first as usize) < cells.len() && batch.iter().all(|binding| binding.cell == first) {
            if self.last.as_ref().is_none_or(|(cell, _)| *cell != first) {
                self.last = Some((first, Coefficients::broadcast(&cells[first as usize])));
            }
            let (_, c) = self.last.as_ref().expect("set just above");
            return Picked::Shared(c);
        }
        // Cells below BAND_FLAG are non-negative as i32; those at or past it (bands, unbound)
        // are negative and stay where they are.
        let cell = cells_of(batch);
        let moved = _mm256_cmpgt_epi32(cell, _mm256_set1_epi32(-1));
        let in_range = _mm256_and_si256(moved, _mm256_cmpgt_epi32(self.count, cell));
        let (moved_bits, in_range_bits) =
            (_mm256_movemask_ps(_mm256_castsi256_ps(moved)), _mm256_movemask_ps(_mm256_castsi256_ps(in_range)));
        if moved_bits != in_range_bits {
            let lane = (moved_bits ^ in_range_bits).trailing_zeros() as usize;
            panic!("binding names cell {} of {}", batch[lane].cell, cells.len());
        }
        if moved_bits == 0 {
            return Picked::Still;
        }
        // Lanes left alone read cell 0 (there is one: some lane moves) and are not written.
        let index =
            std::array::from_fn(|lane| if in_range_bits & (1 << lane) != 0 { batch[lane].cell as usize } else { 0 });
        Picked::Own(index, moved_bits as u32)
    }
}

/// Writes the lanes of `moved` (bit i: lane i) of eight xyz triples to `out` (24 floats,
/// tightly packed), leaving the others' floats alone.
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn store_lanes(xyz: [F8; 3], moved: u32, out: &mut [f32; 24]) {
    if moved == 0xff {
        store_xyz(xyz, out);
        return;
    }
    let xyz = [to_array(xyz[0]), to_array(xyz[1]), to_array(xyz[2])];
    for lane in (0..LANES).filter(|lane| moved & (1 << lane) != 0) {
        out[3 * lane..3 * lane + 3].copy_from_slice(&[xyz[0][lane], xyz[1][lane], xyz[2][lane]]);
    }
}

/// The cells of a batch's bindings, one per lane.
#[target_feature(enable = "avx2,fma")]
#[inline]
fn cells_of(bindings: &[GpuBinding; LANES]) -> __m256i {
    let c = bindings.map(|b| b.cell as i32);
    _mm256_setr_epi32(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7])
}

/// Eq. 2 (+h) in every lane: C(s) + rotate(q(s), ((r + d)·cos δ, (r + d)·sin δ, h)).
#[target_feature(enable = "avx2,fma")]
#[inline]
fn evaluate(c: &Coefficients, b: &Batch) -> [F8; 3] {
    // r(s, φ): Horner in φ for each power of s, then in s.
    let in_phi = |p: usize| cubic([c.radius[0][p], c.radius[1][p], c.radius[2][p], c.radius[3][p]], b.phi);
    let along_s = [in_phi(0), in_phi(1), in_phi(2), in_phi(3)];
    let rho = add(cubic(along_s, b.s), b.d);
    let (cos, sin) = cos_sin_small(mul(_mm256_fmsub_ps(splat(2.0), b.phi, splat(1.0)), c.half_step));
    let local = [mul(rho, cos), mul(rho, sin), b.h];
    let curve = |axis: usize| cubic([c.curve[0][axis], c.curve[1][axis], c.curve[2][axis], c.curve[3][axis]], b.s);
    let q = quat_at(c, b.s);
    let rotated = rotate(q, local);
    [add(curve(0), rotated[0]), add(curve(1), rotated[1]), add(curve(2), rotated[2])]
}

/// The unnormalized q(s) in every lane ([`crate::cpu::sweep_eval::quat_at`]).
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn quat_at(c: &Coefficients, s: F8) -> [F8; 4] {
    if !c.cubic {
        // a0 + s·a1, as the twin's Horner rounds it with a2 = a3 = 0.
        let linear = |k: usize| fma(s, c.rotation[1][k], c.rotation[0][k]);
        return [linear(0), linear(1), linear(2), linear(3)];
    }
    let quat = |k: usize| cubic([c.rotation[0][k], c.rotation[1][k], c.rotation[2][k], c.rotation[3][k]], s);
    [quat(0), quat(1), quat(2), quat(3)]
}

/// dq/ds in every lane ([`crate::cpu::sweep_eval::quat_derivative_at`]).
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn quat_derivative_at(c: &Coefficients, s: F8) -> [F8; 4] {
    if !c.cubic {
        return c.rotation[1];
    }
    let (two, three) = (splat(2.0), splat(3.0));
    let slope = |k: usize| fma(s, fma(s, mul(three, c.rotation[3][k]), mul(two, c.rotation[2][k])), c.rotation[1][k]);
    [slope(0), slope(1), slope(2), slope(3)]
}

/// v rotated by q/|q| ([`crate::cpu::sweep_eval::rotate`]): v + w·t + u × t, t = 2(u × v)/|q|².
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn rotate(q: [F8; 4], v: [F8; 3]) -> [F8; 3] {
    let norm2 = fma(q[0], q[0], fma(q[1], q[1], fma(q[2], q[2], mul(q[3], q[3]))));
    let scale = _mm256_div_ps(splat(2.0), norm2);
    let u = [q[0], q[1], q[2]];
    let uv = cross(u, v);
    let t = [mul(scale, uv[0]), mul(scale, uv[1]), mul(scale, uv[2])];
    let ut = cross(u, t);
    let axis = |i: usize| add(fma(q[3], t[i], v[i]), ut[i]);
    [axis(0), axis(1), axis(2)]
}

/// (cos δ, sin δ) for |δ| ≤ π/3 by the polynomials of [`crate::cpu::sweep_eval::cos_sin_small`].
#[target_feature(enable = "avx2,fma")]
#[inline]
#[expect(clippy::excessive_precision, reason = "the WGSL twin spells the same literals")]
pub(super) fn cos_sin_small(delta: F8) -> (F8, F8) {
    let d2 = mul(delta, delta);
    let sin = mul(
        delta,
        fma(
            d2,
            fma(d2, fma(d2, splat(-0.0001917176645069119), splat(0.008327856912345286)), splat(-0.16666500356755126)),
            splat(0.9999998635311992),
        ),
    );
    let cos = fma(
        d2,
        fma(
            d2,
            fma(d2, fma(d2, splat(2.4056512057197938e-05), splat(-0.0013881774166947518)), splat(0.04166638875586918)),
            splat(-0.4999999619760431),
        ),
        splat(0.9999999991674327),
    );
    (cos, sin)
}

/// Deforms the bound vertices of `bindings` (a multiple of [`LANES`]) into `positions` (three
/// floats each), leaving the others alone.
///
/// # Panics
///
/// If a binding that is neither unbound nor in a band names a cell past `cells`.
#[target_feature(enable = "avx2,fma")]
pub fn deform_batches(cells: &[CellCoeffs], bindings: &[GpuBinding], positions: &mut [f32]) {
    let (batches, _) = bindings.as_chunks::<LANES>();
    let (outputs, _) = positions.as_chunks_mut::<{ 3 * LANES }>();
    let cell_count = _mm256_set1_epi32(cells.len().min(i32::MAX as usize) as i32);
    // The broadcast coefficients of the last uniform batch's cell, which the next batch often
    // shares.
    let mut last: Option<(u32, Coefficients)> = None;
    for (batch, out) in batches.iter().zip(outputs) {
        let first = batch[0].cell;
        let b = Batch::load(batch);
        if (first as usize) < cells.len() && batch.iter().all(|binding| binding.cell == first) {
            if last.as_ref().is_none_or(|(cell, _)| *cell != first) {
                last = Some((first, Coefficients::broadcast(&cells[first as usize])));
            }
            let (_, c) = last.as_ref().expect("set just above");
            store_xyz(evaluate(c, &b), out);
            continue;
        }
        // Cells below BAND_FLAG are non-negative as i32; those at or past it (bands, unbound)
        // are negative and stay where they are.
        let cell = cells_of(batch);
        let moved = _mm256_cmpgt_epi32(cell, _mm256_set1_epi32(-1));
        let in_range = _mm256_and_si256(moved, _mm256_cmpgt_epi32(cell_count, cell));
        let (moved_bits, in_range_bits) =
            (_mm256_movemask_ps(_mm256_castsi256_ps(moved)), _mm256_movemask_ps(_mm256_castsi256_ps(in_range)));
        if moved_bits != in_range_bits {
            let lane = (moved_bits ^ in_range_bits).trailing_zeros() as usize;
            panic!("binding names cell {} of {}", batch[lane].cell, cells.len());
        }
        if moved_bits == 0 {
            continue;
        }
        // Lanes left alone read cell 0 (there is one: some lane moves) and are not written.
        let index =
            std::array::from_fn(|lane| if in_range_bits & (1 << lane) != 0 { batch[lane].cell as usize } else { 0 });
        let c = Coefficients::transposed(cells, index);
        let xyz = evaluate(&c, &b);
        if moved_bits == 0xff {
            store_xyz(xyz, out);
            continue;
        }
        let xyz = [to_array(xyz[0]), to_array(xyz[1]), to_array(xyz[2])];
        for lane in (0..LANES).filter(|lane| moved_bits & (1 << lane) != 0) {
            out[3 * lane..3 * lane + 3].copy_from_slice(&[xyz[0][lane], xyz[1][lane], xyz[2][lane]]);
        }
    }
}
