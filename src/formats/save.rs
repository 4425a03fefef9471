//! [`LoadedMesh::save`]: writing a mesh with new positions, faithfully when possible.

use std::path::Path;

use glam::DVec3;

use super::format::Format;
use super::loaded::{LoadedMesh, Source};
use super::{MeshError, gltf, obj, off, ply};
use crate::atomic_file::write_atomically;

impl LoadedMesh {
    /// Writes the mesh with `positions` (one per vertex, same order) to `path`, format by
    /// extension (`.obj`, `.ply`, `.off`, `.gltf` or `.glb`, case-insensitive).
    ///
    /// *Faithful* when the mesh was loaded from a file of the same format and its vertex count,
    /// faces and groups are still those of the file: the output is the input file with only the
    /// positions of moved vertices changed (see the OBJ and PLY writers for the exact rules);
    /// with unchanged positions an OBJ, an OFF and a PLY come out byte-identical (a PLY whose
    /// `vertex` element has a list property, read through `ply-rs-bw`, parses to identical
    /// data). A glTF read from `.gltf` or `.glb` can be written
    /// faithfully to either: the same document with only the POSITION data of moved vertices
    /// (back in each node's local space), their accessors' `min`/`max`, and the NORMAL of
    /// their triangles changed (see `gltf::write`). Otherwise (another format, a mesh built with
    /// [`Mesh::from_parts`](crate::mesh::Mesh::from_parts) and turned into a `LoadedMesh` by `From`, or edited connectivity)
    /// a generic file is written: OBJ with `v`,
    /// `g` and `f` lines, binary little-endian PLY with float coordinates, OFF with `V F 0`
    /// counts, or glTF with one mesh of one primitive (f32 POSITION, area-weighted NORMAL, u32
    /// indices of the fan-triangulated faces).
    ///
    /// Every coordinate must be finite, and, where the output stores f32 (generic PLY, a
    /// faithful PLY whose `x`, `y` or `z` is `float`, glTF and GLB), within f32's range once
    /// rounded; OBJ and OFF print shortest round-trip f64 digits. This is checked for every
    /// vertex before anything is written.
    ///
    /// Atomic: the file is written to a temporary file in the same directory, flushed, then
    /// renamed over `path`; on any error the temporary file is removed and `path` is untouched.
    ///
    /// # Errors
    ///
    /// [`MeshError::PositionCount`] if `positions.len() != self.mesh.positions.len()`,
    /// [`MeshError::Unwritable`] naming `path`, the vertex and the coordinate for a NaN or
    /// infinite coordinate or one that overflows the f32 of the format,
    /// [`MeshError::UnsupportedFormat`] for another extension, [`MeshError::Write`] if the file
    /// cannot be written.
    pub fn save(&self, path: &Path, positions: &[DVec3]) -> Result<(), MeshError> {
        let mesh = &self.mesh;
        if positions.len() != mesh.positions.len() {
            return Err(MeshError::PositionCount { expected: mesh.positions.len(), found: positions.len() });
        }
        let format = Format::of(path)?;
        check_writable(path, positions, self.stores_f32(format))?;
        write_atomically(path, |out| match (&self.source, format) {
            (Source::Obj(o), Format::Obj) if o.describes(mesh) => obj::write::write_faithful(out, o, positions),
            (Source::Ply(p), Format::Ply) if p.describes(mesh) => {
                ply::write::write_faithful(out, &p.file, &p.positions, positions)
            }
            (Source::Off(o), Format::Off) if o.describes(mesh) => {
                off::write::write_faithful(out, &o.file, &o.positions, positions)
            }
            (Source::Gltf(g), Format::Gltf | Format::Glb) if g.describes(mesh) => {
                gltf::write::write_faithful(out, g, positions, format == Format::Glb)
            }
            (_, Format::Obj) => obj::write::write_generic(out, positions, &mesh.faces, &mesh.groups),
            (_, Format::Ply) => ply::write::write_generic(out, positions, &mesh.faces),
            (_, Format::Off) => off::write::write_generic(out, positions, &mesh.faces),
            (_, Format::Gltf | Format::Glb) => {
                gltf::generic::write_generic(out, positions, &mesh.faces, format == Format::Glb)
            }
        })
        .map_err(|e| MeshError::write(path, e))
    }

    /// Whether [`LoadedMesh::save`] to a file of `format` stores positions as f32.
    fn stores_f32(&self, format: Format) -> bool {
        match (&self.source, format) {
            (Source::Ply(p), Format::Ply) if p.describes(&self.mesh) => ply::write::stores_f32(p.file.header()),
            (_, Format::Ply | Format::Gltf | Format::Glb) => true,
            (_, Format::Obj | Format::Off) => false,
        }
    }
}

/// Checks that every coordinate of `positions` is finite and, if `f32`, stays finite once
/// rounded to f32 (magnitudes up to `f32::MAX` plus half an ulp round to `f32::MAX`).
fn check_writable(path: &Path, positions: &[DVec3], f32: bool) -> Result<(), MeshError> {
    for (vertex, p) in positions.iter().enumerate() {
        let bad = p.to_array().into_iter().find(|&c| !c.is_finite() || (f32 && !(c as f32).is_finite()));
        if let Some(value) = bad {
            return Err(MeshError::Unwritable { path: path.to_path_buf(), vertex, value });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_range_is_checked_after_rounding() {
        let path = Path::new("out.ply");
        let just_over = f64::from(f32::MAX) * (1.0 + f64::from(f32::EPSILON));
        let rounds_down = f64::from(f32::MAX) * (1.0 + f64::from(f32::EPSILON) / 4.0);
        assert!(check_writable(path, &[DVec3::new(0.0, rounds_down, 0.0)], true).is_ok());
        let err = check_writable(path, &[DVec3::ZERO, DVec3::new(0.0, 0.0, -just_over)], true).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "out.ply: vertex 1 has the coordinate {}, which does not fit in the f32 this format stores; nothing was written",
                format_args!("{:e}", -just_over)
            )
        );
        assert!(check_writable(path, &[DVec3::splat(1e300)], false).is_ok());
    }

    #[test]
    fn non_finite_coordinates_are_refused_in_every_format() {
        for f32 in [false, true] {
            let err = check_writable(Path::new("o.obj"), &[DVec3::new(f64::NAN, 0.0, 0.0)], f32).unwrap_err();
            assert_eq!(
                err.to_string(),
                "o.obj: vertex 0 has the coordinate NaN, which is not finite; nothing was written"
            );
        }
        let err = check_writable(Path::new("o.off"), &[DVec3::new(1.0, f64::NEG_INFINITY, 0.0)], false).unwrap_err();
        assert_eq!(
            err.to_string(),
            "o.off: vertex 0 has the coordinate -inf, which is not finite; nothing was written"
        );
    }
}
