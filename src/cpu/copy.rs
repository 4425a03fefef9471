//! Twin of `shaders/copy.wgsl`, the benchmark's memory-ceiling kernel: reads each binding,
//! writes three floats derived from it.

use crate::coeffs::GpuBinding;

/// Every invocation of the kernel.
pub fn copy(bindings: &[GpuBinding], positions: &mut [f32]) {
    for (xyz, b) in positions.chunks_exact_mut(3).zip(bindings) {
        xyz[0] = b.s + b.cell as f32;
        xyz[1] = b.phi + b.h;
        xyz[2] = b.d;
    }
}
