//! A mesh on the fast path, end to end: bound to a rest rig with its falloff bands, then
//! deformed by posed sweeps, in the GPU's forms (as [`crate::gpu::GpuDeformer`] holds them).

use super::bands::{band_records, flagged_owners};
use super::deform::deform_with_bands;
use crate::bind::falloff::BandWeight;
use crate::coeffs::{BandRecord, BindSegment, GpuBinding, StructureMismatch, SweepCoefficients, bind_segments};
use crate::cpu::bind::BindInputs;
use crate::sweep::Sweep;

/// A mesh bound on the fast path to its rest rig: one binding per vertex ([`crate::coeffs::BAND_FLAG`]
/// on band vertices), the band records, and the rest rig's tables.
#[derive(Clone, Debug)]
pub struct FastMesh {
    /// The binding of each vertex.
    pub bindings: Vec<GpuBinding>,
    /// The band vertices' records, sorted by vertex.
    pub bands: Vec<BandRecord>,
    /// The rest rig's cell records (the band kernel reads them).
    pub rest: SweepCoefficients,
    /// Its binding quintics.
    pub tables: Vec<BindSegment>,
    /// The posed cell records, refilled by [`FastMesh::deform`].
    posed: SweepCoefficients,
}

impl FastMesh {
    /// Binds `positions` (tightly packed xyz) owned by `owners[i]`, with the falloff bands of
    /// `weights` (vertices sorted), to the rest sweeps `rest`.
    pub fn bind(rest: &[Sweep], owners: &[u32], weights: &[BandWeight], positions: &[f32]) -> FastMesh {
        let coefficients = SweepCoefficients::new(rest);
        let tables = bind_segments(rest);
        let inputs = BindInputs { cells: &coefficients.cells, bind_segments: &tables, sweeps: &coefficients.sweeps };
        let mut bindings = vec![GpuBinding::default(); owners.len()];
        super::bind::bind(&inputs, &flagged_owners(owners, weights), positions, &mut bindings);
        let bands = band_records(&inputs, weights, positions);
        FastMesh::from_parts(coefficients, tables, bindings, bands)
    }

    /// Bindings and band records made before (by [`FastMesh::bind`], the GPU, or converted from
    /// the reference form by [`SweepCoefficients::gpu_mesh_bindings`]) for the rest sweeps `rest`.
    pub fn with_bindings(rest: &[Sweep], bindings: Vec<GpuBinding>, bands: Vec<BandRecord>) -> FastMesh {
        FastMesh::from_parts(SweepCoefficients::new(rest), bind_segments(rest), bindings, bands)
    }

    fn from_parts(
        rest: SweepCoefficients,
        tables: Vec<BindSegment>,
        bindings: Vec<GpuBinding>,
        bands: Vec<BandRecord>,
    ) -> FastMesh {
        FastMesh { bindings, bands, posed: rest.clone(), rest, tables }
    }

    /// Overwrites the moving vertices of `positions` (tightly packed xyz, rest positions before
    /// the first call) with their positions on the posed sweeps `posed`; unbound vertices and
    /// band vertices at weight 0 against the rest position are left alone. Fails, changing
    /// nothing, if `posed` lacks the rest rig's structure.
    pub fn deform(&mut self, posed: &[Sweep], positions: &mut [f32]) -> Result<(), StructureMismatch> {
        self.posed.update(posed)?;
        deform_with_bands(&self.posed.cells, &self.rest.cells, &self.bindings, &self.bands, positions);
        Ok(())
    }
}
