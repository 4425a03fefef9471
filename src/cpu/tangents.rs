//! Twin of `shaders/tangents.wgsl`: deformed tangents in f32, each rest tangent's xyz turned by
//! the minimal rotation taking the rest normal n₀ to the deformed normal n (Rodrigues), made
//! orthogonal to n and normalized, w copied. The equation and the degenerate cases are those
//! of the f64 reference, [`crate::normals::tangents`].

use crate::parallel::prelude::*;
use glam::{Vec3, Vec4};

use super::position;

/// `1 + n₀ · n` at or below which the normals count as opposite
/// ([`crate::normals::tangents::OPPOSITE`]).
const OPPOSITE: f32 = 1e-4;
/// Relative squared length below which a tangent is parallel to the normal
/// ([`crate::normals::tangents::PARALLEL`]).
const PARALLEL: f32 = 1e-12;

/// A unit vector perpendicular to `n`: n × e, normalized, for the axis e least aligned with n
/// (the first of x, y, z on ties); zero for a zero `n`.
pub fn any_perpendicular(n: Vec3) -> Vec3 {
    let a = n.abs();
    let mut e = Vec3::Z;
    if a.x <= a.y && a.x <= a.z {
        e = Vec3::X;
    } else if a.y <= a.z {
        e = Vec3::Y;
    }
    let p = n.cross(e);
    let length2 = p.dot(p);
    if length2 > 0.0 {
        return p * length2.sqrt().recip();
    }
    Vec3::ZERO
}

/// The deformed tangent of one vertex from its rest normal `n0`, deformed normal `n` (each unit
/// or zero) and rest tangent `t`.
pub fn deformed_tangent(n0: Vec3, n: Vec3, t: Vec4) -> Vec4 {
    let mut v = t.truncate();
    if n0 != Vec3::ZERO && n != Vec3::ZERO {
        let c = n0.dot(n);
        if 1.0 + c > OPPOSITE {
            let k = n0.cross(n);
            v = c * v + k.cross(v) + k * (k.dot(v) / (1.0 + c));
        } else {
            // The half turn about a unit axis a perpendicular to n0.
            let a = any_perpendicular(n0);
            v = 2.0 * a * a.dot(v) - v;
        }
    }
    let u = v - n * n.dot(v);
    let length2 = u.dot(u);
    let mut d = any_perpendicular(n);
    if length2 > PARALLEL * v.dot(v) {
        d = u * length2.sqrt().recip();
    }
    d.extend(t.w)
}

/// One invocation of the kernel: the tangent of vertex `v` from the tightly packed xyz
/// `rest_normals` and `normals` and the xyzw `rest_tangents` (here whole arrays; the kernel
/// reads windows of them).
pub fn vertex_tangent(rest_normals: &[f32], normals: &[f32], rest_tangents: &[[f32; 4]], v: usize) -> Vec4 {
    let n0 = position(rest_normals, v);
    let n = position(normals, v);
    deformed_tangent(n0, n, Vec4::from_array(rest_tangents[v]))
}

/// The invocations of the kernel over `vertices`: writes their tangents into `tangents` (one
/// xyzw per vertex of the mesh; the others are left alone), in parallel.
pub fn tangents_of(
    rest_normals: &[f32],
    normals: &[f32],
    rest_tangents: &[[f32; 4]],
    vertices: &[u32],
    tangents: &mut [[f32; 4]],
) {
    let computed: Vec<[f32; 4]> = vertices
        .par_iter()
        .map(|&v| vertex_tangent(rest_normals, normals, rest_tangents, v as usize).to_array())
        .collect();
    for (&v, t) in vertices.iter().zip(computed) {
        tangents[v as usize] = t;
    }
}

/// Every vertex's tangent, written into `tangents`, in parallel.
pub fn tangents(rest_normals: &[f32], normals: &[f32], rest_tangents: &[[f32; 4]], tangents: &mut [[f32; 4]]) {
    tangents.par_iter_mut().enumerate().for_each(|(v, out)| {
        *out = vertex_tangent(rest_normals, normals, rest_tangents, v).to_array();
    });
}
