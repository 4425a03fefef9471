//! Twin of `shaders/skinning.wgsl`, the benchmark's four-influence linear-blend-skinning
//! baseline: p′ = Σ_k w_k·M_k·(p, 1).

use crate::parallel::prelude::*;
use glam::{Vec3, Vec4};

use super::position;
use crate::coeffs::{Joint, SkinInfluence};

/// The four unorm8 weights packed in `packed`, lowest byte first.
pub fn unpack_weights(packed: u32) -> Vec4 {
    Vec4::from_array(packed.to_le_bytes().map(|b| b as f32 / 255.0))
}

/// One invocation of the kernel: the skinned position of vertex `i`.
pub fn skin_vertex(joints: &[Joint], rest: &[f32], influences: &[SkinInfluence], i: usize) -> Vec3 {
    let p = position(rest, i).extend(1.0);
    let influence = influences[i];
    let weights = unpack_weights(influence.weights);
    let mut skinned = Vec3::ZERO;
    for k in 0..4 {
        let joint = &joints[((influence.joints >> (8 * k)) & 0xff) as usize];
        let rows = joint.rows.map(Vec4::from_array);
        skinned += weights[k] * Vec3::new(rows[0].dot(p), rows[1].dot(p), rows[2].dot(p));
    }
    skinned
}

/// Every invocation of the kernel, in parallel.
pub fn skinning(joints: &[Joint], rest: &[f32], influences: &[SkinInfluence], positions: &mut [f32]) {
    positions.par_chunks_mut(3).enumerate().for_each(|(i, xyz)| {
        xyz.copy_from_slice(&skin_vertex(joints, rest, influences, i).to_array());
    });
}
