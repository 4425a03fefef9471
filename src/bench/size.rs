//! The sizes and run counts a bench can honour. The synthetic tube has 256 vertices per ring,
//! at least three rings (its falloff comparison splits it at a middle ring), and a center
//! vertex on each cap: 256·k + 2 vertices for k ≥ 3, up to the backend's limit
//! ([`gpu_vertex_limit`] on a GPU, [`MAX_BENCH_VERTICES`] on the CPU). A size between two tubes
//! measures the largest tube below it, and the caller says so.

use thiserror::Error;

use crate::limits::{MAX_BENCH_RUNS, MAX_BENCH_VERTICES};
use crate::synthetic::Tube;

/// The fewest vertices of a bench tube: three rings of 256 (a middle ring to split the tube
/// at) and the two cap centers.
pub const MIN_BENCH_VERTICES: usize = 3 * 256 + 2;

/// A bench size or run count that cannot be honoured; each message starts with the field at
/// fault (`vertices`, `runs`).
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum BenchSizeError {
    /// Fewer vertices than the smallest tube.
    #[error(
        "vertices {0} is below the smallest synthetic tube, {MIN_BENCH_VERTICES} vertices (3 rings of 256 and \
         2 cap centers)"
    )]
    TooFewVertices(usize),
    /// More vertices than the backend can measure.
    #[error("vertices {vertices} is over the limit of {max} vertices on this backend")]
    TooManyVertices { vertices: usize, max: usize },
    /// No timed run.
    #[error("runs must be at least 1, found 0")]
    NoRuns,
    /// More runs than [`MAX_BENCH_RUNS`].
    #[error("runs {0} is over the limit of {MAX_BENCH_RUNS} runs")]
    TooManyRuns(usize),
}

/// The most vertices the GPU bench measures on a device with `limits`: the widest per-vertex
/// buffer it makes (16 bytes a vertex: the normal coordinates of the fused kernel's baseline)
/// must fit the device's largest buffer, and no more than [`MAX_BENCH_VERTICES`].
pub fn gpu_vertex_limit(limits: &wgpu::Limits) -> usize {
    let widest = 16;
    usize::try_from(limits.max_buffer_size / widest).unwrap_or(usize::MAX).min(MAX_BENCH_VERTICES)
}

/// The vertex count of the largest synthetic tube with at most `requested` vertices, on a
/// backend that measures at most `max`.
///
/// # Errors
///
/// A request below [`MIN_BENCH_VERTICES`] or over `max`.
pub fn tube_vertex_count(requested: usize, max: usize) -> Result<usize, BenchSizeError> {
    if requested < MIN_BENCH_VERTICES {
        return Err(BenchSizeError::TooFewVertices(requested));
    }
    if requested > max {
        return Err(BenchSizeError::TooManyVertices { vertices: requested, max });
    }
    Ok(Tube::with_vertex_count(requested, 4.0, 0.5).vertex_count())
}

/// Checks a count of timed runs per figure: 1 to [`MAX_BENCH_RUNS`].
///
/// # Errors
///
/// Zero runs, or more than [`MAX_BENCH_RUNS`].
pub fn check_runs(runs: usize) -> Result<(), BenchSizeError> {
    match runs {
        0 => Err(BenchSizeError::NoRuns),
        _ if runs > MAX_BENCH_RUNS => Err(BenchSizeError::TooManyRuns(runs)),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_round_down_to_a_whole_tube() {
        let max = MAX_BENCH_VERTICES;
        assert_eq!(tube_vertex_count(770, max), Ok(770));
        assert_eq!(tube_vertex_count(1025, max), Ok(770));
        assert_eq!(tube_vertex_count(1026, max), Ok(1026));
        assert_eq!(tube_vertex_count(1_000_000, max), Ok(999_938));
        assert_eq!(tube_vertex_count(100_000_000, max), Ok(99_999_746));
        assert_eq!(tube_vertex_count(MAX_BENCH_VERTICES, max), Ok(1_073_741_570));
    }

    #[test]
    fn the_smallest_tube_makes_a_bench_scene() {
        let n = tube_vertex_count(MIN_BENCH_VERTICES, MAX_BENCH_VERTICES).unwrap();
        assert_eq!(crate::bench::BenchScene::tube(n).vertex_count(), MIN_BENCH_VERTICES);
    }

    #[test]
    fn sizes_outside_the_tubes_are_refused() {
        let max = MAX_BENCH_VERTICES;
        assert_eq!(tube_vertex_count(0, max), Err(BenchSizeError::TooFewVertices(0)));
        assert_eq!(tube_vertex_count(769, max), Err(BenchSizeError::TooFewVertices(769)));
        assert_eq!(
            tube_vertex_count(514, max).unwrap_err().to_string(),
            "vertices 514 is below the smallest synthetic tube, 770 vertices (3 rings of 256 and 2 cap centers)"
        );
        assert_eq!(
            tube_vertex_count(MAX_BENCH_VERTICES + 1, max).unwrap_err().to_string(),
            "vertices 1073741825 is over the limit of 1073741824 vertices on this backend"
        );
    }

    #[test]
    fn the_gpu_limit_comes_from_the_device_largest_buffer() {
        let limits = |max_buffer_size| wgpu::Limits { max_buffer_size, ..wgpu::Limits::default() };
        // lavapipe's 2 GiB buffers hold 134M vertices; an H200's hold the host bound.
        assert_eq!(gpu_vertex_limit(&limits(2_147_483_647)), 134_217_727);
        assert_eq!(gpu_vertex_limit(&limits(1 << 40)), MAX_BENCH_VERTICES);
        assert_eq!(gpu_vertex_limit(&limits(256 << 20)), 16 << 20);
        let error = tube_vertex_count(20 << 20, gpu_vertex_limit(&limits(256 << 20))).unwrap_err();
        assert_eq!(error, BenchSizeError::TooManyVertices { vertices: 20 << 20, max: 16 << 20 });
    }

    #[test]
    fn run_counts_from_one_to_the_limit() {
        assert_eq!(check_runs(1), Ok(()));
        assert_eq!(check_runs(MAX_BENCH_RUNS), Ok(()));
        assert_eq!(check_runs(0).unwrap_err().to_string(), "runs must be at least 1, found 0");
        assert_eq!(check_runs(10_001).unwrap_err().to_string(), "runs 10001 is over the limit of 10000 runs");
    }
}
