//! The WGSL kernels against their f32 twins and the f64 reference: binding and Eq. 2 (the
//! three-way equivalence), cell groups, instances, normals and Jacobian normals, tangents,
//! outputs, the naga layout checks and the zero-allocation frame.

mod cell_groups;
mod cubic_rotation;
mod equivalence;
mod frame_allocations;
mod instances;
mod jacobian_normals;
mod normal_fans;
mod outputs;
mod partial_normals;
mod shader_layout;
mod small_limits;
mod tangents;
