//! [`Mesh::save`]: writing a mesh with new positions, faithfully when possible.

use std::path::Path;

use glam::DVec3;

use super::atomic::write_atomically;
use super::format::Format;
use super::source::Source;
use super::{Mesh, MeshDataError, MeshError, gltf, obj, off, ply};

impl Mesh {
    /// Writes the mesh with `positions` (one per vertex, same order) to `path`, format by
    /// extension (`.obj`, `.ply`, `.off`, `.gltf` or `.glb`, case-insensitive).
    ///
    /// *Faithful* when the mesh was loaded from a file of the same format and its vertex count,
    /// faces and groups are still those of the file: the output is the input file with only the
    /// positions of moved vertices changed (see the OBJ and PLY writers for the exact rules);
    /// with unchanged positions an OBJ comes out byte-identical and a PLY parses to identical
    /// data; an OFF comes out byte-identical. A glTF read from `.gltf` or `.glb` can be written
    /// faithfully to either: the same document with only the POSITION data of moved vertices
    /// (back in each node's local space), their accessors' `min`/`max`, and the NORMAL of
    /// their triangles changed (see `gltf::write`). Otherwise (another format, a mesh built with
    /// [`Mesh::from_parts`], or edited connectivity) a generic file is written: OBJ with `v`,
    /// `g` and `f` lines, binary little-endian PLY with float coordinates, OFF with `V F 0`
    /// counts, or glTF with one mesh of one primitive (f32 POSITION, area-weighted NORMAL, u32
    /// indices of the fan-triangulated faces).
    ///
    /// Atomic: the file is written to a temporary file in the same directory, flushed, then
    /// renamed over `path`; on any error the temporary file is removed and `path` is untouched.
    ///
    /// # Errors
    ///
    /// [`MeshError::PositionCount`] if `positions.len() != self.positions.len()`,
    /// [`MeshError::Invalid`] with [`MeshDataError::NonFinite`] for a NaN or infinite position,
    /// [`MeshError::UnsupportedFormat`] for another extension, [`MeshError::Write`] if the file
    /// cannot be written.
    pub fn save(&self, path: &Path, positions: &[DVec3]) -> Result<(), MeshError> {
        if positions.len() != self.positions.len() {
            return Err(MeshError::PositionCount { expected: self.positions.len(), found: positions.len() });
        }
        let format = Format::of(path)?;
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshDataError::NonFinite { vertex }.into());
        }
        write_atomically(path, |out| match (&self.source, format) {
            (Source::Obj(o), Format::Obj) if o.describes(self) => {
                obj::write::write_faithful(out, &o.file, &o.positions, positions)
            }
            (Source::Ply(p), Format::Ply) if p.describes(self) => {
                ply::write::write_faithful(out, &p.file, &p.positions, positions)
            }
            (Source::Off(o), Format::Off) if o.describes(self) => {
                off::write::write_faithful(out, &o.file, &o.positions, positions)
            }
            (Source::Gltf(g), Format::Gltf | Format::Glb) if g.describes(self) => {
                gltf::write::write_faithful(out, g, positions, format == Format::Glb)
            }
            (_, Format::Obj) => obj::write::write_generic(out, positions, &self.faces, &self.groups),
            (_, Format::Ply) => ply::write::write_generic(out, positions, &self.faces),
            (_, Format::Off) => off::write::write_generic(out, positions, &self.faces),
            (_, Format::Gltf | Format::Glb) => {
                gltf::generic::write_generic(out, positions, &self.faces, format == Format::Glb)
            }
        })
        .map_err(|e| MeshError::write(path, e))
    }
}
