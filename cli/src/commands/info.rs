//! `sweepffd info`: the GPU adapter, its backend and the limits that shape the kernels.

use super::CliResult;
use sweepffd::coeffs::UNIFORM_CELL_CAPACITY;
use sweepffd::coeffs::WORKGROUP_SIZE;
use sweepffd::gpu::{CellRecords, DeformOrder, DeformVariant, GpuContext};

pub fn run() -> CliResult {
    let context = GpuContext::new()?;
    let info = &context.info;
    let limits = context.device.limits();
    println!("adapter:   {}", info.name);
    println!("backend:   {:?}", info.backend);
    println!("type:      {:?}", info.device_type);
    println!("driver:    {} {}", info.driver, info.driver_info);
    println!("timestamp queries:                 {}", context.has_timestamps());
    println!("max_storage_buffer_binding_size:   {} bytes", limits.max_storage_buffer_binding_size);
    println!("max_buffer_size:                   {} bytes", limits.max_buffer_size);
    println!("max_storage_buffers_per_shader_stage: {}", limits.max_storage_buffers_per_shader_stage);
    println!("max_compute_workgroups_per_dimension: {}", limits.max_compute_workgroups_per_dimension);
    println!("min_storage_buffer_offset_alignment:  {} bytes", limits.min_storage_buffer_offset_alignment);
    println!("workgroup size of the kernels:     {WORKGROUP_SIZE}");
    let small = CellRecords::Auto.variant(1, &limits, info.device_type);
    let records = match small {
        DeformVariant::Uniform => format!("uniform (rigs of up to {UNIFORM_CELL_CAPACITY} cells), storage beyond"),
        DeformVariant::Storage => "storage".to_string(),
    };
    let order = DeformOrder::Auto.on_type(info.device_type).name();
    println!("cell records (auto):               {records}");
    println!("deform order (auto):               {order}");
    Ok(())
}
