//! Twin of `shaders/band_flags.wgsl`: replacing the falloff bands without binding again. For
//! each vertex whose membership changes, sets or clears [`BAND_FLAG`] in its binding's cell, and
//! writes the rest position of a vertex that keeps it in the new bands ([`KEEPS_REST`]: w = 0
//! against the rest position), which the band kernel never writes.

use crate::coeffs::{BAND_FLAG, BandFlag, GpuBinding, KEEPS_REST, UNOWNED};

/// One invocation of the kernel: applies `flag` to the dispatch's `bindings` and `positions`
/// (tightly packed xyz, indexed like `bindings`). An unbound vertex is left as it is.
pub fn band_flags_vertex(flag: &BandFlag, bindings: &mut [GpuBinding], positions: &mut [f32]) {
    let v = (flag.vertex & !(BAND_FLAG | KEEPS_REST)) as usize;
    let cell = bindings[v].cell;
    if cell == UNOWNED {
        return;
    }
    bindings[v].cell = (cell & !BAND_FLAG) | (flag.vertex & BAND_FLAG);
    if flag.vertex & KEEPS_REST != 0 {
        positions[3 * v] = flag.x;
        positions[3 * v + 1] = flag.y;
        positions[3 * v + 2] = flag.z;
    }
}

/// Every invocation of the kernel over one dispatch (each vertex at most once in `flags`).
pub fn band_flags(flags: &[BandFlag], bindings: &mut [GpuBinding], positions: &mut [f32]) {
    for flag in flags {
        band_flags_vertex(flag, bindings, positions);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binding(cell: u32) -> GpuBinding {
        GpuBinding { cell, s: 0.25, phi: 0.5, d: -0.1, h: 0.2 }
    }

    #[test]
    fn entering_sets_the_flag_and_leaving_clears_it_keeping_the_cell() {
        let mut bindings = vec![binding(7), binding(9 | BAND_FLAG)];
        let mut positions = vec![1.0; 6];
        let flags =
            [BandFlag { vertex: BAND_FLAG, ..Default::default() }, BandFlag { vertex: 1, ..Default::default() }];
        band_flags(&flags, &mut bindings, &mut positions);
        assert_eq!(bindings, vec![binding(7 | BAND_FLAG), binding(9)]);
        assert_eq!(positions, vec![1.0; 6], "no rest position without KEEPS_REST");
    }

    #[test]
    fn a_vertex_keeping_its_rest_position_gets_it_written() {
        let mut bindings = vec![binding(3), binding(4 | BAND_FLAG)];
        let mut positions = vec![9.0; 6];
        let rest = BandFlag { vertex: 1 | BAND_FLAG | KEEPS_REST, x: 0.5, y: -1.5, z: 2.0 };
        band_flags(&[rest], &mut bindings, &mut positions);
        assert_eq!(bindings, vec![binding(3), binding(4 | BAND_FLAG)]);
        assert_eq!(positions, vec![9.0, 9.0, 9.0, 0.5, -1.5, 2.0]);
    }

    #[test]
    fn an_unbound_vertex_is_left_alone() {
        let mut bindings = vec![binding(UNOWNED)];
        let mut positions = vec![9.0; 3];
        band_flags_vertex(&BandFlag { vertex: KEEPS_REST, x: 1.0, y: 2.0, z: 3.0 }, &mut bindings, &mut positions);
        assert_eq!(bindings[0].cell, UNOWNED);
        assert_eq!(positions, vec![9.0; 3]);
    }
}
