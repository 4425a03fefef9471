// The rest rig's cell records in a uniform buffer, for the band kernel's uniform variant (rigs of
// up to UNIFORM_CELL_CAPACITY cells). Composed after cells_uniform.wgsl.
@group(0) @binding(4) var<uniform> rest_cells: array<CellCoeffs, UNIFORM_CELL_CAPACITY>;
