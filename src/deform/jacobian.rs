//! Normals through the deformation, on the f64 reference path: the Jacobian of Eq. 2 (extended
//! by h) maps a rest normal to the deformed one per vertex, the way skinning turns normals,
//! with no gather over the vertex's triangles. The f32 twins of the GPU kernels are
//! `crate::cpu::jacobian`.
//!
//! A bound vertex is x = P₀(θ, t, d) on the rest sweep and moves to P(θ, t, d) on the posed one,
//! so the deformation F = P ∘ P₀⁻¹ has the Jacobian J = DP · DP₀⁻¹, DP the 3 × 3 matrix of the
//! partial derivatives of P in the binding parameters. Beyond an end of the sweep (t ∈ {0, 1},
//! h ≠ 0) the parameters are (θ, h, d) instead: t is fixed there and h moves the vertex along
//! N(t). Normals, as the normals of small surface elements, transform by the cofactor matrix
//! cof(J) = det(J)·J⁻ᵀ (Nanson's formula), and cof(AB) = cof(A)·cof(B) gives
//!
//! ```text
//! n′ ∝ cof(DP) · m,    m = DP₀ᵀ·n / det(DP₀),
//! ```
//!
//! so the rest part m, the *normal coordinates*, is computed once at bind time and each frame
//! costs one cofactor product: with the columns a, b, c of DP, cof(DP)·m = m₁ b×c + m₂ c×a +
//! m₃ a×b. Normalized, n′ is the exact limit of the normals of vanishing facets around the
//! vertex; it differs from the area-weighted normal of the deformed facets by the facets'
//! size. Where DP₀ is singular (a vertex on the sweep's axis, where θ has no meaning) the
//! normal follows the frame R(t)·R₀(t)ᵀ instead.
//!
//! The columns, with the unit direction c = R(t)·(cos θ, sin θ, 0), the plane normal
//! e = R(t)·e_z, ρ = r(θ, t) + d and the angular velocity ω of R(t):
//!
//! ```text
//! ∂P/∂θ = r_θ·c + ρ·e × c
//! ∂P/∂t = C′(t) + r_t·c + ω × (ρ·c + h·e)       (∂P/∂h = e beyond an end)
//! ∂P/∂d = c
//! ```

use std::f64::consts::TAU;

use glam::{DMat3, DQuat, DVec3};

use crate::bind::VertexBinding;
use crate::sweep::Sweep;
use crate::sweep::radius::angular_cell;

/// Below this |det(DP₀)| relative to the product of its columns' lengths, the rest frame is
/// treated as singular and the normal follows the sweep's frame.
pub const SINGULAR_FRAME: f64 = 1e-6;

/// How a vertex's normal follows its sweep, fixed at bind time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalCoordinates {
    /// Through the Jacobian: m = DP₀ᵀ·n / det(DP₀), scaled to unit length (in the parameters
    /// of [`parameter_jacobian`]).
    Jacobian(DVec3),
    /// Through the frame: the rest normal in the rest frame, R₀(t)ᵀ·n.
    Frame(DVec3),
}

/// Whether `binding` lies beyond an end of its sweep, where t is fixed and h is a parameter.
pub fn is_beyond_end(binding: &VertexBinding) -> bool {
    binding.h != 0.0 && (binding.t <= 0.0 || binding.t >= 1.0)
}

/// DP: the partial derivatives of the point of `binding` on `sweep` (Eq. 2 extended by h) in
/// (θ, t, d), or (θ, h, d) beyond an end, as the columns of a matrix.
pub fn parameter_jacobian(sweep: &Sweep, binding: &VertexBinding) -> DMat3 {
    let at = sweep.locate(binding.t);
    let segment = &sweep.segments()[at.segment];
    let samples = sweep.radius_samples();
    let (j, phi) = angular_cell(binding.theta, samples);
    let c = sweep.radius_field().patch(at.segment, j).c;
    // r and its partial derivatives in the patch's local (s, φ).
    let powers = |x: f64| [1.0, x, x * x, x * x * x];
    let slopes = |x: f64| [0.0, 1.0, 2.0 * x, 3.0 * x * x];
    let (sp, ss, pp, ps) = (powers(at.s), slopes(at.s), powers(phi), slopes(phi));
    let mut r = 0.0;
    let (mut r_s, mut r_phi) = (0.0, 0.0);
    for p in 0..4 {
        for q in 0..4 {
            r += c[p][q] * sp[p] * pp[q];
            r_s += c[p][q] * ss[p] * pp[q];
            r_phi += c[p][q] * sp[p] * ps[q];
        }
    }
    let dt = segment.t1 - segment.t0;
    let (r_t, r_theta) = (r_s / dt, r_phi * samples as f64 / TAU);
    let q = segment.orientation.unnormalized(at.s);
    let dq = segment.orientation.derivative(at.s);
    let rotation = q.normalize();
    let (sin, cos) = binding.theta.sin_cos();
    let direction = rotation * DVec3::new(cos, sin, 0.0);
    let normal = rotation * DVec3::Z;
    let rho = r + binding.d;
    let along_theta = r_theta * direction + rho * normal.cross(direction);
    let along_axis = if is_beyond_end(binding) {
        normal
    } else {
        let omega = angular_velocity(q, dq) / dt;
        segment.curve.derivative(at.s) + r_t * direction + omega.cross(rho * direction + binding.h * normal)
    };
    DMat3::from_cols(along_theta, along_axis, direction)
}

/// The angular velocity of the rotation of q / |q| as q moves by `dq` per unit parameter:
/// ω = 2·vec(dq·q*) / |q|², so that d/ds (R·v) = ω × R·v.
pub fn angular_velocity(q: DQuat, dq: DQuat) -> DVec3 {
    let w = dq * q.conjugate();
    2.0 * DVec3::new(w.x, w.y, w.z) / q.length_squared()
}

/// cof(A)·m for the matrix A with columns a, b, c: m₁ b×c + m₂ c×a + m₃ a×b.
pub fn cofactor_times(a: &DMat3, m: DVec3) -> DVec3 {
    let (x, y, z) = (a.x_axis, a.y_axis, a.z_axis);
    m.x * y.cross(z) + m.y * z.cross(x) + m.z * x.cross(y)
}

/// The normal coordinates of rest normal `normal` at `binding` on the rest sweep `rest`.
pub fn normal_coordinates(rest: &Sweep, binding: &VertexBinding, normal: DVec3) -> NormalCoordinates {
    let frame = parameter_jacobian(rest, binding);
    let det = frame.determinant();
    let scale = frame.x_axis.length() * frame.y_axis.length() * frame.z_axis.length();
    if det.abs() > SINGULAR_FRAME * scale {
        let m = (frame.transpose() * normal * det.signum()).normalize_or_zero();
        NormalCoordinates::Jacobian(m)
    } else {
        NormalCoordinates::Frame(rest.orientation(binding.t).inverse() * normal)
    }
}

/// The unit normal of a vertex bound by `binding` on the posed sweep `posed`, from its normal
/// coordinates (zero where the deformation degenerates there).
pub fn deformed_normal(posed: &Sweep, binding: &VertexBinding, coordinates: &NormalCoordinates) -> DVec3 {
    match *coordinates {
        NormalCoordinates::Jacobian(m) => cofactor_times(&parameter_jacobian(posed, binding), m).normalize_or_zero(),
        NormalCoordinates::Frame(local) => (posed.orientation(binding.t) * local).normalize_or_zero(),
    }
}
