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

/// The most vertices `bench` measures on a synthetic tube on any backend (the host builds the
/// tube, about 100 bytes a vertex); on a GPU the device's largest buffer bounds it further
/// (`bench::gpu_vertex_limit`, feature `bench`).
pub const MAX_BENCH_VERTICES: usize = 1 << 30;

/// The most timed runs per `bench` figure.
pub const MAX_BENCH_RUNS: usize = 10_000;

/// The largest input file read (4 GiB).
pub const MAX_INPUT_BYTES: u64 = 1 << 32;

/// Reads the whole of the regular file `path` (symbolic links followed), refusing any other
/// kind of file (a FIFO would block, a device would not end) and files over
/// [`MAX_INPUT_BYTES`]. The buffer is reserved once, fallibly, so a file too large for the
/// memory left is an error, not an abort.
///
/// # Errors
///
/// The I/O error, or `InvalidInput` for a file that is not regular or is too large, or
/// `OutOfMemory` when the buffer cannot be reserved. The error does not name `path`; callers
/// add it.
pub fn read_input(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
    use std::io::{Error, ErrorKind, Read};
    let mut file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!("{} bytes, over the limit of {MAX_INPUT_BYTES} bytes for an input file", meta.len()),
        ));
    }
    let mut bytes = Vec::new();
    // One byte more than the length seen, so that a file growing while read is noticed.
    bytes.try_reserve_exact(meta.len() as usize + 1).map_err(|_| {
        Error::new(ErrorKind::OutOfMemory, format!("{} bytes do not fit in the memory left", meta.len()))
    })?;
    file.by_ref().take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(Error::new(ErrorKind::InvalidInput, "the file grew past the input limit while read"));
    }
    Ok(bytes)
}

/// [`read_input`] as UTF-8 text.
///
/// # Errors
///
/// As [`read_input`], or `InvalidData` for text that is not UTF-8.
pub fn read_input_text(path: &std::path::Path) -> std::io::Result<String> {
    String::from_utf8(read_input(path)?)
        .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidData, "stream did not contain valid UTF-8"))
}

/// The most entries of a PLY element other than `vertex` and `face` (such elements are read
/// and kept so that a faithful write copies them).
pub const MAX_PLY_ENTRIES: usize = MAX_FACES;

/// The most node instances a glTF scene expands to: each node counted once per path from a
/// root to it, when a mesh lies at or below it (2²² = 4,194,304). Bounds the time of the
/// expansion, which multiplies one matrix per node instance, in a graph whose nodes share
/// children.
pub const MAX_GLTF_NODE_INSTANCES: usize = 1 << 22;

/// How many times the vertices (and triangles) a glTF file stores its scene may give, past
/// [`MAX_GLTF_UNSTORED`]: instancing a mesh by many nodes, or an accessor whose count is not
/// backed by bytes (no buffer view, a few sparse values), multiplies a small file into a large
/// mesh (a 20 KB node graph into 33 million vertices, a 600-byte file into 33 million zero
/// positions); the cost of a file follows what it holds.
pub const MAX_GLTF_EXPANSION: usize = 16;

/// The vertices (and triangles) a glTF scene may give beyond what its file stores, whatever
/// [`MAX_GLTF_EXPANSION`] allows (2²⁰ = 1,048,576): a small file instancing a part many times
/// stays readable up to a mesh the rest of the engine handles in well under a gigabyte.
pub const MAX_GLTF_UNSTORED: usize = 1 << 20;

/// How many times its mesh's size (bounding-box diagonal) a key radius may be when the rig is
/// bound to the mesh. A vertex far inside a radius r is placed by r + d, and f64 keeps
/// r + d to about r · 10⁻¹⁶: at 10⁶ times the mesh that is 10⁻¹⁰ of the mesh, while radii of
/// 10¹⁵ on a 4-unit tube moved its vertices by 0.3 under the rest pose.
pub const MAX_RADIUS_PER_MESH_SIZE: f64 = 1e6;

/// The most radii of a whole rig, summed over its sweeps' keys (2²⁰ = 1,048,576). A sweep's
/// radius function keeps one 128-byte bicubic patch per radius (§3), and an edit rebuilds it,
/// so this keeps a rig's surfaces within about 128 MB and an edit's work bounded.
pub const MAX_RADII_PER_RIG: usize = 1 << 20;

/// The largest magnitude of a rig or pose coordinate or radius, in mesh units (10¹⁵). Keys
/// within it give sweep surfaces, volumes (Eq. 1) and f32 coefficients that are all finite;
/// a pose or an edit that goes beyond it is an error naming the sweep and key.
pub const MAX_RIG_COORDINATE: f64 = 1e15;

/// The smallest gap between consecutive knots u_i (10⁻⁶ of the knots' span [0, 1]), whether
/// given or from the chord length: closer knots would not survive the f32 parameters of the
/// GPU (its resolution near 1 is 6·10⁻⁸) and make the spline's second derivatives explode.
pub const MIN_KNOT_SPACING: f64 = 1e-6;
