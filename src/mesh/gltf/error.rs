//! What can be wrong with the data of a glTF file.

use thiserror::Error;

/// What is wrong with the data of a glTF file. Meshes, primitives, accessors and buffers are
/// numbered from 0, as in the file's arrays.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GltfDataError {
    /// A primitive of a mode this crate does not read (lines).
    #[error(
        "mesh {mesh} primitive {primitive}: {mode} primitives are not supported (triangles, strips, fans and points are)"
    )]
    UnsupportedMode {
        /// Mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// `"LINES"`, `"LINE_LOOP"` or `"LINE_STRIP"`.
        mode: &'static str,
    },
    /// A primitive without a POSITION attribute.
    #[error("mesh {mesh} primitive {primitive} has no POSITION attribute")]
    NoPositions {
        /// Mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
    },
    /// A POSITION accessor that is not float VEC3 (as with `KHR_mesh_quantization`).
    #[error("mesh {mesh} primitive {primitive}: POSITION is not float VEC3 (quantized positions are not supported)")]
    PositionType {
        /// Mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
    },
    /// An accessor whose data reach past the end of its buffer.
    #[error("accessor {accessor} reaches past the end of its buffer")]
    AccessorOutOfBounds {
        /// Accessor index.
        accessor: usize,
    },
    /// A POSITION element with an infinite or NaN coordinate.
    #[error("accessor {accessor} element {element} has a non-finite coordinate")]
    NonFinite {
        /// Accessor index.
        accessor: usize,
        /// Element index.
        element: usize,
    },
    /// An index past the end of the primitive's POSITION accessor.
    #[error("mesh {mesh} primitive {primitive} refers to vertex {index} but its POSITION has {count}")]
    IndexOutOfRange {
        /// Mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// The index as stored.
        index: u32,
        /// The POSITION accessor's element count.
        count: usize,
    },
    /// A node that is its own ancestor.
    #[error("the node hierarchy has a cycle (through node {node})")]
    NodeCycle {
        /// A node on the cycle.
        node: usize,
    },
    /// A buffer whose data cannot be had.
    #[error("buffer {buffer}: {reason}")]
    Buffer {
        /// Buffer index.
        buffer: usize,
        /// Why.
        reason: String,
    },
}
