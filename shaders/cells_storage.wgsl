// The per-frame cell records in a storage buffer, for rigs of any size (and for binding).
// Composed between layout.wgsl and deform.wgsl or bind.wgsl.
@group(0) @binding(1) var<storage, read> cells: array<CellCoeffs>;
