//! `sweepffd info`: the GPU adapter, its backend and the limits that shape the kernels.

use super::CliResult;
use sweepffd::coeffs::UNIFORM_CELL_CAPACITY;
use sweepffd::coeffs::WORKGROUP_SIZE;
use sweepffd::gpu::{CellRecords, DeformOrder, DeformVariant, GpuContext};

pub fn run() -> CliResult {
    let context = GpuContext::new()?;
    let info = &context.info;
    let limits = context.device.limits();
    out!("adapter:   {}", info.name);
    out!("backend:   {:?}", info.backend);
    out!("type:      {:?}", info.device_type);
    out!("driver:    {} {}", info.driver, info.driver_info);
    out!("timestamp queries:                 {}", context.has_timestamps());
    out!("max_storage_buffer_binding_size:   {} bytes", limits.max_storage_buffer_binding_size);
    out!("max_buffer_size:                   {} bytes", limits.max_buffer_size);
    out!("max_storage_buffers_per_shader_stage: {}", limits.max_storage_buffers_per_shader_stage);
    out!("max_compute_workgroups_per_dimension: {}", limits.max_compute_workgroups_per_dimension);
    out!("min_storage_buffer_offset_alignment:  {} bytes", limits.min_storage_buffer_offset_alignment);
    out!("workgroup size of the kernels:     {WORKGROUP_SIZE}");
    let small = CellRecords::Auto.variant(1, &limits, info.device_type);
    let records = match small {
        DeformVariant::Uniform => format!("uniform (rigs of up to {UNIFORM_CELL_CAPACITY} cells), storage beyond"),
        DeformVariant::Storage => "storage".to_string(),
    };
    let order = DeformOrder::Auto.on_type(info.device_type).name();
    out!("cell records (auto):               {records}");
    out!("deform order (auto):               {order}");
    Ok(())
}
