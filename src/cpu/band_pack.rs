//! Twin of `shaders/band_pack.wgsl`: the band records' second influences from the bindings of
//! band vertices to their neighbouring sweeps: the cell ([`UNOWNED`](crate::coeffs::UNOWNED):
//! the rest position) and (s, φ) as two unorm16.

use crate::coeffs::{BandRecord, GpuBinding};

/// x ∈ [0, 1] as a 16-bit fixed-point value, rounded to nearest.
pub fn unorm16(x: f32) -> u32 {
    (x.clamp(0.0, 1.0) * 65535.0 + 0.5).floor() as u32
}

/// One invocation of the kernel: fills `band`'s second influence from `second`.
pub fn band_pack_vertex(second: &GpuBinding, band: &mut BandRecord) {
    band.cell = second.cell;
    band.s_phi = unorm16(second.s) | (unorm16(second.phi) << 16);
}

/// Every invocation of the kernel.
pub fn band_pack(second_bindings: &[GpuBinding], bands: &mut [BandRecord]) {
    for (second, band) in second_bindings.iter().zip(bands) {
        band_pack_vertex(second, band);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::band::unpack_s_phi;

    #[test]
    fn packed_s_and_phi_round_trip_within_half_a_step() {
        for i in 0..=1000 {
            let (s, phi) = (i as f32 / 1000.0, 1.0 - (i as f32 / 1000.0).powi(2));
            let mut band = BandRecord::default();
            band_pack_vertex(&GpuBinding { cell: 7, s, phi, d: 0.0, h: 0.0 }, &mut band);
            let back = unpack_s_phi(band.s_phi);
            assert_eq!(band.cell, 7);
            assert!((back.x - s).abs() <= 0.5 / 65535.0 + 1e-7 && (back.y - phi).abs() <= 0.5 / 65535.0 + 1e-7);
        }
        assert_eq!(unorm16(0.0), 0);
        assert_eq!(unorm16(1.0), 65535);
    }
}
