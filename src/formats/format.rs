//! Which mesh format a file name asks for.

use std::path::Path;

use super::MeshError;

/// A mesh file format, chosen by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// Stanford PLY (`.ply`).
    Ply,
    /// Object File Format (`.off`), ASCII.
    Off,
    /// glTF 2.0 as JSON (`.gltf`); buffers written embedded as base64 data URIs.
    Gltf,
    /// glTF 2.0 binary container (`.glb`).
    Glb,
}

impl Format {
    /// The format of `path` by its extension, `.obj`, `.ply`, `.off`, `.gltf` or `.glb` in any
    /// case.
    pub fn of(path: &Path) -> Result<Format, MeshError> {
        let extension = path.extension().and_then(|e| e.to_str());
        match extension.map(str::to_ascii_lowercase).as_deref() {
            Some("obj") => Ok(Format::Obj),
            Some("ply") => Ok(Format::Ply),
            Some("off") => Ok(Format::Off),
            Some("gltf") => Ok(Format::Gltf),
            Some("glb") => Ok(Format::Glb),
            _ => Err(MeshError::UnsupportedFormat { path: path.to_path_buf() }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extension_is_case_insensitive() {
        assert_eq!(Format::of(Path::new("a/b.OBJ")).unwrap(), Format::Obj);
        assert_eq!(Format::of(Path::new("b.Ply")).unwrap(), Format::Ply);
        assert_eq!(Format::of(Path::new("c.OFF")).unwrap(), Format::Off);
        assert_eq!(Format::of(Path::new("d.glTF")).unwrap(), Format::Gltf);
        assert_eq!(Format::of(Path::new("e.GLB")).unwrap(), Format::Glb);
    }

    #[test]
    fn other_or_missing_extension_is_unsupported() {
        for name in ["x.stl", "obj", "x.obj.gz", "x."] {
            let err = Format::of(Path::new(name)).unwrap_err();
            assert_eq!(
                err.to_string(),
                format!("{name}: unsupported mesh format (expected .obj, .ply, .off, .gltf or .glb)")
            );
        }
    }
}
