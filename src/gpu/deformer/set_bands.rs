//! Replacing a deformer's falloff bands ([`GpuDeformer::set_bands`]) without binding its vertices
//! again: when a sweep's falloff width W changes, only the band vertices' flags, their records and
//! their second influences change; the primary bindings and the positions stay on the GPU.
//!
//! Data flow: rig (new W) → bind (falloff weights, on the CPU) → **band flags and records** (on
//! the GPU) → deform → normals → output.

use std::ops::Range;

use super::super::bands::{BandPlan, BandSource, BandStage};
use super::super::binder::Binder;
use super::super::buffers::params_buffer;
use super::super::chunks::dispatch_grid;
use super::super::kernels::Kernel;
use super::super::readback::wait;
use super::super::{GpuError, InputError};
use super::{DeformChunk, GpuDeformer, check_weights};
use crate::bind::falloff::BandWeight;
use crate::coeffs::{BAND_FLAG, BandFlag, BandRecord, DispatchParams, KEEPS_REST, UNOWNED};
use crate::sweep::Sweep;
use wgpu::util::DeviceExt;

/// A vertex in the falloff bands, as replacing the bands needs to know it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct BandMember {
    /// The vertex, global.
    pub vertex: u32,
    /// Whether the band kernel leaves it at its rest position (w = 0 against the rest position,
    /// tested on the f32 weight as the kernel tests it).
    pub keeps_rest: bool,
}

impl BandMember {
    /// The member of a falloff weight.
    pub(super) fn of_weight(weight: &BandWeight) -> BandMember {
        BandMember { vertex: weight.vertex, keeps_rest: weight.neighbour == UNOWNED && weight.weight as f32 == 0.0 }
    }

    /// The member of a band record (vertex global).
    pub(super) fn of_record(record: &BandRecord) -> BandMember {
        BandMember { vertex: record.vertex, keeps_rest: record.cell == UNOWNED && record.weight == 0.0 }
    }
}

/// What [`GpuDeformer::set_bands`] keeps between calls: the rest sweeps and the bind kernel (made
/// on first use when the deformer was given precomputed bindings), the band-flags kernel (made on
/// first use), the current band members, and which vertices are bound (one bit each).
#[derive(Debug)]
pub(super) struct Rebanding {
    rest: Vec<Sweep>,
    binder: Option<Binder>,
    flags: Option<std::sync::Arc<Kernel>>,
    members: Vec<BandMember>,
    bound: Vec<u64>,
}

impl Rebanding {
    /// The state of a deformer built on `rest` with these band `members`; `bound[v]` tells whether
    /// vertex v is bound.
    pub(super) fn new(rest: &[Sweep], binder: Option<Binder>, members: Vec<BandMember>, bound: &[bool]) -> Rebanding {
        let mut bits = vec![0u64; bound.len().div_ceil(64)];
        for (v, _) in bound.iter().enumerate().filter(|(_, b)| **b) {
            bits[v / 64] |= 1 << (v % 64);
        }
        Rebanding { rest: rest.to_vec(), binder, flags: None, members, bound: bits }
    }

    fn is_bound(&self, v: usize) -> bool {
        self.bound.get(v / 64).is_some_and(|word| word >> (v % 64) & 1 == 1)
    }
}

/// The membership changes from the bands `old` to the bands `new` (both sorted by vertex), as
/// [`BandFlag`]s with global vertices, sorted: a vertex only in `old` leaves (flag clear); one only
/// in `new` enters ([`BAND_FLAG`]); one that keeps its rest position in `new` but did not in `old`
/// (or was not in `old`) also gets [`KEEPS_REST`] and its f32 rest position from `rest`, since the
/// deform and band kernels may have moved it. A vertex in both that needs no rest position is
/// unchanged. Each vertex appears at most once, so the kernel's writes never race.
pub(super) fn flag_changes(old: &[BandMember], new: &[BandWeight], rest: &[[f32; 3]]) -> Vec<BandFlag> {
    let enter = |member: BandMember| {
        let mut flag = BandFlag { vertex: member.vertex | BAND_FLAG, ..Default::default() };
        if member.keeps_rest {
            let [x, y, z] = rest[member.vertex as usize];
            flag = BandFlag { vertex: flag.vertex | KEEPS_REST, x, y, z };
        }
        flag
    };
    let mut changes = Vec::new();
    let (mut i, mut j) = (0, 0);
    while i < old.len() || j < new.len() {
        let next_old = old.get(i).map_or(u32::MAX, |m| m.vertex);
        let next_new = new.get(j).map_or(u32::MAX, |w| w.vertex);
        if next_old < next_new {
            changes.push(BandFlag { vertex: next_old, ..Default::default() });
            i += 1;
        } else if next_new < next_old {
            changes.push(enter(BandMember::of_weight(&new[j])));
            j += 1;
        } else {
            let member = BandMember::of_weight(&new[j]);
            if member.keeps_rest && !old[i].keeps_rest {
                changes.push(enter(member));
            }
            i += 1;
            j += 1;
        }
    }
    changes
}

/// The changes of the vertices in `range` (a slice of the sorted `changes`), vertices made relative
/// to the range's first.
fn changes_in(changes: &[BandFlag], range: &Range<u32>) -> Vec<BandFlag> {
    let vertex = |f: &BandFlag| f.vertex & !(BAND_FLAG | KEEPS_REST);
    let first = changes.partition_point(|f| vertex(f) < range.start);
    let last = changes.partition_point(|f| vertex(f) < range.end);
    changes[first..last]
        .iter()
        .map(|f| {
            debug_assert!(vertex(f) - range.start < KEEPS_REST, "a dispatch holds fewer than 2³⁰ vertices");
            BandFlag { vertex: f.vertex - range.start, ..*f }
        })
        .collect()
}

impl GpuDeformer {
    /// Replaces the falloff bands by `weights` ([`crate::rig::Rig::band_weights`] after a change of
    /// falloff widths; empty: hard boundaries), without binding the vertices again or uploading
    /// the positions: on the GPU, the band-flags kernel sets [`BAND_FLAG`] on the bindings of the
    /// vertices that enter the bands and clears it on those that leave them (the deform kernel
    /// moves them again), and writes the rest position of those that now keep it; the band
    /// records are rebuilt and the second influences bound by the bind kernel, as
    /// [`new`](GpuDeformer::new) does. `rest` are the rest positions the deformer was built
    /// with, f32 (only the band vertices' are read and uploaded).
    ///
    /// The result equals a deformer built with `weights` from the next
    /// [`encode`](GpuDeformer::encode) on; nothing changes per frame. Blocks until the GPU is
    /// done. Fails, changing nothing, on weights that are not sorted, owned and in range, or on
    /// `rest` of another length; wgpu errors are returned.
    pub fn set_bands(&mut self, rest: &[[f32; 3]], weights: &[BandWeight]) -> Result<(), GpuError> {
        if rest.len() != self.vertex_count as usize {
            return Err(InputError::RestPositionCount { positions: rest.len(), vertices: self.vertex_count }.into());
        }
        if self.jacobian_normals {
            return Err(InputError::BandsWithJacobianNormals.into());
        }
        check_weights(weights, self.coefficients.sweeps.len(), |v| self.rebanding.is_bound(v))?;
        if let Some(w) = weights.iter().find(|w| !rest[w.vertex as usize].iter().all(|c| c.is_finite())) {
            return Err(InputError::PositionNotFinite { vertex: w.vertex as usize }.into());
        }
        let device = self.context.device.clone();
        let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sweepffd set bands") });
        let changes = flag_changes(&self.rebanding.members, weights, rest);
        self.encode_flag_changes(&changes, &mut encoder);
        if !changes.is_empty() {
            // Band vertices are in no cell group: the groups follow the new flags.
            for chunk in &self.chunks {
                chunk.encode_sort(&mut encoder);
            }
        }
        if !weights.is_empty() && self.rebanding.binder.is_none() {
            // The binder takes the sweeps' layout (SweepInfo), which does not change with the pose,
            // from the coefficients, and the rest cells from their own buffer.
            let rest = &self.rebanding.rest;
            self.rebanding.binder = Some(Binder::new(&self.context, rest, &self.coefficients, &self.rest_cells));
        }
        if !weights.is_empty() || self.bands.is_some() {
            let stage = self.bands.get_or_insert_with(|| BandStage::new(&self.context, self.variant, &self.rest_cells));
            let plan = BandPlan { cells: &self.cells, targets: &self.targets, limits: &self.limits };
            let windows: Vec<(Range<u32>, &wgpu::Buffer)> =
                self.chunks.iter().map(|chunk| (chunk.range.clone(), &chunk.bindings)).collect();
            let source = BandSource::Bind { weights, positions: rest };
            stage.set_records(&self.context, plan, &windows, source, self.rebanding.binder.as_ref(), &mut encoder);
        }
        self.context.queue.submit([encoder.finish()]);
        let (validation, out_of_memory) = (validation.pop(), out_of_memory.pop());
        let validation_error = pollster::block_on(validation);
        let memory_error = pollster::block_on(out_of_memory);
        if let Some(error) = validation_error.or(memory_error) {
            return Err(error.into());
        }
        wait(&self.context)?;
        self.rebanding.members = weights.iter().map(BandMember::of_weight).collect();
        Ok(())
    }

    /// Records the band-flags kernel over each deform chunk's share of `changes`.
    fn encode_flag_changes(&mut self, changes: &[BandFlag], encoder: &mut wgpu::CommandEncoder) {
        if changes.is_empty() {
            return;
        }
        let device = &self.context.device;
        let kernels = self.context.kernels();
        let kernel = self.rebanding.flags.get_or_insert_with(|| kernels.band_flags(device));
        let targets = &self.targets;
        // The flags are set once per instance and position buffer (the same bits each time), so
        // that every instance's rest positions are written to both buffers.
        let views: Vec<(usize, u32)> =
            (0..targets.buffers.len()).flat_map(|p| (0..targets.instances).map(move |i| (p, i))).collect();
        let dispatches: Vec<(wgpu::BindGroup, (u32, u32))> = self
            .chunks
            .iter()
            .flat_map(|chunk: &DeformChunk| {
                let flags = changes_in(changes, &chunk.range);
                if flags.is_empty() {
                    return Vec::new();
                }
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sweepffd band flags"),
                    contents: bytemuck::cast_slice(&flags),
                    usage: wgpu::BufferUsages::STORAGE,
                });
                let count = flags.len() as u32;
                let params = params_buffer(device, DispatchParams { vertex_count: count, ..Default::default() });
                let grid = dispatch_grid(count, &self.limits);
                views
                    .iter()
                    .map(|&(parity, instance)| {
                        let group = kernel.bind_group(
                            device,
                            "sweepffd band flags",
                            &[
                                params.as_entire_binding(),
                                buffer.as_entire_binding(),
                                chunk.bindings.as_entire_binding(),
                                targets.window(parity, &chunk.range, &(instance..instance + 1)),
                            ],
                        );
                        (group, grid)
                    })
                    .collect()
            })
            .collect();
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sweepffd band flags"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&kernel.pipeline);
        for (group, (x, y)) in &dispatches {
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(*x, *y, 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn weight(vertex: u32, weight: f64, neighbour: u32) -> BandWeight {
        BandWeight { vertex, weight, neighbour }
    }

    fn member(vertex: u32, keeps_rest: bool) -> BandMember {
        BandMember { vertex, keeps_rest }
    }

    fn rest() -> Vec<[f32; 3]> {
        (0..8).map(|i| [i as f32, 0.5, -1.0]).collect()
    }

    #[test]
    fn leaving_entering_and_staying_vertices() {
        let old = [member(1, false), member(3, false), member(5, true)];
        let new = [weight(3, 0.4, 0), weight(5, 0.0, UNOWNED), weight(6, 0.7, UNOWNED)];
        let changes = flag_changes(&old, &new, &rest());
        // 1 leaves, 3 and 5 stay as they were, 6 enters moving (w > 0).
        assert_eq!(
            changes,
            vec![
                BandFlag { vertex: 1, ..Default::default() },
                BandFlag { vertex: 6 | BAND_FLAG, ..Default::default() }
            ]
        );
    }

    #[test]
    fn a_vertex_that_now_keeps_its_rest_position_gets_it_back() {
        // 2 enters at w = 0 against the rest; 4 stays but now fades to the rest at w = 0 (it was
        // fading into sweep 1); 7 is at w = 0 against sweep 1, which moves it.
        let old = [member(4, false)];
        let new = [weight(2, 0.0, UNOWNED), weight(4, 0.0, UNOWNED), weight(7, 0.0, 1)];
        let changes = flag_changes(&old, &new, &rest());
        let back = |v: u32| BandFlag { vertex: v | BAND_FLAG | KEEPS_REST, x: v as f32, y: 0.5, z: -1.0 };
        assert_eq!(changes, vec![back(2), back(4), BandFlag { vertex: 7 | BAND_FLAG, ..Default::default() }]);
    }

    #[test]
    fn a_weight_that_rounds_to_zero_in_f32_keeps_the_rest_position_as_the_kernel_does() {
        assert!(BandMember::of_weight(&weight(0, 1e-50, UNOWNED)).keeps_rest);
        assert!(!BandMember::of_weight(&weight(0, 1e-30, UNOWNED)).keeps_rest);
    }

    #[test]
    fn same_bands_change_nothing_and_no_bands_clear_every_flag() {
        let new = [weight(2, 0.0, UNOWNED), weight(4, 0.5, 0)];
        let old: Vec<BandMember> = new.iter().map(BandMember::of_weight).collect();
        assert!(flag_changes(&old, &new, &rest()).is_empty());
        let cleared = flag_changes(&old, &[], &rest());
        assert_eq!(cleared.iter().map(|f| f.vertex).collect::<Vec<_>>(), vec![2, 4]);
    }

    #[test]
    fn changes_are_split_by_dispatch_with_relative_vertices() {
        let changes = [
            BandFlag { vertex: 3 | BAND_FLAG, ..Default::default() },
            BandFlag { vertex: 130 | BAND_FLAG | KEEPS_REST, x: 1.0, y: 2.0, z: 3.0 },
            BandFlag { vertex: 200, ..Default::default() },
        ];
        assert_eq!(changes_in(&changes, &(0..128)), vec![changes[0]]);
        assert_eq!(
            changes_in(&changes, &(128..256)),
            vec![
                BandFlag { vertex: 2 | BAND_FLAG | KEEPS_REST, x: 1.0, y: 2.0, z: 3.0 },
                BandFlag { vertex: 72, ..Default::default() },
            ]
        );
        assert!(changes_in(&changes, &(256..300)).is_empty());
    }

    #[test]
    fn bound_vertices_are_one_bit_each() {
        let bound: Vec<bool> = (0..130).map(|v| v % 3 == 0).collect();
        let rebanding = Rebanding::new(&[], None, Vec::new(), &bound);
        assert_eq!(rebanding.bound.len(), 3);
        assert!((0..130).all(|v| rebanding.is_bound(v) == (v % 3 == 0)));
        assert!(!rebanding.is_bound(130) && !rebanding.is_bound(10_000));
    }
}
