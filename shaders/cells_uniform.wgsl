// The per-frame cell records of the deform kernel in a uniform buffer (rigs of up to
// UNIFORM_CELL_CAPACITY cells): on lavapipe and many GPUs, uniform reads are much cheaper than
// storage reads. Composed between layout.wgsl and deform.wgsl.
@group(0) @binding(1) var<uniform> cells: array<CellCoeffs, UNIFORM_CELL_CAPACITY>;
