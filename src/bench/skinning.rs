//! Input for the linear-blend-skinning baseline: 64 joints and four influences per vertex.

use glam::{Affine3A, Quat, Vec3};

use crate::coeffs::{Joint, SkinInfluence};

/// Joints of the skinning baseline: 64 distinct rigid transforms.
pub fn skinning_joints() -> Vec<Joint> {
    (0..64)
        .map(|j| {
            let angle = j as f32 * 0.1;
            let transform = Affine3A::from_rotation_translation(
                Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), angle),
                Vec3::new(angle.sin(), angle.cos(), 0.01 * j as f32),
            );
            let m = glam::Mat4::from(transform).transpose();
            Joint { rows: [m.x_axis.to_array(), m.y_axis.to_array(), m.z_axis.to_array()] }
        })
        .collect()
}

/// Four influences per vertex: joints spread over the mesh order, weights 128 + 64 + 32 + 31
/// (of 255), so every vertex reads four different joints as a skinned character's would.
pub fn skinning_influences(vertices: usize) -> Vec<SkinInfluence> {
    (0..vertices)
        .map(|i| {
            let base = (i * 64 / vertices.max(1)) as u32;
            let joints = [base, (base + 1) % 64, (base + 7) % 64, (base + 13) % 64];
            SkinInfluence {
                joints: u32::from_le_bytes(joints.map(|j| j as u8)),
                weights: u32::from_le_bytes([128, 64, 32, 31]),
            }
        })
        .collect()
}
