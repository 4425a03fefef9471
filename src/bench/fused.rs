//! The fused deform + Jacobian normals kernel in the GPU bench: its time against a copy
//! kernel moving as many bytes (`shaders/copy_wide.wgsl`) and against the deform and triangle
//! normals passes it replaces, and the angle between its normals and the triangle normals, on
//! the bench's scene.

use super::GpuTimer;
use super::creation::timed_deformer;
use super::passes::{Dispatches, chunk_params, encode, time};
use crate::coeffs::{BAND_FLAG, UNOWNED};
use crate::gpu::buffers::window;
use crate::gpu::{DeformerDescriptor, GpuContext, GpuDeformer, GpuError, dispatch_grid, kernels};
use crate::normals::jacobian_reach;
use crate::sweep::Sweep;

/// Bytes of a normal coordinates record.
pub(super) const RECORD_STRIDE: u64 = 16;

/// The fused deformer of the bench's scene and its memory-ceiling baseline.
pub(super) struct FusedComparison {
    deformer: GpuDeformer,
    wide_copy: Dispatches,
    /// The 99th percentile of the angle between the fused deformer's normals and the triangle
    /// normals of the same positions, over the Jacobian reach (the vertices the kernel writes,
    /// and those [`crate::deform::jacobian_normal_vertices`] leaves to the normals pass),
    /// degrees.
    pub(super) angle_p99_deg: f64,
    /// Milliseconds to create the deformer: the whole and the host's share.
    pub(super) creation: (f64, f64),
}

impl FusedComparison {
    /// A deformer of `descriptor` (that of `plain`, without falloff bands) with Jacobian
    /// normals; both posed by `posed` once to compare their normals.
    pub(super) fn new(
        context: &GpuContext,
        descriptor: DeformerDescriptor,
        plain: &mut GpuDeformer,
        posed: &[Sweep],
    ) -> Result<FusedComparison, GpuError> {
        let device = &context.device;
        let triangles = descriptor.triangles.unwrap_or(&[]);
        let (mut deformer, creation_ms, creation_host_ms) =
            timed_deformer(context, &descriptor.with_jacobian_normals())?;
        deformer.deform(posed)?;
        plain.deform(posed)?;
        let angle_p99_deg = normals_angle_p99_deg(&deformer, plain, triangles)?;

        let n = deformer.vertex_count() as u64;
        let scratch = |label, stride: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: n * stride,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        let records = scratch("sweepffd bench records", RECORD_STRIDE);
        let (out_positions, out_normals) =
            (scratch("sweepffd bench positions", 12), scratch("sweepffd bench normals", 12));
        let kernel = kernels::copy_wide(device);
        let limits = *deformer.limits();
        let dispatches = deformer
            .binding_chunks()
            .map(|(range, bindings)| {
                let group = kernel.bind_group(
                    device,
                    "sweepffd wide copy baseline",
                    &[
                        chunk_params(device, range).as_entire_binding(),
                        bindings.as_entire_binding(),
                        window(&records, range, RECORD_STRIDE),
                        window(&out_positions, range, 12),
                        window(&out_normals, range, 12),
                    ],
                );
                (group, dispatch_grid(range.len() as u32, &limits))
            })
            .collect();
        Ok(FusedComparison {
            deformer,
            wide_copy: (kernel, dispatches),
            angle_p99_deg,
            creation: (creation_ms, creation_host_ms),
        })
    }

    /// Seconds of the fused deform pass (positions and Jacobian normals).
    pub(super) fn time_fused(&mut self, context: &GpuContext, timer: Option<&GpuTimer>) -> Result<f64, GpuError> {
        time(context, timer, |encoder, stamps| {
            self.deformer.encode_deform_pass(encoder, stamps.opening());
            self.deformer.encode_normals_pass(encoder, stamps.closing());
        })
    }

    /// Seconds of the copy kernel moving the fused kernel's bytes.
    pub(super) fn time_wide_copy(&self, context: &GpuContext, timer: Option<&GpuTimer>) -> Result<f64, GpuError> {
        time(context, timer, |encoder, stamps| encode(encoder, &self.wide_copy, stamps))
    }
}

/// The 99th percentile of the angle between `fused`'s normals and `plain`'s over the vertices
/// of the Jacobian reach, degrees.
fn normals_angle_p99_deg(fused: &GpuDeformer, plain: &GpuDeformer, triangles: &[u32]) -> Result<f64, GpuError> {
    let bindings = fused.read_bindings()?;
    // One sweep moves every bound vertex of the bench's rig, without bands.
    let influence: Vec<u32> = bindings.iter().map(|b| if b.cell < BAND_FLAG { 0 } else { UNOWNED }).collect();
    let reach = jacobian_reach(triangles, &influence);
    let (a, b) = (fused.read_normals()?, plain.read_normals()?);
    let (Some(a), Some(b)) = (a, b) else { return Ok(0.0) };
    let mut degrees: Vec<f64> = (0..bindings.len())
        .filter(|&i| reach[i])
        .map(|i| {
            let x = glam::Vec3::from_slice(&a[3 * i..3 * i + 3]).as_dvec3();
            let y = glam::Vec3::from_slice(&b[3 * i..3 * i + 3]).as_dvec3();
            x.cross(y).length().atan2(x.dot(y)).to_degrees()
        })
        .collect();
    degrees.sort_by(f64::total_cmp);
    Ok(degrees.get(((degrees.len().max(1) - 1) as f64 * 0.99).round() as usize).copied().unwrap_or(0.0))
}
