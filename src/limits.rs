//! Resource limits: the largest inputs sweepffd accepts.
//!
//! Each limit is checked before anything is allocated for the input it bounds, and the error
//! names the limit. Counts read from a file header never size an allocation on their own: a
//! reader reserves at most what the rest of the file can hold. The README's "Limits" table
//! lists these values; keep the two in step.

/// The most vertices of a mesh, after glTF instancing and subdivision (2²⁵ = 33,554,432).
///
/// The GPU's binding records keep two flag bits above the vertex index, and a frame holds
/// about 100 bytes per vertex on the host, so this keeps the largest mesh within 4 GB.
pub const MAX_VERTICES: usize = 1 << 25;

/// The most polygon faces of a mesh (2²⁶ = 67,108,864), and the most triangles after fans.
pub const MAX_FACES: usize = 1 << 26;

/// The most corners of one polygon face.
pub const MAX_FACE_CORNERS: usize = 1 << 16;

/// The most sweeps of a rig.
pub const MAX_SWEEPS: usize = 256;

/// The most keys of one sweep.
pub const MAX_KEYS_PER_SWEEP: usize = 1024;

/// The most radii of one key (the cross-section samples, M in §3).
pub const MAX_RADII_PER_KEY: usize = 4096;

/// The most edits of one edits file.
pub const MAX_EDITS: usize = 10_000;

/// The deepest glTF node hierarchy (root at depth 0).
pub const MAX_GLTF_NODE_DEPTH: usize = 1024;

/// The most mesh instances of a glTF scene (a mesh drawn by several nodes counts once each).
pub const MAX_GLTF_INSTANCES: usize = 1 << 16;

/// The most vertices `bench` measures on a synthetic tube.
pub const MAX_BENCH_VERTICES: usize = 1 << 25;

/// The most timed runs per `bench` figure.
pub const MAX_BENCH_RUNS: usize = 10_000;
