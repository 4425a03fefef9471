//! The instruction sets the fast CPU path's tests check: the detected one and the scalar
//! fallback.

use sweepffd::cpu_fast::Isa;

/// The detected instruction set, then [`Isa::Scalar`] if that is another.
pub fn isas() -> Vec<Isa> {
    let mut isas = vec![Isa::detect(), Isa::Scalar];
    isas.dedup();
    isas
}
