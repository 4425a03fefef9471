//! The bindings file written by `sweepffd bind` and read by `sweepffd deform --bindings`.
//!
//! Little-endian binary:
//!
//! | offset | size | content |
//! |---|---|---|
//! | 0 | 8 | magic `SFFDBIND` |
//! | 8 | 4 | format version, 2 (version 1 files, which have no bands, still load) |
//! | 12 | 4 | number of sweeps in the rig |
//! | 16 | 8 | number of vertices N |
//! | 24 | 8 | rig fingerprint (FNV-1a 64 of the rest rig's JSON) |
//! | 32 | 8 | mesh fingerprint (FNV-1a 64 of the vertex positions' f64 bits) |
//! | 40 | 40·N | per vertex: u32 sweep (0xFFFFFFFF: unowned), u32 zero, f64 t, θ, d, h |
//! | 40 + 40·N | 8 | number of falloff band vertices B (version 2) |
//! | 48 + 40·N | 48·B | per band vertex, by increasing vertex: u32 vertex, u32 second sweep (0xFFFFFFFF: the rest position), f64 weight w, and the second binding's f64 t, θ, d, h |
//!
//! The fingerprints let `deform` refuse bindings made for another rig or mesh. Every record
//! is range-checked on load ([`check`]: θ ∈ [0, 2π], t ∈ [0, 1], finite d and h, sweeps in
//! range, band weights in [0, 1), band vertices owned and strictly increasing), and against
//! the rig and mesh by [`BindingsFile::check_matches`] (|d|, |h| ≤ [`check::offset_bound`]),
//! so the CPU and the GPU deform the same positions or both refuse the file.

pub mod check;

use std::io::Write;
use std::path::{Path, PathBuf};

use glam::DVec3;
use thiserror::Error;

use crate::bind::{BandBinding, Binding, MeshBindings, UNOWNED, VertexBinding};
use crate::rig::Rig;

const MAGIC: &[u8; 8] = b"SFFDBIND";
const VERSION: u32 = 2;
const HEADER_BYTES: usize = 40;
const RECORD_BYTES: usize = 40;
const BAND_RECORD_BYTES: usize = 48;

/// Bindings of every vertex of a mesh to a rig, with fingerprints of both.
#[derive(Clone, Debug, PartialEq)]
pub struct BindingsFile {
    /// Number of sweeps of the rig the bindings were made for.
    pub sweep_count: u32,
    /// Fingerprint of that rig ([`rig_fingerprint`]).
    pub rig_fingerprint: u64,
    /// Fingerprint of the mesh positions ([`mesh_fingerprint`]).
    pub mesh_fingerprint: u64,
    /// One binding per vertex, in mesh order, and the falloff bands.
    pub bindings: MeshBindings,
}

/// Why a bindings file cannot be read or used.
#[derive(Debug, Error)]
pub enum BindingsFileError {
    #[error("cannot read {}: {source}", path.display())]
    Read { path: PathBuf, source: std::io::Error },
    #[error("cannot write {}: {source}", path.display())]
    Write { path: PathBuf, source: std::io::Error },
    #[error("{}: not a sweepffd bindings file ({reason})", path.display())]
    Malformed { path: PathBuf, reason: String },
    #[error("{}: the bindings were made for {made_for}", path.display())]
    Mismatch { path: PathBuf, made_for: MadeFor },
    /// A record of a well-formed file holds a value no binding can have.
    #[error("{}: {reason}", path.display())]
    OutOfRange { path: PathBuf, reason: String },
}

/// What a bindings file was made for, where that is not the rig and mesh at hand.
#[derive(Clone, Copy, Debug, Error, PartialEq, Eq)]
pub enum MadeFor {
    #[error("{file} vertices, the mesh has {mesh}")]
    VertexCount { file: usize, mesh: usize },
    #[error("another rig")]
    AnotherRig,
    #[error("another mesh with the same vertex count")]
    AnotherMesh,
}

/// FNV-1a 64 of the rest rig's canonical JSON.
pub fn rig_fingerprint(rig: &Rig) -> u64 {
    fnv1a(rig.to_document().to_json().as_bytes())
}

/// FNV-1a 64 of the little-endian bits of every coordinate.
pub fn mesh_fingerprint(positions: &[DVec3]) -> u64 {
    let bytes: Vec<u8> = positions.iter().flat_map(|p| p.to_array()).flat_map(f64::to_le_bytes).collect();
    fnv1a(&bytes)
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| (hash ^ b as u64).wrapping_mul(0x0100_0000_01b3))
}

impl BindingsFile {
    /// The file for `bindings` of `positions` to `rig`.
    pub fn new(rig: &Rig, positions: &[DVec3], bindings: MeshBindings) -> BindingsFile {
        BindingsFile {
            sweep_count: rig.sweeps().len() as u32,
            rig_fingerprint: rig_fingerprint(rig),
            mesh_fingerprint: mesh_fingerprint(positions),
            bindings,
        }
    }

    /// The file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let MeshBindings { vertices, bands } = &self.bindings;
        let mut bytes =
            Vec::with_capacity(HEADER_BYTES + RECORD_BYTES * vertices.len() + 8 + BAND_RECORD_BYTES * bands.len());
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&VERSION.to_le_bytes());
        bytes.extend_from_slice(&self.sweep_count.to_le_bytes());
        bytes.extend_from_slice(&(vertices.len() as u64).to_le_bytes());
        bytes.extend_from_slice(&self.rig_fingerprint.to_le_bytes());
        bytes.extend_from_slice(&self.mesh_fingerprint.to_le_bytes());
        let params_bytes = |bytes: &mut Vec<u8>, params: &VertexBinding| {
            for value in [params.t, params.theta, params.d, params.h] {
                bytes.extend_from_slice(&value.to_le_bytes());
            }
        };
        for Binding { sweep, params } in vertices {
            bytes.extend_from_slice(&sweep.to_le_bytes());
            bytes.extend_from_slice(&0u32.to_le_bytes());
            params_bytes(&mut bytes, params);
        }
        bytes.extend_from_slice(&(bands.len() as u64).to_le_bytes());
        for band in bands {
            bytes.extend_from_slice(&band.vertex.to_le_bytes());
            bytes.extend_from_slice(&band.second.sweep.to_le_bytes());
            bytes.extend_from_slice(&band.weight.to_le_bytes());
            params_bytes(&mut bytes, &band.second.params);
        }
        bytes
    }

    /// Parses a file's bytes; `path` is named in errors.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<BindingsFile, BindingsFileError> {
        let malformed = |reason: String| BindingsFileError::Malformed { path: path.to_path_buf(), reason };
        if bytes.len() < HEADER_BYTES || &bytes[..8] != MAGIC {
            return Err(malformed("missing the SFFDBIND header".to_string()));
        }
        let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
        let u64_at = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes"));
        let f64_at = |at: usize| f64::from_bits(u64_at(at));
        let params_at =
            |at: usize| VertexBinding { t: f64_at(at), theta: f64_at(at + 8), d: f64_at(at + 16), h: f64_at(at + 24) };
        let version = u32_at(8);
        if version != 1 && version != VERSION {
            return Err(malformed(format!("version {version} is neither 1 nor {VERSION}")));
        }
        let sweep_count = u32_at(12);
        let count = u64_at(16);
        let vertices_end = (count as u128) * RECORD_BYTES as u128 + HEADER_BYTES as u128;
        let band_count = if version == 1 {
            if bytes.len() as u128 != vertices_end {
                return Err(malformed(format!("{} bytes for {count} vertices, expected {vertices_end}", bytes.len())));
            }
            0
        } else {
            if (bytes.len() as u128) < vertices_end + 8 {
                return Err(malformed(format!("{} bytes for {count} vertices and a band count", bytes.len())));
            }
            let band_count = u64_at(vertices_end as usize);
            let expected = vertices_end + 8 + band_count as u128 * BAND_RECORD_BYTES as u128;
            if bytes.len() as u128 != expected {
                let found = bytes.len();
                return Err(malformed(format!(
                    "{found} bytes for {count} vertices and {band_count} band vertices, expected {expected}"
                )));
            }
            band_count
        };
        let out_of_range = |reason: String| BindingsFileError::OutOfRange { path: path.to_path_buf(), reason };
        // The sweep, then (for an owned record) its parameters, `prefix` before their reason.
        let binding = |sweep: u32, params: &VertexBinding, what: &str, prefix: &str| {
            check::sweep(sweep, sweep_count, what)?;
            if sweep == UNOWNED { Ok(()) } else { check::params(params).map_err(|reason| format!("{prefix}{reason}")) }
        };
        let mut vertices = Vec::with_capacity(count as usize);
        for i in 0..count as usize {
            let at = HEADER_BYTES + i * RECORD_BYTES;
            let (sweep, params) = (u32_at(at), params_at(at + 8));
            binding(sweep, &params, "sweep", "").map_err(|reason| out_of_range(format!("vertex {i}: {reason}")))?;
            vertices.push(Binding { sweep, params });
        }
        let mut bands: Vec<BandBinding> = Vec::with_capacity(band_count as usize);
        for i in 0..band_count as usize {
            let at = vertices_end as usize + 8 + i * BAND_RECORD_BYTES;
            let (vertex, sweep, weight, params) = (u32_at(at), u32_at(at + 4), f64_at(at + 8), params_at(at + 16));
            let band = check_band(&vertices, bands.last(), vertex, sweep, weight)
                .and_then(|()| binding(sweep, &params, "second sweep", "second binding: "));
            band.map_err(|reason| out_of_range(format!("band vertex {i} (vertex {vertex}): {reason}")))?;
            bands.push(BandBinding { vertex, weight, second: Binding { sweep, params } });
        }
        let bindings = MeshBindings { vertices, bands };
        Ok(BindingsFile { sweep_count, rig_fingerprint: u64_at(24), mesh_fingerprint: u64_at(32), bindings })
    }

    /// Reads a bindings file.
    pub fn load(path: &Path) -> Result<BindingsFile, BindingsFileError> {
        let bytes = crate::limits::read_input(path)
            .map_err(|source| BindingsFileError::Read { path: path.to_path_buf(), source })?;
        BindingsFile::from_bytes(&bytes, path)
    }

    /// Writes the file atomically (temporary file, then rename).
    pub fn save(&self, path: &Path) -> Result<(), BindingsFileError> {
        let bytes = self.to_bytes();
        crate::atomic_file::write_atomically(path, |out| out.write_all(&bytes))
            .map_err(|source| BindingsFileError::Write { path: path.to_path_buf(), source })
    }

    /// Checks that the bindings were made for `rig` and `positions`; `path` is named in errors.
    pub fn check_matches(&self, rig: &Rig, positions: &[DVec3], path: &Path) -> Result<(), BindingsFileError> {
        let mismatch = |made_for| Err(BindingsFileError::Mismatch { path: path.to_path_buf(), made_for });
        if self.bindings.vertices.len() != positions.len() {
            return mismatch(MadeFor::VertexCount { file: self.bindings.vertices.len(), mesh: positions.len() });
        }
        if self.sweep_count as usize != rig.sweeps().len() || self.rig_fingerprint != rig_fingerprint(rig) {
            return mismatch(MadeFor::AnotherRig);
        }
        if self.mesh_fingerprint != mesh_fingerprint(positions) {
            return mismatch(MadeFor::AnotherMesh);
        }
        self.check_offsets(check::offset_bound(rig.rest(), positions))
            .map_err(|reason| BindingsFileError::OutOfRange { path: path.to_path_buf(), reason })
    }

    /// Why some binding's d or h is beyond `bound` in size, if one is.
    fn check_offsets(&self, bound: f64) -> Result<(), String> {
        let beyond = |params: &VertexBinding| {
            [("d", params.d), ("h", params.h)].into_iter().find(|(_, value)| value.abs() > bound).map(
                |(name, value)| {
                    format!(
                        "{name} = {} is out of range: |d| and |h| are at most {} for this mesh and rig",
                        check::number(value),
                        check::number(bound)
                    )
                },
            )
        };
        let MeshBindings { vertices, bands } = &self.bindings;
        for (i, b) in vertices.iter().enumerate().filter(|(_, b)| b.sweep != UNOWNED) {
            if let Some(reason) = beyond(&b.params) {
                return Err(format!("vertex {i}: {reason}"));
            }
        }
        for (i, band) in bands.iter().enumerate().filter(|(_, b)| b.second.sweep != UNOWNED) {
            if let Some(reason) = beyond(&band.second.params) {
                return Err(format!("band vertex {i} (vertex {}): second binding: {reason}", band.vertex));
            }
        }
        Ok(())
    }
}

/// Why a band record of `vertex` (second sweep `sweep`, weight `weight`) cannot follow
/// `previous` among the bands of `vertices`, if it cannot.
fn check_band(
    vertices: &[Binding],
    previous: Option<&BandBinding>,
    vertex: u32,
    sweep: u32,
    weight: f64,
) -> Result<(), String> {
    let Some(own) = vertices.get(vertex as usize).map(|b| b.sweep) else {
        return Err(format!("the vertex is out of range: the file has {} vertices", vertices.len()));
    };
    if own == UNOWNED {
        return Err("the vertex is unowned, so it has no sweep to fade from".to_string());
    }
    if let Some(previous) = previous.filter(|p| p.vertex >= vertex) {
        return Err(format!(
            "listed after vertex {}; band vertices must be listed by strictly increasing vertex",
            previous.vertex
        ));
    }
    if !(0.0..1.0).contains(&weight) {
        return Err(format!("weight {} is outside [0, 1)", check::number(weight)));
    }
    if sweep == own {
        return Err(format!("its second sweep {sweep} is its own sweep"));
    }
    Ok(())
}
