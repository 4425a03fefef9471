//! The WGSL kernels, composed from `shaders/` and validated with naga at build time (see
//! `build.rs`): each is the shared `layout.wgsl` (and `sweep_eval.wgsl` where needed) followed
//! by the kernel's own file.

/// Binding (§3) of every owned vertex: `shaders/bind.wgsl`, entry point `bind_main`.
pub const BIND: &str = include_str!(concat!(env!("OUT_DIR"), "/bind.wgsl"));
/// Eq. 2 for every bound vertex, cell records in a uniform buffer: `shaders/deform.wgsl` after
/// `shaders/cells_uniform.wgsl` and before `shaders/deform_groups.wgsl`, entry points
/// `deform_main` (one workgroup layer per instance), `deform_staged_main` (the same, a
/// workgroup's positions stored whole), `deform_instances_main` (instances numbered flat), and over cell groups `deform_groups_main` and `deform_groups_instances_main`.
pub const DEFORM_UNIFORM: &str = include_str!(concat!(env!("OUT_DIR"), "/deform_uniform.wgsl"));
/// Eq. 2 for every bound vertex, cell records in a storage buffer: `shaders/deform.wgsl` after
/// `shaders/cells_storage.wgsl` and before `shaders/deform_groups.wgsl`, the same entry points.
pub const DEFORM_STORAGE: &str = include_str!(concat!(env!("OUT_DIR"), "/deform_storage.wgsl"));
/// Eq. 2 fused with the Jacobian normals, cell records in a uniform buffer:
/// `shaders/deform_normals.wgsl` after `shaders/cells_uniform.wgsl` and `shaders/jacobian.wgsl`
/// and before `shaders/deform_normals_groups.wgsl`, entry points `deform_normals_main` and, over
/// cell groups, `deform_normals_groups_main`.
pub const DEFORM_NORMALS_UNIFORM: &str = include_str!(concat!(env!("OUT_DIR"), "/deform_normals_uniform.wgsl"));
/// The same, cell records in a storage buffer.
pub const DEFORM_NORMALS_STORAGE: &str = include_str!(concat!(env!("OUT_DIR"), "/deform_normals_storage.wgsl"));
/// The normal coordinates of every vertex at creation, rest cell records in a uniform buffer:
/// `shaders/normal_coords.wgsl` after `shaders/jacobian.wgsl`, entry point `normal_coords_main`.
pub const NORMAL_COORDS_UNIFORM: &str = include_str!(concat!(env!("OUT_DIR"), "/normal_coords_uniform.wgsl"));
/// The same, rest cell records in a storage buffer.
pub const NORMAL_COORDS_STORAGE: &str = include_str!(concat!(env!("OUT_DIR"), "/normal_coords_storage.wgsl"));
/// Falloff bands, cell records in uniform buffers: `shaders/band.wgsl` after
/// `shaders/cells_uniform.wgsl`, `shaders/rest_cells_uniform.wgsl` and `shaders/blend.wgsl`, entry
/// point `band_main`.
pub const BAND_UNIFORM: &str = include_str!(concat!(env!("OUT_DIR"), "/band_uniform.wgsl"));
/// Falloff bands, cell records in storage buffers: `shaders/band.wgsl` after
/// `shaders/cells_storage.wgsl`, `shaders/rest_cells_storage.wgsl` and `shaders/blend.wgsl`, entry
/// point `band_main`.
pub const BAND_STORAGE: &str = include_str!(concat!(env!("OUT_DIR"), "/band_storage.wgsl"));
/// The band records' second influences from bindings: `shaders/band_pack.wgsl`, `band_pack_main`.
pub const BAND_PACK: &str = include_str!(concat!(env!("OUT_DIR"), "/band_pack.wgsl"));
/// The cell groups of a chunk's vertices, a counting sort by (block, cell):
/// `shaders/cell_order.wgsl`, entry points `cell_order_clear_main`, `cell_order_count_main`,
/// `cell_order_sums_main`, `cell_order_scan_main`, `cell_order_offsets_main`,
/// `cell_order_scatter_main` and `cell_order_fill_main`, run in that order.
pub const CELL_ORDER: &str = include_str!(concat!(env!("OUT_DIR"), "/cell_order.wgsl"));
/// Band membership changes when the falloff bands are replaced: `shaders/band_flags.wgsl`,
/// `band_flags_main`.
pub const BAND_FLAGS: &str = include_str!(concat!(env!("OUT_DIR"), "/band_flags.wgsl"));
/// Area-weighted vertex normals when the positions fit one storage binding:
/// `shaders/normals.wgsl` with `shaders/positions_one_window.wgsl`, entry point `normals_main`.
pub const NORMALS_ONE_WINDOW: &str = include_str!(concat!(env!("OUT_DIR"), "/normals_one_window.wgsl"));
/// Area-weighted vertex normals reading the positions through two storage bindings:
/// `shaders/normals.wgsl` with `shaders/positions_two_windows.wgsl`, entry point `normals_main`.
pub const NORMALS_TWO_WINDOWS: &str = include_str!(concat!(env!("OUT_DIR"), "/normals_two_windows.wgsl"));
/// Per-instance bounds of the deformed positions on ordered u32 encodings:
/// `shaders/bounds.wgsl`, entry point `bounds_main`.
pub const BOUNDS: &str = include_str!(concat!(env!("OUT_DIR"), "/bounds.wgsl"));
/// The bounds decoded to f32 min.xyz, 0, max.xyz, 0: `shaders/bounds_finalize.wgsl`, entry point
/// `bounds_finalize_main`.
pub const BOUNDS_FINALIZE: &str = include_str!(concat!(env!("OUT_DIR"), "/bounds_finalize.wgsl"));
/// Benchmark baseline moving the deform kernel's bytes: `shaders/copy.wgsl`, `copy_main`.
pub const COPY: &str = include_str!(concat!(env!("OUT_DIR"), "/copy.wgsl"));
/// Benchmark baseline moving the fused deform + Jacobian normals kernel's bytes:
/// `shaders/copy_wide.wgsl`, `copy_wide_main`.
pub const COPY_WIDE: &str = include_str!(concat!(env!("OUT_DIR"), "/copy_wide.wgsl"));
/// Benchmark baseline, four-influence linear-blend skinning: `shaders/skinning.wgsl`,
/// `skinning_main`.
pub const SKINNING: &str = include_str!(concat!(env!("OUT_DIR"), "/skinning.wgsl"));
/// Deformed tangents, the rest tangents turned with the normals: `shaders/tangents.wgsl`,
/// entry point `tangents_main`.
pub const TANGENTS: &str = include_str!(concat!(env!("OUT_DIR"), "/tangents.wgsl"));

/// The Jacobian probe's verdicts at creation: `shaders/jacobian_probe.wgsl`,
/// `jacobian_probe_main`.
pub const JACOBIAN_PROBE: &str = include_str!(concat!(env!("OUT_DIR"), "/jacobian_probe.wgsl"));

/// Every kernel as (name, composed source, entry point).
pub const ALL: [(&str, &str, &str); 38] = [
    ("bind", BIND, "bind_main"),
    ("bind_cubic", BIND, "bind_cubic_main"),
    ("deform_uniform", DEFORM_UNIFORM, "deform_main"),
    ("deform_storage", DEFORM_STORAGE, "deform_main"),
    ("deform_instances_uniform", DEFORM_UNIFORM, "deform_instances_main"),
    ("deform_staged_uniform", DEFORM_UNIFORM, "deform_staged_main"),
    ("deform_staged_storage", DEFORM_STORAGE, "deform_staged_main"),
    ("deform_instances_storage", DEFORM_STORAGE, "deform_instances_main"),
    ("deform_groups_uniform", DEFORM_UNIFORM, "deform_groups_main"),
    ("deform_groups_storage", DEFORM_STORAGE, "deform_groups_main"),
    ("deform_groups_instances_uniform", DEFORM_UNIFORM, "deform_groups_instances_main"),
    ("deform_groups_instances_storage", DEFORM_STORAGE, "deform_groups_instances_main"),
    ("deform_normals_uniform", DEFORM_NORMALS_UNIFORM, "deform_normals_main"),
    ("deform_normals_storage", DEFORM_NORMALS_STORAGE, "deform_normals_main"),
    ("deform_normals_groups_uniform", DEFORM_NORMALS_UNIFORM, "deform_normals_groups_main"),
    ("deform_normals_groups_storage", DEFORM_NORMALS_STORAGE, "deform_normals_groups_main"),
    ("normal_coords_uniform", NORMAL_COORDS_UNIFORM, "normal_coords_main"),
    ("normal_coords_storage", NORMAL_COORDS_STORAGE, "normal_coords_main"),
    ("band_uniform", BAND_UNIFORM, "band_main"),
    ("band_storage", BAND_STORAGE, "band_main"),
    ("band_pack", BAND_PACK, "band_pack_main"),
    ("band_flags", BAND_FLAGS, "band_flags_main"),
    ("cell_order_clear", CELL_ORDER, "cell_order_clear_main"),
    ("cell_order_count", CELL_ORDER, "cell_order_count_main"),
    ("cell_order_sums", CELL_ORDER, "cell_order_sums_main"),
    ("cell_order_scan", CELL_ORDER, "cell_order_scan_main"),
    ("cell_order_offsets", CELL_ORDER, "cell_order_offsets_main"),
    ("cell_order_scatter", CELL_ORDER, "cell_order_scatter_main"),
    ("cell_order_fill", CELL_ORDER, "cell_order_fill_main"),
    ("normals_one_window", NORMALS_ONE_WINDOW, "normals_main"),
    ("normals_two_windows", NORMALS_TWO_WINDOWS, "normals_main"),
    ("bounds", BOUNDS, "bounds_main"),
    ("bounds_finalize", BOUNDS_FINALIZE, "bounds_finalize_main"),
    ("copy", COPY, "copy_main"),
    ("copy_wide", COPY_WIDE, "copy_wide_main"),
    ("skinning", SKINNING, "skinning_main"),
    ("tangents", TANGENTS, "tangents_main"),
    ("jacobian_probe", JACOBIAN_PROBE, "jacobian_probe_main"),
];
