//! Key orientations whose normal follows the axis, with θ = 0 carried along the axis by
//! parallel transport so that the frames do not twist between keys.

use glam::{DMat3, DQuat, DVec3};

/// One rotation per normal: the local z axis is the normal; the local x axis (θ = 0) of the
/// first key is `reference` made orthogonal to its normal (a direction taken from the part,
/// so that the frames of a rigidly moved part are the moved frames), or where that is `None`
/// or nearly along the normal, the world axis least aligned with the normal; each next key's
/// x axis is the previous one turned by the smallest rotation between the normals.
/// Successive quaternions are sign-aligned, as R(t)'s interpolation expects.
pub fn transported_frames(normals: &[DVec3], reference: Option<DVec3>) -> Vec<DQuat> {
    let mut rotations: Vec<DQuat> = Vec::with_capacity(normals.len());
    let mut x_axis = DVec3::ZERO;
    for (i, &normal) in normals.iter().enumerate() {
        x_axis = if i == 0 {
            first_x_axis(normal, reference)
        } else {
            DQuat::from_rotation_arc(normals[i - 1], normal) * x_axis
        };
        x_axis = (x_axis - normal * x_axis.dot(normal)).normalize();
        let mut rotation = DQuat::from_mat3(&DMat3::from_cols(x_axis, normal.cross(x_axis), normal)).normalize();
        if rotations.last().is_some_and(|previous| previous.dot(rotation) < 0.0) {
            rotation = -rotation;
        }
        rotations.push(rotation);
    }
    rotations
}

/// `reference` without its component along `normal`, where that leaves at least 1e-3 of its
/// length; else the world axis (X, then Y, then Z on ties) with the smallest component along
/// `normal`.
pub fn first_x_axis(normal: DVec3, reference: Option<DVec3>) -> DVec3 {
    reference
        .map(|r| (r, r - normal * r.dot(normal)))
        .filter(|(r, across)| across.length() > 1e-3 * r.length())
        .and_then(|(_, across)| across.try_normalize())
        .unwrap_or_else(|| least_aligned_axis(normal))
}

/// A direction across the axis taken from the part itself, for θ = 0 (see
/// [`transported_frames`]): the offset of the part's centroid from the axis line through
/// `start` along the unit `tangent` (where the part bends away from its first tangent, by
/// more than 1e-3 of `length`), else the skew Σ q|q|² of the vertices' offsets q from the
/// centroid across the tangent (which side the part bulges to); `None` for a part symmetric
/// enough to have neither (a round tube), whose frames then take a world axis.
pub fn reference_direction(positions: &[DVec3], start: DVec3, tangent: DVec3, length: f64) -> Option<DVec3> {
    let across = |d: DVec3| d - tangent * d.dot(tangent);
    let centroid = positions.iter().copied().sum::<DVec3>() / positions.len().max(1) as f64;
    let bend = across(centroid - start);
    if bend.length() > 1e-3 * length {
        return Some(bend);
    }
    let (mut skew, mut scale) = (DVec3::ZERO, 0.0);
    for &p in positions {
        let q = across(p - centroid);
        skew += q * q.length_squared();
        scale += q.length_squared() * q.length();
    }
    (skew.length() > 1e-3 * scale).then_some(skew)
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
        let frames = transported_frames(&normals, None);
        for (q, n) in frames.iter().zip(&normals) {
            assert!((*q * DVec3::Z - *n).length() < 1e-12);
            // Bending in the xz plane keeps the y axis fixed: no twist.
            assert!((*q * DVec3::Y - DVec3::Y).length() < 1e-12, "{}", *q * DVec3::Y);
        }
        assert!(frames.windows(2).all(|w| w[0].dot(w[1]) > 0.0));
    }

    #[test]
    fn a_reference_direction_sets_theta_0() {
        let frame = transported_frames(&[DVec3::Z], Some(DVec3::new(0.0, 2.0, 1.0)))[0];
        assert!((frame * DVec3::X - DVec3::Y).length() < 1e-15);
        // Along the normal, the reference cannot set θ = 0: the world axis does.
        assert!(transported_frames(&[DVec3::Z], Some(DVec3::Z))[0].abs_diff_eq(DQuat::IDENTITY, 1e-15));
    }

    #[test]
    fn a_z_axis_gets_the_identity_frame() {
        assert!(transported_frames(&[DVec3::Z], None)[0].abs_diff_eq(DQuat::IDENTITY, 1e-15));
    }
}
