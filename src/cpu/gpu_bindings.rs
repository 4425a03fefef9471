//! Converting bindings between the reference form of [`crate::bind`] (f64, per sweep: θ, t,
//! d, h) and the GPU form of [`crate::layout`] (f32, per radius cell: s, φ, d, h), for
//! a rig's rest sweeps. Every conversion between the two lives here.
//!
//! Data flow: rig → sweep → sweep coefficients → **bind** (f64) → its f32 form for the kernels
//! and their twins → deform → normals → output.
//!
//! One vocabulary, two precisions:
//!
//! | reference (f64, [`crate::bind`]) | GPU (f32, [`crate::coeffs`]) | reference → GPU | GPU → reference |
//! | --- | --- | --- | --- |
//! | [`VertexBinding`] (θ, t, d, h) inside a [`Binding`] (sweep, params) | [`GpuBinding`] (cell, s, φ, d, h) | [`SweepCoefficients::gpu_binding`] | [`SweepCoefficients::reference_binding`] |
//! | [`Binding::UNOWNED`] | `GpuBinding { cell: UNOWNED, .. }` | the same | the same |
//! | [`BandBinding`] (vertex, w, second binding) | [`BandRecord`] (vertex, w, second cell, packed s, φ) | [`SweepCoefficients::band_record`] | none: the record drops the second binding's d and h (see [`BandRecord`]) |
//! | [`BandWeight`] (vertex, w, neighbour), before binding | a [`BandRecord`] the GPU binds | [`BandRecord::unbound`] | none |
//! | [`MeshBindings`] (vertices, bands) | `(Vec<GpuBinding>, Vec<BandRecord>)`, [`BAND_FLAG`] on band vertices | [`SweepCoefficients::gpu_mesh_bindings`] | per vertex by `reference_binding`; the bands are bound again in f64 |
//!
//! The cell of (sweep i, knot interval k, angular interval j) is
//! `first_cell(i) + k·M_i + j`; t = u_k + s·(u_{k+1} − u_k) and θ = (j + φ)·2π/M_i.

use std::f64::consts::TAU;

use super::band_pack::band_pack_vertex;
use crate::coeffs::{BAND_FLAG, BandRecord, GpuBinding, SweepCoefficients, UNOWNED};
use crate::bind::falloff::BandWeight;
use crate::bind::{BandBinding, Binding, MeshBindings, VertexBinding};
use crate::sweep::Sweep;
use crate::sweep::radius::angular_cell;

impl SweepCoefficients {
    /// The reference form of a GPU binding: t = u_k + s·(u_{k+1} − u_k), θ = (j + φ)·2π/M, in
    /// f64. `rest` are the sweeps these coefficients were built from.
    pub fn reference_binding(&self, rest: &[Sweep], binding: &GpuBinding) -> Binding {
        let binding =
            &GpuBinding { cell: if binding.cell == UNOWNED { UNOWNED } else { binding.cell & !BAND_FLAG }, ..*binding };
        let Some((sweep, info)) = (binding.cell != UNOWNED)
            .then(|| {
                self.sweeps.iter().enumerate().find(|(_, info)| {
                    (info.first_cell..info.first_cell + info.segment_count * info.samples).contains(&binding.cell)
                })
            })
            .flatten()
        else {
            return Binding::UNOWNED;
        };
        let local = binding.cell - info.first_cell;
        let (k, j) = ((local / info.samples) as usize, local % info.samples);
        let segment = &rest[sweep].segments()[k];
        let s = binding.s as f64;
        Binding {
            sweep: sweep as u32,
            params: VertexBinding {
                t: segment.t0 + s * (segment.t1 - segment.t0),
                theta: (j as f64 + binding.phi as f64) * TAU / info.samples as f64,
                d: binding.d as f64,
                h: binding.h as f64,
            },
        }
    }

    /// The GPU forms of a mesh's bindings: one binding per vertex ([`BAND_FLAG`] set on band
    /// vertices) and the band records, vertices global.
    pub fn gpu_mesh_bindings(&self, rest: &[Sweep], bindings: &MeshBindings) -> (Vec<GpuBinding>, Vec<BandRecord>) {
        let mut vertices: Vec<GpuBinding> = bindings.vertices.iter().map(|b| self.gpu_binding(rest, b)).collect();
        let records = bindings
            .bands
            .iter()
            .map(|band| {
                vertices[band.vertex as usize].cell |= BAND_FLAG;
                self.band_record(rest, band)
            })
            .collect();
        (vertices, records)
    }

    /// The GPU band record of a band vertex, its vertex global.
    pub fn band_record(&self, rest: &[Sweep], band: &BandBinding) -> BandRecord {
        let second = self.gpu_binding(rest, &band.second);
        let mut record = BandRecord { vertex: band.vertex, weight: band.weight as f32, cell: 0, s_phi: 0 };
        band_pack_vertex(&second, &mut record);
        record
    }

    /// The GPU form of a reference binding, in f32.
    pub fn gpu_binding(&self, rest: &[Sweep], binding: &Binding) -> GpuBinding {
        if binding.sweep == UNOWNED {
            return GpuBinding { cell: UNOWNED, s: 0.0, phi: 0.0, d: 0.0, h: 0.0 };
        }
        let info = self.sweeps[binding.sweep as usize];
        let at = rest[binding.sweep as usize].locate(binding.params.t);
        let (j, phi) = angular_cell(binding.params.theta, info.samples as usize);
        GpuBinding {
            cell: info.first_cell + at.segment as u32 * info.samples + j as u32,
            s: at.s as f32,
            phi: phi as f32,
            d: binding.params.d as f32,
            h: binding.params.h as f32,
        }
    }
}

impl BandRecord {
    /// The record of a band vertex before the GPU binds its second influence: its weight w in
    /// f32, its vertex made relative to `first_vertex` (its dispatch's), cell and (s, φ) 0 until
    /// the band-pack kernel fills them.
    pub fn unbound(weight: &BandWeight, first_vertex: u32) -> BandRecord {
        BandRecord { vertex: weight.vertex - first_vertex, weight: weight.weight as f32, cell: 0, s_phi: 0 }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::bind::SweepBinder;
    use crate::synthetic::{Tube, tube_rig};

    #[test]
    fn reference_and_gpu_forms_convert_both_ways() {
        let rig = tube_rig(&Tube { rings: 3, around: 8, length: 2.0, radius: 0.5 }, 4, 8);
        let rest = rig.rest();
        let coefficients = SweepCoefficients::new(rest);
        let binder = SweepBinder::new(&rest[0]);
        for v in [DVec3::new(0.3, -0.2, 0.1), DVec3::new(-0.6, 0.1, 1.3), DVec3::new(0.0, 0.7, 2.4)] {
            let reference = Binding { sweep: 0, params: binder.bind(v) };
            let back = coefficients.reference_binding(rest, &coefficients.gpu_binding(rest, &reference));
            assert_eq!(back.sweep, 0);
            assert!((back.params.t - reference.params.t).abs() < 1e-7);
            assert!((back.params.theta - reference.params.theta).abs() < 1e-6);
            assert!((back.params.d - reference.params.d).abs() < 1e-7);
        }
        let unowned = coefficients.gpu_binding(rest, &Binding::UNOWNED);
        assert_eq!(unowned.cell, UNOWNED);
        assert_eq!(coefficients.reference_binding(rest, &unowned), Binding::UNOWNED);
    }
}
