//! Key orientations whose normal follows the axis, with θ = 0 carried along the axis by
//! parallel transport so that the frames do not twist between keys.

use glam::{DMat3, DQuat, DVec3};

/// One rotation per normal: the local z axis is the normal; the local x axis (θ = 0) of the
/// first key is the world axis least aligned with its normal, made orthogonal to it, and each
/// next key's x axis is the previous one turned by the smallest rotation between the normals.
/// Successive quaternions are sign-aligned, as R(t)'s interpolation expects.
pub fn transported_frames(normals: &[DVec3]) -> Vec<DQuat> {
    let mut rotations: Vec<DQuat> = Vec::with_capacity(normals.len());
    let mut x_axis = DVec3::ZERO;
    for (i, &normal) in normals.iter().enumerate() {
        x_axis =
            if i == 0 { least_aligned_axis(normal) } else { DQuat::from_rotation_arc(normals[i - 1], normal) * x_axis };
        x_axis = (x_axis - normal * x_axis.dot(normal)).normalize();
        let mut rotation = DQuat::from_mat3(&DMat3::from_cols(x_axis, normal.cross(x_axis), normal)).normalize();
        if rotations.last().is_some_and(|previous| previous.dot(rotation) < 0.0) {
            rotation = -rotation;
        }
        rotations.push(rotation);
    }
    rotations
}

/// The world axis (X, then Y, then Z on ties) with the smallest component along `normal`.
fn least_aligned_axis(normal: DVec3) -> DVec3 {
    let a = normal.abs();
    if a.x <= a.y && a.x <= a.z {
        DVec3::X
    } else if a.y <= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_follow_the_normals_without_twist() {
        let normals: Vec<DVec3> =
            (0..8).map(|i| DVec3::new((i as f64 * 0.2).sin(), 0.0, (i as f64 * 0.2).cos())).collect();
        let frames = transported_frames(&normals);
        for (q, n) in frames.iter().zip(&normals) {
            assert!((*q * DVec3::Z - *n).length() < 1e-12);
            // Bending in the xz plane keeps the y axis fixed: no twist.
            assert!((*q * DVec3::Y - DVec3::Y).length() < 1e-12, "{}", *q * DVec3::Y);
        }
        assert!(frames.windows(2).all(|w| w[0].dot(w[1]) > 0.0));
    }

    #[test]
    fn a_z_axis_gets_the_identity_frame() {
        assert!(transported_frames(&[DVec3::Z])[0].abs_diff_eq(DQuat::IDENTITY, 1e-15));
    }
}
