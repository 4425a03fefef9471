//! The CPU bench's memory-ceiling kernel, after `shaders/copy.wgsl`: reads each binding (the
//! f32 form, as the CPU paths hold them; the GPU kernel reads the packed form), writes three
//! floats derived from it.

use crate::parallel::prelude::*;

use crate::coeffs::GpuBinding;

/// One invocation of the kernel.
pub fn copy_vertex(b: &GpuBinding, xyz: &mut [f32]) {
    xyz[0] = b.s + b.cell as f32;
    xyz[1] = b.phi + b.h;
    xyz[2] = b.d;
}

/// Every invocation of the kernel, in parallel.
pub fn copy(bindings: &[GpuBinding], positions: &mut [f32]) {
    const CHUNK: usize = 4096;
    positions.par_chunks_mut(3 * CHUNK).zip(bindings.par_chunks(CHUNK)).for_each(|(positions, bindings)| {
        for (xyz, b) in positions.chunks_exact_mut(3).zip(bindings) {
            copy_vertex(b, xyz);
        }
    });
}

/// One invocation of `shaders/copy_wide.wgsl`, the fused kernel's memory ceiling.
pub fn copy_wide_vertex(b: &GpuBinding, record: [f32; 4], xyz: &mut [f32], normal: &mut [f32]) {
    copy_vertex(b, xyz);
    normal[0] = record[0] + record[3];
    normal[1] = record[1];
    normal[2] = record[2];
}
