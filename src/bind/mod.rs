//! Vertex binding (§3): the parameters (θ, t, d, h) that tie a vertex to its sweep, on the f64
//! reference path. The f32 twin of the GPU kernel is `crate::cpu::bind`.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind** → deform → normals → output.
//!
//! For a vertex v, t is the root of f(t) = ⟨v − C(t), N(t)⟩ on [0, 1] nearest to v (smallest
//! |v − C(t)|); every root that may be the nearest is found (`plane_roots`; a knot interval
//! whose piece of C(t) lies farther from v than a root already found holds none, and is
//! skipped). A vertex with no root lies beyond an end of the sweep and takes the nearer end,
//! t ∈ {0, 1}. Then, with v̂ = R(t)ᵀ·(v − C(t)):
//! θ = atan2(v̂_y, v̂_x) ∈ [0, 2π), d = |(v̂_x, v̂_y)| − r(θ, t) and h = v̂_z. For a root h is zero
//! up to round-off; beyond an end it is the axial offset, so caps follow their sweep.

pub mod band;
pub mod falloff;
internal_mod! {
    plane_roots;
}

use std::f64::consts::TAU;

use crate::parallel::prelude::*;
use glam::DVec3;

use crate::sweep::curve::CurvePiece;
use crate::sweep::plane_polynomial::PlanePolynomial;
use crate::sweep::{AxisPoint, Sweep};

pub use band::{BandBinding, MeshBindings};

/// Marks a vertex that no sweep owns; it stays where it is. One name for the f64 path, the
/// GPU buffers and the owner lists.
pub use crate::layout::UNOWNED;

/// The binding parameters of one vertex to one sweep (Eq. 2 extended by h).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VertexBinding {
    /// Axis parameter t ∈ [0, 1] of the vertex's cross-section.
    pub t: f64,
    /// Angle θ ∈ [0, 2π) in the cross-section plane, counter-clockwise from the local x axis.
    pub theta: f64,
    /// Signed distance from the sweep surface along the cross-section's ray at θ, mesh units.
    pub d: f64,
    /// Offset along N(t): zero (up to round-off) for a root, the axial offset beyond an end.
    pub h: f64,
}

/// A vertex's binding within a mesh: which sweep it follows and how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Binding {
    /// Index of the owning sweep in the rig, or [`UNOWNED`].
    pub sweep: u32,
    /// The parameters; meaningless when `sweep` is [`UNOWNED`].
    pub params: VertexBinding,
}

impl Binding {
    /// The binding of a vertex no sweep owns.
    pub const UNOWNED: Binding =
        Binding { sweep: UNOWNED, params: VertexBinding { t: 0.0, theta: 0.0, d: 0.0, h: 0.0 } };
}

/// Binds vertices to one sweep; built once per sweep, then shared by all its vertices.
#[derive(Clone, Debug)]
pub struct SweepBinder<'a> {
    sweep: &'a Sweep,
    planes: Vec<PlanePolynomial>,
    /// A sphere around each interval's piece of C(t), to skip intervals whose every point lies
    /// farther from a vertex than a root already found.
    bounds: Vec<Bound>,
}

/// A sphere enclosing one piece of C(t): the sphere around its Bézier control points (a cubic
/// piece lies in their convex hull), widened by a margin that rounding cannot cross.
#[derive(Clone, Copy, Debug)]
struct Bound {
    center: DVec3,
    radius: f64,
    /// The size of the piece's coordinates, which scales the rounding of its points.
    magnitude: f64,
}

impl Bound {
    /// Relative slack for rounding: far above the few units in the last place by which a point
    /// evaluated on the piece, or its squared distance from a vertex, can be off.
    const SLACK: f64 = 1e-9;

    fn of(piece: &CurvePiece) -> Bound {
        let [a0, a1, a2, a3] = piece.power_coefficients();
        let control = [a0, a0 + a1 / 3.0, a0 + (2.0 * a1 + a2) / 3.0, a0 + a1 + a2 + a3];
        let center = 0.5 * (control[0] + control[3]);
        let radius = control.iter().map(|p| p.distance(center)).fold(0.0, f64::max);
        let magnitude = control.iter().map(|p| p.length()).sum::<f64>() + a1.length() + a2.length() + a3.length();
        Bound { center, radius, magnitude }
    }

    /// A distance from `v` that no point of the piece comes nearer than; at most 0 when unsure.
    fn nearest_possible(&self, v: DVec3) -> f64 {
        v.distance(self.center) - self.radius * (1.0 + Self::SLACK) - Self::SLACK * (self.magnitude + v.length())
    }
}

impl<'a> SweepBinder<'a> {
    /// Precomputes the per-interval plane polynomials of `sweep`.
    pub fn new(sweep: &'a Sweep) -> SweepBinder<'a> {
        let planes = sweep.segments().iter().map(PlanePolynomial::new).collect();
        let bounds = sweep.segments().iter().map(|segment| Bound::of(&segment.curve)).collect();
        SweepBinder { sweep, planes, bounds }
    }

    /// Every root t of ⟨v − C(t), N(t)⟩ in [0, 1], as axis points, increasing.
    pub fn roots(&self, v: DVec3) -> Vec<AxisPoint> {
        let mut roots = Vec::new();
        for (segment, plane) in self.planes.iter().enumerate() {
            plane_roots::for_each_root(&plane.for_vertex(v)[..=plane.degree], &mut |s| {
                roots.push(AxisPoint { segment, s })
            });
        }
        roots
    }

    /// The cross-section that v binds to: the root nearest to v, or the nearer end when there
    /// is no root.
    pub fn cross_section(&self, v: DVec3) -> AxisPoint {
        self.nearest_root(v).unwrap_or_else(|| self.nearer_end(v))
    }

    /// The root of ⟨v − C(t), N(t)⟩ on [0, 1] nearest to v, if there is one; of roots equally
    /// near, the first along the axis.
    ///
    /// The interval whose piece of C(t) may come nearest to v is searched first; then every
    /// other, in order, but for those whose bounding sphere lies farther from v than the
    /// nearest root found so far, which hold no nearer root. The result is that of searching
    /// every interval in order.
    pub fn nearest_root(&self, v: DVec3) -> Option<AxisPoint> {
        let segments = self.sweep.segments();
        let first = (0..segments.len())
            .min_by(|&a, &b| self.bounds[a].nearest_possible(v).total_cmp(&self.bounds[b].nearest_possible(v)))?;
        let mut best: Option<(AxisPoint, f64)> = None;
        for segment in std::iter::once(first).chain((0..segments.len()).filter(|&k| k != first)) {
            let nearest_possible = self.bounds[segment].nearest_possible(v);
            if let Some((_, best_d2)) = best
                && nearest_possible > 0.0
                && nearest_possible * nearest_possible > best_d2
            {
                continue;
            }
            let plane = &self.planes[segment];
            plane_roots::for_each_root(&plane.for_vertex(v)[..=plane.degree], &mut |s| {
                let d2 = segments[segment].curve.value(s).distance_squared(v);
                let nearer = best
                    .is_none_or(|(at, best_d2)| d2 < best_d2 || (d2 == best_d2 && (segment, s) < (at.segment, at.s)));
                if nearer {
                    best = Some((AxisPoint { segment, s }, d2));
                }
            });
        }
        best.map(|(at, _)| at)
    }

    /// The end of the sweep (t = 0 or 1) nearer to v.
    fn nearer_end(&self, v: DVec3) -> AxisPoint {
        let segments = self.sweep.segments();
        let distance = |at: &AxisPoint| segments[at.segment].curve.value(at.s).distance_squared(v);
        let start = AxisPoint { segment: 0, s: 0.0 };
        let end = AxisPoint { segment: segments.len() - 1, s: 1.0 };
        if distance(&end) < distance(&start) { end } else { start }
    }

    /// The binding of v, and whether it binds with a root (rather than by end clamping).
    pub fn bind_reporting_root(&self, v: DVec3) -> (VertexBinding, bool) {
        match self.nearest_root(v) {
            Some(at) => (self.bind_at(v, at), true),
            None => (self.bind_at(v, self.nearer_end(v)), false),
        }
    }

    /// The binding parameters (θ, t, d, h) of vertex v.
    pub fn bind(&self, v: DVec3) -> VertexBinding {
        self.bind_at(v, self.cross_section(v))
    }

    /// The binding parameters of v on the cross-section at `at`.
    fn bind_at(&self, v: DVec3, at: AxisPoint) -> VertexBinding {
        let segment = &self.sweep.segments()[at.segment];
        let local = segment.orientation.value(at.s).inverse() * (v - segment.curve.value(at.s));
        // On the axis θ is arbitrary: every path (f64, f32 twin, GPU) pins it to 0.
        let theta = if local.x == 0.0 && local.y == 0.0 { 0.0 } else { wrap_angle(local.y.atan2(local.x)) };
        let radius = self.sweep.radius_field().value(at.segment, at.s, theta);
        VertexBinding {
            t: segment.t0 + at.s * (segment.t1 - segment.t0),
            theta,
            d: local.x.hypot(local.y) - radius,
            h: local.z,
        }
    }
}

/// An angle from atan2, moved into [0, 2π).
fn wrap_angle(theta: f64) -> f64 {
    let wrapped = if theta < 0.0 { theta + TAU } else { theta };
    if wrapped >= TAU { 0.0 } else { wrapped }
}

/// Binds every vertex to the sweep that owns it (`owners[i]` indexes `sweeps`, or is
/// [`UNOWNED`]), in parallel. `progress` is called from worker threads with the number of
/// vertices just finished, every few thousand vertices.
pub fn bind_vertices(
    sweeps: &[Sweep],
    owners: &[u32],
    positions: &[DVec3],
    progress: &(dyn Fn(usize) + Sync),
) -> Vec<Binding> {
    const CHUNK: usize = 4096;
    let binders: Vec<SweepBinder> = sweeps.iter().map(SweepBinder::new).collect();
    let mut bindings = vec![Binding::UNOWNED; positions.len()];
    bindings.par_chunks_mut(CHUNK).zip(owners.par_chunks(CHUNK).zip(positions.par_chunks(CHUNK))).for_each(
        |(out, (owners, positions))| {
            for ((binding, &owner), &v) in out.iter_mut().zip(owners).zip(positions) {
                if owner != UNOWNED {
                    *binding = Binding { sweep: owner, params: binders[owner as usize].bind(v) };
                }
            }
            progress(out.len());
        },
    );
    bindings
}

#[cfg(test)]
mod tests;
