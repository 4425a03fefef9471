//! The upload of every instance's cell records by each encode, recorded into the encoder.
//!
//! `queue.write_buffer` lands before the whole next submission, so two set-pose-and-encode
//! pairs recorded for one submission would both see the last pose. Each encode instead writes
//! the poses into a mapped staging buffer and records a copy from it into the cell records,
//! ahead of its dispatches: the copy is part of the command buffer, so any number of encodes of
//! one deformer may share a command buffer or a submission, each deforming with its own poses.
//!
//! A staging buffer is unmapped for its copy, and mapped again once the submission holding it
//! is done (`map_buffer_on_submit`), which wgpu reports on the next `queue.submit` or
//! `device.poll` after the GPU finishes; then the next encode reuses it. An encode that finds
//! none mapped makes one more, so there are as many as encodes in flight at once (2 or 3 in a
//! frame loop, one per encode in a command buffer holding several); they are kept for reuse.
//! An encoder dropped without being submitted keeps its staging buffer unmapped until the
//! deformer is dropped.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A staging buffer and whether it is mapped (free for the next encode).
#[derive(Debug)]
struct Staging {
    buffer: wgpu::Buffer,
    mapped: Arc<AtomicBool>,
}

/// The staging buffers of one deformer's pose uploads.
#[derive(Debug)]
pub(crate) struct PoseUploads {
    staging: Vec<Staging>,
    bytes: u64,
}

impl PoseUploads {
    /// `count` staging buffers of `bytes` bytes (a multiple of 4), mapped.
    pub(crate) fn new(device: &wgpu::Device, bytes: u64, count: u32) -> PoseUploads {
        let mut uploads = PoseUploads { staging: Vec::with_capacity(count as usize), bytes };
        for _ in 0..count {
            uploads.add(device);
        }
        uploads
    }

    /// How many staging buffers there are.
    pub(crate) fn len(&self) -> usize {
        self.staging.len()
    }

    fn add(&mut self, device: &wgpu::Device) -> usize {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sweepffd pose upload"),
            size: self.bytes,
            usage: wgpu::BufferUsages::MAP_WRITE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: true,
        });
        self.staging.push(Staging { buffer, mapped: Arc::new(AtomicBool::new(true)) });
        self.staging.len() - 1
    }

    /// The index of a mapped staging buffer: a free one, else one made now.
    fn free(&mut self, device: &wgpu::Device) -> usize {
        let mapped = |uploads: &PoseUploads| uploads.staging.iter().position(|s| s.mapped.load(Ordering::Acquire));
        if let Some(index) = mapped(self) {
            return index;
        }
        // Collect the mappings of finished submissions, without waiting.
        let _ = device.poll(wgpu::PollType::Poll);
        mapped(self).unwrap_or_else(|| self.add(device))
    }

    /// Records into `encoder` the upload of `records` (`bytes` long) into `target` at offset 0.
    pub(crate) fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        records: &[u8],
        target: &wgpu::Buffer,
    ) {
        debug_assert_eq!(records.len() as u64, self.bytes);
        let index = self.free(device);
        let staging = &self.staging[index];
        let written = match staging.buffer.slice(..).get_mapped_range_mut() {
            Ok(mut view) => {
                view.copy_from_slice(records);
                true
            }
            Err(_) => false,
        };
        if !written {
            // Not reachable while the flags follow the mappings. Should it be, the buffer is
            // dropped and this one upload falls back to the queue (right for one encode per
            // submission).
            self.staging.swap_remove(index);
            queue.write_buffer(target, 0, records);
            return;
        }
        staging.mapped.store(false, Ordering::Release);
        staging.buffer.unmap();
        encoder.copy_buffer_to_buffer(&staging.buffer, 0, target, 0, self.bytes);
        let mapped = Arc::clone(&staging.mapped);
        encoder.map_buffer_on_submit(&staging.buffer, wgpu::MapMode::Write, .., move |result| {
            mapped.store(result.is_ok(), Ordering::Release);
        });
    }
}
