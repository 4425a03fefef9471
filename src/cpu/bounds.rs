//! Twin of `shaders/bounds.wgsl` and `shaders/bounds_finalize.wgsl`: the axis-aligned bounds of
//! tightly packed f32 positions, reduced on order-preserving u32 encodings of the coordinates,
//! so min and max are exact.

/// The u32 whose unsigned order is the f32 order of `f` (−0 below +0).
pub fn ordered(f: f32) -> u32 {
    let bits = f.to_bits();
    if bits & 0x8000_0000 != 0 { !bits } else { bits | 0x8000_0000 }
}

/// The f32 that [`ordered`] encodes as `u`.
pub fn unordered(u: u32) -> f32 {
    f32::from_bits(if u & 0x8000_0000 != 0 { u & 0x7fff_ffff } else { !u })
}

/// The seed of the reduction: min above and max below every encoding.
pub const EMPTY: [u32; 8] = [u32::MAX, u32::MAX, u32::MAX, 0, 0, 0, 0, 0];

/// Folds the positions (tightly packed xyz) into `extremes` (ordered min xyz, unused, ordered
/// max xyz, unused), as the workgroups of the bounds kernel do.
pub fn reduce(positions: &[f32], extremes: &mut [u32; 8]) {
    for p in positions.chunks_exact(3) {
        for c in 0..3 {
            let u = ordered(p[c]);
            extremes[c] = extremes[c].min(u);
            extremes[4 + c] = extremes[4 + c].max(u);
        }
    }
}

/// The finalize kernel: min.xyz, 0, max.xyz, 0 as f32.
pub fn finalize(extremes: &[u32; 8]) -> [f32; 8] {
    let f = |i: usize| unordered(extremes[i]);
    [f(0), f(1), f(2), 0.0, f(4), f(5), f(6), 0.0]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_encoding_preserves_order_across_zero_and_infinities() {
        let values = [f32::NEG_INFINITY, -3.5, -1e-40, -0.0, 0.0, 1e-40, 2.0, f32::MAX, f32::INFINITY];
        for pair in values.windows(2) {
            assert!(ordered(pair[0]) < ordered(pair[1]), "{pair:?}");
        }
        for v in values {
            assert_eq!(unordered(ordered(v)).to_bits(), v.to_bits());
        }
    }

    #[test]
    fn bounds_of_a_few_points_are_their_exact_extremes() {
        let mut extremes = EMPTY;
        reduce(&[1.0, -2.0, 3.0, -0.5, 4.0, 0.25, 0.1, 0.2, -7.0], &mut extremes);
        assert_eq!(finalize(&extremes), [-0.5, -2.0, -7.0, 0.0, 1.0, 4.0, 3.0, 0.0]);
    }
}
