//! Sweep coefficients: a rig's sweeps as compact f32 arrays for the per-vertex kernels (WGSL
//! and their CPU twins).
//!
//! Data flow: rig → sweep → **sweep coefficients** → bind → deform → normals → output.
//!
//! Every frame the posed sweeps become a few KB of [`CellCoeffs`], one record per (knot
//! interval, angular interval) cell holding everything a vertex in it needs (bicubic radius,
//! curve, orientation ends, angular constants); only these travel to the GPU. Binding
//! additionally needs the rest rig's [`BindSegment`]s and [`SweepInfo`]s. Indices are global
//! across the rig: sweep i's intervals and cells follow those of sweeps 0..i.

use std::f64::consts::PI;

use glam::{DQuat, DVec3};

pub use crate::layout::{
    BAND_FLAG, BandFlag, BandRecord, BindSegment, CELL_BITS, CELL_GROUP, CELL_MASK, CellCoeffs, CellOrderParams,
    DispatchParams, GpuBinding, INSTANCES_PER_INVOCATION, InstanceParams, Joint, KEEPS_REST, MAX_PACKED_CELLS,
    PARAMETER_BITS, PARAMETER_MAX, PARAMETER_SCALE, PackedBinding, SCAN_RUN, SkinInfluence, SweepInfo,
    UNIFORM_CELL_CAPACITY, UNOWNED, WORKGROUP_SIZE,
};

use crate::sweep::Sweep;
use crate::sweep::plane_polynomial::PlanePolynomial;

/// The per-frame coefficient array of a rig, sized once for its structure and refilled in
/// place for each pose.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepCoefficients {
    /// One record per (knot interval, angular interval) cell of every sweep.
    pub cells: Vec<CellCoeffs>,
    /// Where each sweep's knot intervals and cells start.
    pub sweeps: Vec<SweepInfo>,
}

impl SweepCoefficients {
    /// Sizes the array for the structure of `sweeps` (interval and radius counts) and fills it
    /// with their coefficients.
    pub fn new(sweeps: &[Sweep]) -> SweepCoefficients {
        let mut infos = Vec::with_capacity(sweeps.len());
        let (mut segments, mut cells) = (0u32, 0u32);
        for sweep in sweeps {
            let (n, m) = (sweep.segments().len() as u32, sweep.radius_samples() as u32);
            infos.push(SweepInfo { first_segment: segments, segment_count: n, first_cell: cells, samples: m });
            segments += n;
            cells += n * m;
        }
        let mut coefficients = SweepCoefficients { cells: vec![CellCoeffs::default(); cells as usize], sweeps: infos };
        coefficients.update(sweeps).expect("arrays sized from these very sweeps");
        coefficients
    }

    /// The sweep whose cells hold `cell` (its [`BAND_FLAG`] ignored), or [`UNOWNED`] for
    /// [`UNOWNED`] or a cell past the last sweep's.
    pub fn sweep_of_cell(&self, cell: u32) -> u32 {
        if cell == UNOWNED {
            return UNOWNED;
        }
        let cell = cell & !BAND_FLAG;
        let after = self.sweeps.partition_point(|info| info.first_cell <= cell);
        match after.checked_sub(1).map(|i| (i, &self.sweeps[i])) {
            Some((i, info)) if cell < info.first_cell + info.segment_count * info.samples => i as u32,
            _ => UNOWNED,
        }
    }

    /// Whether `sweeps` have the structure these arrays were sized for.
    pub fn fits(&self, sweeps: &[Sweep]) -> bool {
        sweeps.len() == self.sweeps.len()
            && sweeps.iter().zip(&self.sweeps).all(|(sweep, info)| {
                sweep.segments().len() == info.segment_count as usize && sweep.radius_samples() == info.samples as usize
            })
    }

    /// Refills the array from posed `sweeps` without allocating. Fails, changing nothing, if
    /// the sweeps lack the structure the array was built for ([`SweepCoefficients::fits`]); a
    /// pose checked by [`crate::rig::Rig::pose`] always has it.
    pub fn update(&mut self, sweeps: &[Sweep]) -> Result<(), StructureMismatch> {
        if !self.fits(sweeps) {
            return Err(StructureMismatch);
        }
        for (sweep, info) in sweeps.iter().zip(&self.sweeps) {
            let m = info.samples as usize;
            let half_step = PI / m as f64;
            for (k, segment) in sweep.segments().iter().enumerate() {
                let mut curve = segment.curve.power_coefficients().map(vec4);
                curve[0][3] = half_step as f32;
                curve[1][3] = CellCoeffs::ends(k, sweep.segments().len());
                curve[2][3] = f32::from(u8::from(segment.orientation.cubic));
                let power = segment.orientation.power;
                for j in 0..m {
                    // R(t)·Rz(θ_mid) as one quaternion: right multiplication by qz(θ_mid) is linear,
                    // so it turns each power coefficient of q(s).
                    let middle = DQuat::from_rotation_z((2 * j + 1) as f64 * half_step);
                    let c = sweep.radius_field().patch(k, j).c;
                    let radius = std::array::from_fn(|q| std::array::from_fn(|p| c[p][q] as f32));
                    let rotation = if segment.orientation.cubic {
                        power.map(|a| quat4(a * middle))
                    } else {
                        // As the linear interpolation mixes its ends: a1 = q̃_{k+1}·qz − q_k·qz.
                        let (q0, q1) = (segment.orientation.start * middle, segment.orientation.end * middle);
                        [quat4(q0), quat4(q1 - q0), [0.0; 4], [0.0; 4]]
                    };
                    self.cells[info.first_cell as usize + k * m + j] = CellCoeffs { radius, curve, rotation };
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

/// The binding polynomial of every knot interval of the rest sweeps, in global segment order.
pub fn bind_segments(rest: &[Sweep]) -> Vec<BindSegment> {
    rest.iter()
        .flat_map(|sweep| sweep.segments())
        .map(|segment| {
            let plane = PlanePolynomial::new(segment);
            let e = plane.curve_dot_normal.map(|e| e as f32);
            BindSegment {
                origin: vec4(plane.origin),
                normal: plane.normal.map(vec4),
                e_low: [e[0], e[1], e[2], e[3]],
                e_high: [e[4], e[5], e[6], e[7]],
                e9: e[8],
                t0: segment.t0 as f32,
                t1: segment.t1 as f32,
                degree: plane.degree as u32,
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
