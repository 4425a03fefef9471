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
}

impl Format {
    /// The format of `path` by its extension, `.obj` or `.ply` in any case.
    pub fn of(path: &Path) -> Result<Format, MeshError> {
        let extension = path.extension().and_then(|e| e.to_str());
        match extension.map(str::to_ascii_lowercase).as_deref() {
            Some("obj") => Ok(Format::Obj),
            Some("ply") => Ok(Format::Ply),
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
    }

    #[test]
    fn other_or_missing_extension_is_unsupported() {
        for name in ["x.stl", "obj", "x.obj.gz", "x."] {
            let err = Format::of(Path::new(name)).unwrap_err();
            assert_eq!(err.to_string(), format!("{name}: unsupported mesh format (expected .obj or .ply)"));
        }
    }
}
