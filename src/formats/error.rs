//! What can go wrong reading or writing a mesh file.
//!
//! Every error names the file as it was given (`Path::display`), and for OBJ and OFF, text
//! formats, the line at fault; numbers of vertices and faces are written the way the file
//! writes them (1-based in OBJ, zero-based in PLY, OFF and glTF).

use std::path::{Path, PathBuf};

use thiserror::Error;

use super::gltf::GltfDataError;
use super::off::OffLineError;
use super::ply::PlyHeaderError;
use crate::mesh::{LimitError, MeshDataError};

/// A reason a mesh file cannot be read or written.
///
/// Data that cannot form a [`Mesh`](crate::mesh::Mesh) is [`MeshError::Invalid`].
#[derive(Debug, Error)]
pub enum MeshError {
    /// The file could not be opened or read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file as given.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file (or its temporary sibling) could not be created, written or renamed.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file as given.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file name ends in none of `.obj`, `.ply`, `.off`, `.gltf`, `.glb`.
    #[error("{}: unsupported mesh format (expected .obj, .ply, .off, .gltf or .glb)", path.display())]
    UnsupportedFormat {
        /// The file as given.
        path: PathBuf,
    },
    /// The file holds no vertex at all.
    #[error("{}: the mesh has no vertices", path.display())]
    Empty {
        /// The file as given.
        path: PathBuf,
    },
    /// The file has more vertices or face indices than 32-bit indices can address.
    #[error("{}: more than {} vertices or face indices (indices are 32-bit)", path.display(), u32::MAX)]
    TooLarge {
        /// The file as given.
        path: PathBuf,
    },
    /// A line of an OBJ file cannot be understood.
    #[error("{}:{line}: {problem}", path.display())]
    Obj {
        /// The file as given.
        path: PathBuf,
        /// 1-based line number (the first line of a `\`-continued statement).
        line: usize,
        /// What is wrong with the line.
        problem: ObjLineError,
    },
    /// A line of an OFF file cannot be understood.
    #[error("{}:{line}: {problem}", path.display())]
    Off {
        /// The file as given.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong with the line.
        problem: OffLineError,
    },
    /// The glTF parser rejected the file, or a buffer it needs cannot be read.
    #[error("{}: not a valid glTF file: {reason}", path.display())]
    InvalidGltf {
        /// The file as given.
        path: PathBuf,
        /// The parser's reason, on one line.
        reason: String,
    },
    /// The data of a glTF file do not form a mesh this crate reads.
    #[error("{}: {problem}", path.display())]
    GltfData {
        /// The file as given.
        path: PathBuf,
        /// What is wrong with the data.
        problem: GltfDataError,
    },
    /// The PLY parser rejected the file.
    #[error("{}: not a valid PLY file: {reason}", path.display())]
    InvalidPly {
        /// The file as given.
        path: PathBuf,
        /// The parser's reason, on one line.
        reason: String,
    },
    /// A line of a PLY header declares something this reader refuses (see [`PlyHeaderError`]).
    #[error("{}:{line}: {problem}", path.display())]
    PlyHeader {
        /// The file as given.
        path: PathBuf,
        /// 1-based line number in the header.
        line: usize,
        /// What is wrong with the declaration.
        problem: PlyHeaderError,
    },
    /// A `float` or `double` property of a PLY element (scalar or list) holds an infinite or
    /// NaN value: in ASCII a number too large for the type, in binary any bit pattern.
    #[error("{}: element \"{element}\" entry {entry}, property \"{property}\": the value {value} is not finite", path.display())]
    PlyNonFinite {
        /// The file as given.
        path: PathBuf,
        /// The element's name.
        element: String,
        /// Zero-based entry of the element.
        entry: usize,
        /// The property's name.
        property: String,
        /// The value read.
        value: f64,
    },
    /// The file holds more of something than sweepffd reads (see [`crate::limits`]).
    #[error("{}: {problem}", path.display())]
    Limit {
        /// The file as given.
        path: PathBuf,
        /// Which limit, and the count met.
        problem: LimitError,
    },
    /// A position to be written is not finite, or does not fit in the f32 the output format
    /// stores; nothing was written.
    #[error(
        "{}: vertex {vertex} has the coordinate {}, {}; nothing was written",
        path.display(),
        super::obj::write::Coordinate(*value),
        if value.is_finite() { "which does not fit in the f32 this format stores" } else { "which is not finite" }
    )]
    Unwritable {
        /// The output file as given.
        path: PathBuf,
        /// Zero-based vertex number.
        vertex: usize,
        /// The coordinate at fault (the first of the vertex's three).
        value: f64,
    },
    /// The PLY file has no `vertex` element with float or double `x`, `y` and `z`.
    #[error("{}: no \"vertex\" element with x, y, z properties", path.display())]
    NoPlyVertices {
        /// The file as given.
        path: PathBuf,
    },
    /// The PLY file's `face` element has no integer list `vertex_indices` or `vertex_index`.
    #[error("{}: the \"face\" element has no integer list property vertex_indices or vertex_index", path.display())]
    NoPlyFaceIndices {
        /// The file as given.
        path: PathBuf,
    },
    /// The data of a PLY file does not form a mesh (zero-based face and vertex numbers).
    #[error("{}: {problem}", path.display())]
    PlyData {
        /// The file as given.
        path: PathBuf,
        /// What is wrong with the data.
        problem: MeshDataError,
    },
    /// Data given in code (or positions given to save) do not form a mesh.
    #[error("{0}")]
    Invalid(#[from] MeshDataError),
    /// A position list does not have one entry per vertex of the mesh.
    #[error("positions has {found} entries but the mesh has {expected} vertices")]
    PositionCount {
        /// The mesh's vertex count.
        expected: usize,
        /// The length of the list given.
        found: usize,
    },
}

/// What is wrong with one statement of an OBJ file. Vertex numbers are 1-based, as in OBJ.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ObjLineError {
    /// A token that should be a number is not one.
    #[error("{what} \"{token}\" is not a number")]
    NotANumber {
        /// `"vertex coordinate"`, `"face index"`, `"vertex value"`, `"texture coordinate"`, ….
        what: &'static str,
        /// The token as written (invalid UTF-8 replaced).
        token: String,
    },
    /// A `v` statement with fewer than three numbers.
    #[error("vertex has {found} coordinates; x, y and z are needed")]
    MissingCoordinates {
        /// How many numbers the statement has.
        found: usize,
    },
    /// A `v` statement with an infinite or NaN coordinate.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// 1-based vertex number.
        vertex: usize,
    },
    /// A `v` value after the position (w or a colour), or a `vt`, `vn` or `vp` value, that is
    /// infinite or NaN (as written, or too large for f64).
    #[error("{what} \"{token}\" is not finite")]
    NonFiniteValue {
        /// `"vertex value"`, `"texture coordinate"`, `"normal coordinate"` or
        /// `"parameter-space coordinate"`.
        what: &'static str,
        /// The token as written.
        token: String,
    },
    /// The file reaches one of the limits at this statement.
    #[error(transparent)]
    Limit(LimitError),
    /// A face index of 0, which OBJ does not define.
    #[error("face refers to vertex 0 (OBJ indices start at 1)")]
    ZeroIndex,
    /// A positive face index past the last vertex of the file.
    #[error("face refers to vertex {index} but the file has {count} vertices")]
    IndexOutOfRange {
        /// The index as written.
        index: i64,
        /// The number of vertices in the file.
        count: usize,
    },
    /// A negative (relative) face index that reaches before the first vertex.
    #[error("face refers to vertex {index} but only {preceding} vertices precede it")]
    RelativeIndexOutOfRange {
        /// The index as written.
        index: i64,
        /// The number of vertices read before the face.
        preceding: usize,
    },
    /// A face with fewer than three vertices.
    #[error("face has {count} vertices; a face needs at least 3")]
    ShortFace {
        /// How many vertices the face has.
        count: usize,
    },
}

impl MeshError {
    /// Wraps an I/O error met while reading `path`.
    pub(crate) fn read(path: &Path, source: std::io::Error) -> Self {
        Self::Read { path: path.to_path_buf(), source }
    }

    /// Wraps an I/O error met while writing `path`.
    pub(crate) fn write(path: &Path, source: std::io::Error) -> Self {
        Self::Write { path: path.to_path_buf(), source }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obj_index_error_names_file_and_line() {
        let e = MeshError::Obj {
            path: PathBuf::from("bunny.obj"),
            line: 1234,
            problem: ObjLineError::IndexOutOfRange { index: 40000, count: 35947 },
        };
        assert_eq!(e.to_string(), "bunny.obj:1234: face refers to vertex 40000 but the file has 35947 vertices");
    }

    #[test]
    fn io_errors_name_the_path() {
        let e = MeshError::read(Path::new("m.obj"), std::io::Error::new(std::io::ErrorKind::NotFound, "gone"));
        assert_eq!(e.to_string(), "cannot read m.obj: gone");
        let e =
            MeshError::write(Path::new("out.obj"), std::io::Error::new(std::io::ErrorKind::PermissionDenied, "denied"));
        assert_eq!(e.to_string(), "cannot write out.obj: denied");
    }

    #[test]
    fn file_level_messages() {
        let p = || PathBuf::from("m.ply");
        assert_eq!(
            MeshError::NoPlyVertices { path: p() }.to_string(),
            "m.ply: no \"vertex\" element with x, y, z properties"
        );
        assert_eq!(
            MeshError::UnsupportedFormat { path: PathBuf::from("x.stl") }.to_string(),
            "x.stl: unsupported mesh format (expected .obj, .ply, .off, .gltf or .glb)"
        );
        assert_eq!(
            MeshError::Empty { path: PathBuf::from("empty.obj") }.to_string(),
            "empty.obj: the mesh has no vertices"
        );
        assert_eq!(
            MeshError::PositionCount { expected: 12, found: 10 }.to_string(),
            "positions has 10 entries but the mesh has 12 vertices"
        );
        assert_eq!(
            MeshError::PlyData { path: p(), problem: MeshDataError::ShortFace { face: 3, count: 2 } }.to_string(),
            "m.ply: face 3 has 2 vertices; a face needs at least 3"
        );
    }
}
