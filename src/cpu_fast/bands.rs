//! The falloff bands on the fast path: the band vertices' second influences bound and packed
//! (the bind and band-pack kernels' twins), and their positions (the band kernel's twin). Band
//! vertices are few, and each costs two influences and a blend, so they run one by one, in
//! parallel.

use crate::parallel::join;
use crate::parallel::prelude::*;

use crate::bind::falloff::BandWeight;
use crate::coeffs::{BAND_FLAG, BandRecord, CellCoeffs, GpuBinding, UNOWNED};
use crate::cpu::band::band_vertex;
use crate::cpu::band_pack::band_pack_vertex;
use crate::cpu::bind::{BindInputs, bind_vertex};
use crate::cpu::position;

/// `owners` as the bind kernel takes them: [`BAND_FLAG`] set on the band vertices of `weights`,
/// so that their bindings carry it and the deform leaves them to the band kernel.
pub fn flagged_owners(owners: &[u32], weights: &[BandWeight]) -> Vec<u32> {
    let mut flagged = owners.to_vec();
    for weight in weights {
        flagged[weight.vertex as usize] |= BAND_FLAG;
    }
    flagged
}

/// The band records of `weights` (vertices global, sorted), their second influences bound to the
/// neighbouring sweeps of the rest rig `inputs` from `positions` (tightly packed xyz), as the GPU
/// deformer binds them.
pub fn band_records(inputs: &BindInputs, weights: &[BandWeight], positions: &[f32]) -> Vec<BandRecord> {
    weights
        .par_iter()
        .map(|weight| {
            let mut record =
                BandRecord { vertex: weight.vertex, weight: weight.weight as f32, cell: UNOWNED, s_phi: 0 };
            let second = bind_vertex(inputs, weight.neighbour, position(positions, weight.vertex as usize));
            band_pack_vertex(&second, &mut record);
            record
        })
        .collect()
}

/// Band records per task of [`deform_bands`].
const BAND_CHUNK: usize = 2048;

/// Overwrites the band vertices of `positions` that move (all but those at weight 0 against the
/// rest position) with their blended positions: `crate::cpu::band::band`, in parallel when the
/// records are sorted by vertex, one per vertex (as the deformer keeps them), without allocating.
pub fn deform_bands(
    cells: &[CellCoeffs],
    rest_cells: &[CellCoeffs],
    bindings: &[GpuBinding],
    bands: &[BandRecord],
    positions: &mut [f32],
) {
    if !bands.is_sorted_by(|a, b| a.vertex < b.vertex) {
        crate::cpu::band::band(cells, rest_cells, bindings, bands, positions);
        return;
    }
    let inputs = BandInputs { cells, rest_cells, bindings };
    split_bands(&inputs, bands, positions, 0);
}

struct BandInputs<'a> {
    cells: &'a [CellCoeffs],
    rest_cells: &'a [CellCoeffs],
    bindings: &'a [GpuBinding],
}

/// The records `bands` (sorted) of the vertices from `first` on, whose positions `positions`
/// start at vertex `first`: halves the records and the positions at the middle record's vertex
/// until a task has [`BAND_CHUNK`], and runs the halves in parallel.
fn split_bands(inputs: &BandInputs, bands: &[BandRecord], positions: &mut [f32], first: usize) {
    if bands.len() <= BAND_CHUNK {
        for band in bands {
            if let Some(p) = band_vertex(inputs.cells, inputs.rest_cells, inputs.bindings, band) {
                let i = 3 * (band.vertex as usize - first);
                positions[i..i + 3].copy_from_slice(&p.to_array());
            }
        }
        return;
    }
    let (low, high) = bands.split_at(bands.len() / 2);
    let middle = high[0].vertex as usize;
    let (low_positions, high_positions) = positions.split_at_mut(3 * (middle - first));
    join(|| split_bands(inputs, low, low_positions, first), || split_bands(inputs, high, high_positions, middle));
}
