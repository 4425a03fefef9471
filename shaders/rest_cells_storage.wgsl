// The rest rig's cell records in a storage buffer, for the band kernel's storage variant (rigs of
// any size). Composed after cells_storage.wgsl.
@group(0) @binding(4) var<storage, read> rest_cells: array<CellCoeffs>;
