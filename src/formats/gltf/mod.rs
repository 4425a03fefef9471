//! glTF 2.0 (`.gltf` JSON and `.glb` binary container), read through the `gltf` crate.
//!
//! **Reading** ([`mod@read`]). Every primitive of every mesh that a node of the default scene
//! (else the first scene; else every root node; else, with no node at all, every mesh)
//! instantiates: its f32 POSITION, transformed by the node's world matrix into f64 positions,
//! and its indices (u8, u16 or u32; none means 0, 1, 2, …). Triangle lists, strips and fans
//! become triangles; points give vertices without faces; lines are an error. Primitives of
//! one node that share a POSITION accessor share their vertices; all vertex blocks are merged
//! into one vertex array in scene order. Each mesh becomes a [`FaceGroup`](super::FaceGroup)
//! named after it (`mesh0`, `mesh1`, … for unnamed meshes; `name.3` if a name repeats), so
//! rigs can select parts by group. Buffers come from the GLB BIN chunk, base64 data URIs or
//! files beside the glTF ([`mod@uri`]: a relative path, percent-decoded, resolving to a regular
//! file inside the folder of the `.gltf` file; at most `byteLength` bytes are read). Image
//! URIs are never read.
//!
//! **Hostile files** are refused before they cost more than their size: the node graph is
//! walked without recursion and measured before it is expanded ([`mod@graph`]: depth at most
//! [`MAX_GLTF_NODE_DEPTH`](crate::limits::MAX_GLTF_NODE_DEPTH), instances, vertices,
//! triangles and node visits within [`crate::limits`]), accessors are bounds-checked before
//! anything is allocated for them ([`mod@accessor`]), non-finite positions, float attributes
//! and node transforms are errors, and what the `gltf` crate would panic on is checked first
//! ([`mod@precheck`]; any other panic is caught silently, [`mod@quiet`]).
//!
//! **Writing back** ([`mod@write`]): the same JSON document and buffers, with only the POSITION
//! elements of moved vertices changed (mapped back through the inverse world matrix into the
//! node's local space), the `min`/`max` of those accessors, and the NORMAL of the vertices of
//! triangles that touch a moved vertex (area-weighted normals of the primitive's triangles;
//! TANGENT is left as it is). Everything else (UVs, colours, joints, weights, materials,
//! textures, animations, extensions, extras) is kept. A mesh instantiated by several nodes
//! shares one POSITION accessor between them, so its instances must agree: each instance's
//! new positions, mapped into local space through its own node, must equal (within f32
//! rounding) those written from the first instance, else the write is an error that suggests
//! another format (.obj, .ply, .off), which keeps the instances' vertices apart. Every buffer is written embedded — in the BIN chunk (buffer
//! 0 of a `.glb`) or as a base64 data URI — so the output is one self-contained file, written
//! atomically; image URIs are kept as they are.
//!
//! **Writing generically** ([`mod@generic`]): one mesh, one primitive, f32 POSITION,
//! area-weighted NORMAL and u32 indices of the fan-triangulated faces.

mod accessor;
mod aliasing;
mod buffers;
mod container;
mod error;
pub(crate) mod generic;
mod graph;
pub(crate) mod morph;
mod normals;
mod precheck;
mod quiet;
pub(crate) mod read;
mod scene;
pub(crate) mod texcoords;
mod uri;
pub(crate) mod write;

use glam::DMat4;

pub use error::GltfDataError;

/// A glTF file as read: what the faithful writer needs to write it back.
pub(crate) struct GltfFile {
    /// The JSON document, as parsed (unknown properties included).
    pub json: serde_json::Value,
    /// The data of each buffer, `byteLength` bytes long.
    pub buffers: Vec<Vec<u8>>,
    /// The vertex blocks of the mesh, in order.
    pub blocks: Vec<Block>,
    /// The primitives that gave faces, in order.
    pub primitives: Vec<PrimitiveRecord>,
}

/// The vertices one node instance took from one POSITION accessor.
pub(crate) struct Block {
    /// The POSITION accessor.
    pub accessor: usize,
    /// The mesh whose primitive gave the block.
    pub mesh: usize,
    /// The node drawing the mesh, `None` in a file without nodes.
    pub node: Option<usize>,
    /// The mesh vertex of the accessor's element 0.
    pub first: usize,
    /// The accessor's elements as read (node-local space).
    pub local: Vec<[f32; 3]>,
    /// The node's world matrix (local → mesh positions).
    pub transform: DMat4,
    /// Where the elements lie in the buffers, if the accessor is dense.
    pub target: Option<Target>,
}

/// Where a dense float VEC3 accessor's elements lie: element `i` is the 12 bytes at
/// `offset + i * stride` of buffer `buffer`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Target {
    /// The buffer index.
    pub buffer: usize,
    /// Byte offset of element 0 (view offset + accessor offset).
    pub offset: usize,
    /// Bytes from one element to the next.
    pub stride: usize,
}

/// A primitive that gave faces.
pub(crate) struct PrimitiveRecord {
    /// Its vertex block.
    pub block: usize,
    /// Its faces (triangles) in the mesh.
    pub faces: std::ops::Range<usize>,
    /// Its NORMAL accessor, when dense float VEC3: (accessor index, its count, where it lies).
    pub normal: Option<(usize, usize, Target)>,
}
