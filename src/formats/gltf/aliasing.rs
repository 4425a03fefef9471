//! Refusing a faithful write whose stores overlap. A glTF file may point two accessors at the
//! same bytes (NORMAL at POSITION's accessor or buffer view, two meshes' POSITION over one
//! another); writing one of them back would overwrite the other, and the file would read back
//! with positions that differ from those computed. Such a write is refused, naming both
//! accessors, before anything is written.

use std::io;

use super::Target;

/// The elements of one accessor that a faithful write stores.
pub(crate) struct Store {
    /// The accessor.
    pub accessor: usize,
    /// The attribute it is, as errors name it (`POSITION`, `NORMAL`).
    pub semantic: &'static str,
    /// Where its elements lie.
    pub target: Target,
    /// The elements stored (12 bytes each).
    pub elements: Vec<usize>,
}

impl Store {
    /// The byte ranges of the stored elements.
    fn ranges(&self) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
        self.elements.iter().map(|&i| {
            let at = self.target.offset + i * self.target.stride;
            at..at + 12
        })
    }
}

/// `Err` naming the first two of `stores` that store into one byte of a buffer of
/// `buffer_lengths` (bytes past a buffer's end are left to the store, which refuses them).
pub(crate) fn check(buffer_lengths: &[usize], stores: &[Store]) -> io::Result<()> {
    let mut marked: Vec<Vec<u64>> = buffer_lengths.iter().map(|_| Vec::new()).collect();
    for (k, store) in stores.iter().enumerate() {
        let Some(bits) = marked.get_mut(store.target.buffer) else { continue };
        if bits.is_empty() {
            bits.resize(buffer_lengths[store.target.buffer].div_ceil(64), 0);
        }
        for byte in store.ranges().flatten() {
            let Some(word) = bits.get_mut(byte / 64) else { continue };
            let bit = 1u64 << (byte % 64);
            if *word & bit != 0 {
                let first = stores[..k]
                    .iter()
                    .find(|s| s.target.buffer == store.target.buffer && s.ranges().any(|r| r.contains(&byte)))
                    .unwrap_or(store);
                return Err(io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!(
                        "accessor {} ({}) and accessor {} ({}) share bytes of buffer {}: writing one would overwrite \
                         the other (write .obj, .ply or .off instead)",
                        first.accessor, first.semantic, store.accessor, store.semantic, store.target.buffer
                    ),
                ));
            }
            *word |= bit;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn store(accessor: usize, semantic: &'static str, offset: usize, stride: usize, elements: &[usize]) -> Store {
        Store { accessor, semantic, target: Target { buffer: 0, offset, stride }, elements: elements.to_vec() }
    }

    #[test]
    fn interleaved_attributes_do_not_alias() {
        // POSITION and NORMAL interleaved in one buffer view of stride 24.
        let stores = [store(0, "POSITION", 0, 24, &[0, 1, 2]), store(1, "NORMAL", 12, 24, &[0, 1, 2])];
        check(&[72], &stores).unwrap();
    }

    #[test]
    fn a_normal_on_the_position_bytes_is_refused_naming_both() {
        let stores = [store(0, "POSITION", 0, 12, &[1]), store(0, "NORMAL", 0, 12, &[1])];
        let error = check(&[36], &stores).unwrap_err().to_string();
        assert!(error.starts_with("accessor 0 (POSITION) and accessor 0 (NORMAL) share bytes of buffer 0"), "{error}");
        // Overlapping by one byte is enough.
        let stores = [store(0, "POSITION", 0, 12, &[0]), store(1, "NORMAL", 11, 12, &[0])];
        assert!(check(&[36], &stores).is_err());
        let stores = [store(0, "POSITION", 0, 12, &[0]), store(1, "NORMAL", 12, 12, &[0])];
        check(&[36], &stores).unwrap();
    }
}
