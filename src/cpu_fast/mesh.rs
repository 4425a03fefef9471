//! A mesh on the fast path, end to end: bound to a rest rig with its falloff bands, then
//! deformed by posed sweeps, in the GPU's forms (as [`crate::gpu::GpuDeformer`] holds them),
//! optionally with its vertex normals carried through the deformation's Jacobian.

use glam::Vec4;

use super::bands::{band_records, deform_bands, flagged_owners};
use super::deform::{deform_with_bands, deform_with_normals};
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
    /// Its binding polynomials (quintics, nonics where the rotations are cubic).
    pub tables: Vec<BindSegment>,
    /// The posed cell records, refilled by [`FastMesh::deform`].
    posed: SweepCoefficients,
    /// Each vertex's normal coordinates record ([`crate::cpu::jacobian::coordinates`]); empty
    /// until [`FastMesh::with_rest_normals`].
    records: Vec<Vec4>,
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
        FastMesh { bindings, bands, posed: rest.clone(), rest, tables, records: Vec::new() }
    }

    /// Keeps Jacobian normals: each vertex's normal coordinates record, made from its rest
    /// normal in `rest_normals` (tightly packed xyz, one triple per binding), on the rest rig,
    /// for [`FastMesh::deform_with_normals`].
    ///
    /// # Panics
    ///
    /// If `rest_normals` is not three floats per binding.
    pub fn with_rest_normals(mut self, rest_normals: &[f32]) -> FastMesh {
        assert_eq!(rest_normals.len(), 3 * self.bindings.len(), "three rest normal floats per vertex");
        self.records = crate::cpu::jacobian::coordinates(&self.rest.cells, &self.bindings, rest_normals);
        self
    }

    /// Whether [`FastMesh::with_rest_normals`] gave the mesh its normal coordinates.
    pub fn has_normals(&self) -> bool {
        self.records.len() == self.bindings.len()
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

    /// [`FastMesh::deform`], and the deformed unit normals of the vertices it moves outside the
    /// falloff bands written into `normals` (tightly packed xyz): each rest normal carried
    /// through the parameter Jacobian of Eq. 2 (cof(DP)·m, [`crate::deform::jacobian`]), in the
    /// same pass. The normals of unbound and band vertices are left alone: recompute those (and
    /// those outside [`crate::deform::jacobian_normal_vertices`]: vertices whose one-ring
    /// another sweep moves, or too coarse for the deformation) from the deformed triangles
    /// (`crate::cpu::normals::normals_of`), as the GPU deformer's normals pass does. Fails,
    /// changing nothing, if `posed` lacks the rest rig's structure.
    ///
    /// # Panics
    ///
    /// If the mesh has no normal coordinates ([`FastMesh::with_rest_normals`]), or `positions`
    /// or `normals` is not three floats per vertex.
    pub fn deform_with_normals(
        &mut self,
        posed: &[Sweep],
        positions: &mut [f32],
        normals: &mut [f32],
    ) -> Result<(), StructureMismatch> {
        assert!(self.has_normals(), "FastMesh::deform_with_normals needs FastMesh::with_rest_normals");
        self.posed.update(posed)?;
        deform_with_normals(&self.posed.cells, &self.bindings, &self.records, positions, normals);
        deform_bands(&self.posed.cells, &self.rest.cells, &self.bindings, &self.bands, positions);
        Ok(())
    }
}
