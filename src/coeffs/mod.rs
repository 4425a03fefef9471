//! Sweep coefficients: a rig's sweeps as compact f32 arrays for the per-vertex kernels (WGSL
//! and their CPU twins).
//!
//! Data flow: rig → sweep → **sweep coefficients** → bind → deform → normals → output.
//!
//! Every frame the posed sweeps become a few KB of [`SegmentCoeffs`] (curve and orientation per
//! knot interval) and [`PatchCoeffs`] (bicubic radius per knot × angular interval); only these
//! travel to the GPU. Binding additionally needs the rest rig's [`BindSegment`]s and
//! [`SweepInfo`]s. Indices are global across the rig: sweep i's intervals and patches follow
//! those of sweeps 0..i.

mod convert;
pub mod layout;

use std::f64::consts::PI;

use glam::{DQuat, DVec3};

pub use layout::{
    BindSegment, DispatchParams, GpuBinding, Joint, PatchCoeffs, SegmentCoeffs, SkinInfluence,
    SweepInfo, UNBOUND, WORKGROUP_SIZE,
};

use crate::sweep::Sweep;
use crate::sweep::plane_quintic::PlaneQuintic;

/// The per-frame coefficient arrays of a rig, sized once for its structure and refilled in
/// place for each pose.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepCoefficients {
    /// One entry per knot interval of every sweep.
    pub segments: Vec<SegmentCoeffs>,
    /// One entry per (knot interval, angular interval) of every sweep.
    pub patches: Vec<PatchCoeffs>,
    /// Where each sweep's segments and patches start.
    pub sweeps: Vec<SweepInfo>,
}

impl SweepCoefficients {
    /// Sizes the arrays for the structure of `sweeps` (interval and radius counts) and fills
    /// them with their coefficients.
    pub fn new(sweeps: &[Sweep]) -> SweepCoefficients {
        let mut infos = Vec::with_capacity(sweeps.len());
        let (mut segments, mut patches) = (0u32, 0u32);
        for sweep in sweeps {
            let (n, m) = (sweep.segments().len() as u32, sweep.radius_samples() as u32);
            infos.push(SweepInfo {
                first_segment: segments,
                segment_count: n,
                first_patch: patches,
                samples: m,
            });
            segments += n;
            patches += n * m;
        }
        let mut coefficients = SweepCoefficients {
            segments: vec![SegmentCoeffs::default(); segments as usize],
            patches: vec![PatchCoeffs::default(); patches as usize],
            sweeps: infos,
        };
        coefficients
            .update(sweeps)
            .expect("arrays sized from these very sweeps");
        coefficients
    }

    /// Whether `sweeps` have the structure these arrays were sized for.
    pub fn fits(&self, sweeps: &[Sweep]) -> bool {
        sweeps.len() == self.sweeps.len()
            && sweeps.iter().zip(&self.sweeps).all(|(sweep, info)| {
                sweep.segments().len() == info.segment_count as usize
                    && sweep.radius_samples() == info.samples as usize
            })
    }

    /// Refills the arrays from posed `sweeps` without allocating. Fails, changing nothing, if
    /// the sweeps lack the structure the arrays were built for ([`SweepCoefficients::fits`]);
    /// a pose checked by [`crate::rig::Rig::pose`] always has it.
    pub fn update(&mut self, sweeps: &[Sweep]) -> Result<(), StructureMismatch> {
        if !self.fits(sweeps) {
            return Err(StructureMismatch);
        }
        for (sweep, info) in sweeps.iter().zip(&self.sweeps) {
            let m = info.samples as usize;
            let half_step = PI / m as f64;
            for (k, segment) in sweep.segments().iter().enumerate() {
                let global = info.first_segment as usize + k;
                let [origin, c1, c2, c3] = segment.curve.power_coefficients();
                self.segments[global] = SegmentCoeffs {
                    origin: vec4(origin),
                    curve: [vec4(c1), vec4(c2), vec4(c3)],
                    q0: quat4(segment.orientation.start),
                    q1: quat4(segment.orientation.end),
                };
                for j in 0..m {
                    let patch = sweep.radius_field().patch(k, j);
                    let mid = (2 * j + 1) as f64 * half_step;
                    self.patches[info.first_patch as usize + k * m + j] = PatchCoeffs {
                        radius: patch.c.map(|row| row.map(|c| c as f32)),
                        segment: global as u32,
                        cos_mid: mid.cos() as f32,
                        sin_mid: mid.sin() as f32,
                        half_step: half_step as f32,
                    };
                }
            }
        }
        Ok(())
    }
}

/// Posed sweeps whose number of sweeps, knot intervals or radii differs from the rig that a
/// [`SweepCoefficients`] was sized for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the posed sweeps differ from the rest rig in number of sweeps, keys or radii")]
pub struct StructureMismatch;

/// The binding quintic of every knot interval of the rest sweeps, in global segment order.
pub fn bind_segments(rest: &[Sweep]) -> Vec<BindSegment> {
    rest.iter()
        .flat_map(|sweep| sweep.segments())
        .map(|segment| {
            let quintic = PlaneQuintic::new(segment);
            let e = quintic.curve_dot_normal;
            BindSegment {
                origin: vec4(quintic.origin),
                normal: quintic.normal.map(vec4),
                e_low: [e[0] as f32, e[1] as f32, e[2] as f32, e[3] as f32],
                e5: e[4] as f32,
                t0: segment.t0 as f32,
                t1: segment.t1 as f32,
                _pad: 0.0,
            }
        })
        .collect()
}

fn vec4(v: DVec3) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, 0.0]
}

fn quat4(q: DQuat) -> [f32; 4] {
    [q.x as f32, q.y as f32, q.z as f32, q.w as f32]
}
