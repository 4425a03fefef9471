//! Vertices at bit-identical positions: the two copies of a vertex along an unwelded patch
//! seam (the Newell teapot's 403 duplicated positions), which no edge joins. Fitting joins
//! them so that a part's sections close ([`crate::fit::autorig`]), and the falloff bands
//! march across them so that both copies get one weight ([`crate::bind::falloff`]).

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use glam::DVec3;

/// A multiply-rotate hasher for position keys (the Fx hash of rustc): positions are not
/// adversarial keys, and a seam search hashes every vertex of a mesh.
#[derive(Clone, Copy, Debug, Default)]
pub struct PositionHasher(u64);

impl Hasher for PositionHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_u32(&mut self, word: u32) {
        self.write_u64(u64::from(word));
    }

    fn write_usize(&mut self, word: usize) {
        self.write_u64(word as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// A hash map keyed by positions ([`position_key`]) and what goes with them.
pub type PositionMap<K, V> = HashMap<K, V, BuildHasherDefault<PositionHasher>>;

/// The bits of `p`, with −0.0 taken as 0.0: equal keys are equal positions.
pub fn position_key(p: DVec3) -> [u64; 3] {
    p.to_array().map(|c| if c == 0.0 { 0 } else { c.to_bits() })
}

/// For each vertex, the first vertex at the same position (bit for bit, −0.0 as 0.0).
pub fn weld(positions: &[DVec3]) -> Vec<u32> {
    weld_by(positions, |_| Some(()))
}

/// For each vertex, the first vertex at the same position with the same `class` (`None`: the
/// vertex is joined to none, itself).
pub fn weld_by<K: Eq + std::hash::Hash>(positions: &[DVec3], class: impl Fn(usize) -> Option<K>) -> Vec<u32> {
    let mut first: PositionMap<([u64; 3], K), u32> = PositionMap::default();
    positions
        .iter()
        .enumerate()
        .map(|(v, &p)| match class(v) {
            Some(k) => *first.entry((position_key(p), k)).or_insert(v as u32),
            None => v as u32,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welding_joins_bit_identical_positions_only() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(-0.0, 0.0, 0.0), DVec3::X + DVec3::splat(1e-12)];
        assert_eq!(weld(&p), [0, 1, 0, 3]);
    }

    #[test]
    fn welding_by_class_keeps_classes_apart() {
        let p = [DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO];
        let class = [Some(1), Some(2), Some(1), None];
        assert_eq!(weld_by(&p, |v| class[v]), [0, 1, 0, 3]);
    }
}
