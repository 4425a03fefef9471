//! What can be wrong with the data of a glTF file.

use thiserror::Error;

/// What is wrong with the data of a glTF file. Meshes, primitives, accessors, nodes and
/// buffers are numbered from 0, as in the file's arrays.
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
    /// An index accessor whose elements are not unsigned byte, short or int scalars.
    #[error(
        "mesh {mesh} primitive {primitive}: indices accessor {accessor} is {found}, not an unsigned integer SCALAR"
    )]
    IndexType {
        /// Mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// Accessor index.
        accessor: usize,
        /// Its component type and type, e.g. `"FLOAT SCALAR"`.
        found: String,
    },
    /// An accessor whose data reach past the end of what holds them.
    #[error("accessor {accessor}: {what} needs {needed} bytes but {holder} holds {available}")]
    AccessorOutOfBounds {
        /// Accessor index.
        accessor: usize,
        /// Which data: `"its data"`, `"its sparse indices"` or `"its sparse values"`.
        what: &'static str,
        /// Bytes needed from the start of the buffer view (saturating).
        needed: usize,
        /// What holds the data: `"buffer view 2"`, `"buffer 0"`.
        holder: String,
        /// Bytes there.
        available: usize,
    },
    /// An accessor whose layout is inconsistent (stride, sparse indices).
    #[error("accessor {accessor}: {reason}")]
    AccessorLayout {
        /// Accessor index.
        accessor: usize,
        /// What is wrong.
        reason: String,
    },
    /// An accessor of more elements than the mesh it feeds may have.
    #[error("accessor {accessor} has {count} elements, more than the limit of {limit} ({name} in sweepffd::limits)")]
    AccessorTooLarge {
        /// Accessor index.
        accessor: usize,
        /// Its element count.
        count: usize,
        /// The limit.
        limit: usize,
        /// The limit's name.
        name: &'static str,
    },
    /// A float vertex attribute with an infinite or NaN component.
    #[error(
        "mesh {mesh} primitive {primitive}: {attribute} accessor {accessor} element {element} has the non-finite value {value}"
    )]
    NonFinite {
        /// Mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// The attribute's semantic, e.g. `"POSITION"`, `"NORMAL"`, `"TEXCOORD_0"`.
        attribute: String,
        /// Accessor index.
        accessor: usize,
        /// Element index.
        element: usize,
        /// The value as stored.
        value: f32,
    },
    /// A position that leaves f64 once transformed to world space.
    #[error(
        "mesh {mesh} primitive {primitive}: POSITION accessor {accessor} element {element} overflows under the world matrix of node {node} (a coordinate of {value})"
    )]
    WorldOverflow {
        /// Mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// Accessor index.
        accessor: usize,
        /// Element index.
        element: usize,
        /// The node instancing the mesh.
        node: usize,
        /// The world coordinate.
        value: f64,
    },
    /// A node whose local transform has an infinite or NaN component.
    #[error("node {node}: its {property} has the non-finite value {value}")]
    NodeTransform {
        /// Node index.
        node: usize,
        /// `"matrix"`, `"translation"`, `"rotation"` or `"scale"`.
        property: &'static str,
        /// The value as read (f32).
        value: f32,
    },
    /// A node whose world matrix (the product of its ancestors' transforms) leaves f64.
    #[error("node {node}: its world matrix overflows (a value of {value})")]
    NodeWorldOverflow {
        /// Node index.
        node: usize,
        /// The offending matrix entry.
        value: f64,
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
    /// A node deeper in the hierarchy than [`MAX_GLTF_NODE_DEPTH`](crate::limits::MAX_GLTF_NODE_DEPTH).
    #[error(
        "node {node} is at depth {depth} of the node hierarchy, deeper than the limit of {limit} (MAX_GLTF_NODE_DEPTH in sweepffd::limits)"
    )]
    NodeTooDeep {
        /// The first node found past the limit.
        node: usize,
        /// Its depth (a root is at depth 0).
        depth: usize,
        /// The limit.
        limit: usize,
    },
    /// A scene that would expand to more than a limit allows, counted before anything is built.
    #[error(
        "the scene would give {} {what}, more than the limit of {limit} ({name} in sweepffd::limits)",
        saturated(*count)
    )]
    SceneTooLarge {
        /// What is counted: `"mesh instances"`, `"vertices"`, `"triangles"`, `"node instances"`.
        what: &'static str,
        /// The count (saturating: `usize::MAX` means at least that many).
        count: usize,
        /// The limit.
        limit: usize,
        /// The limit's name.
        name: &'static str,
    },
    /// A scene that would give far more vertices or triangles than its file stores
    /// ([`MAX_GLTF_EXPANSION`](crate::limits::MAX_GLTF_EXPANSION)), counted before anything is
    /// built.
    #[error(
        "the scene would give {} {what} from {stored} stored in the file, more than {expansion} times as many \
         (beyond the first {unstored}; MAX_GLTF_EXPANSION in sweepffd::limits)",
        saturated(*count)
    )]
    SceneExpands {
        /// What is counted: `"vertices"` or `"triangles"`.
        what: &'static str,
        /// The count (saturating).
        count: usize,
        /// What the file's bytes hold.
        stored: usize,
        /// The factor allowed.
        expansion: usize,
        /// The count allowed whatever is stored.
        unstored: usize,
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

/// A saturating count as text: `usize::MAX` shows as "at least …".
fn saturated(count: usize) -> String {
    if count == usize::MAX { format!("at least {count}") } else { count.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saturated_counts_say_at_least() {
        assert_eq!(saturated(7), "7");
        assert_eq!(saturated(usize::MAX), format!("at least {}", usize::MAX));
    }
}
