//! The texture coordinates (TEXCOORD_0) of a glTF file's vertices, for the animation export:
//! each vertex block's coordinates from the primitive that gave it (`super::Block`), in the
//! form of an OBJ's corner coordinates, v up ([`CornerTexcoords`]). `None` where a block's
//! primitive has none, or not as many as positions, or not as floats or normalized integers.

use ::gltf::Semantic;
use ::gltf::accessor::{DataType, Dimensions};

use super::GltfFile;
use super::accessor::{f32_at, read};
use crate::formats::obj::texcoords::CornerTexcoords;
use crate::limits::MAX_VERTICES;
use crate::mesh::Faces;

/// The texture coordinates of `file`'s vertices as corner coordinates of `faces` (the faces
/// read from it): each corner takes its vertex's.
pub(crate) fn vertex_texcoords(file: &GltfFile, faces: &Faces) -> Option<CornerTexcoords> {
    let root: ::gltf::json::Root = serde_json::from_value(file.json.clone()).ok()?;
    let document = ::gltf::Document::from_json(root).ok()?;
    let count = file.blocks.iter().map(|b| b.first + b.local.len()).max()?;
    let mut coords = vec![[0.0f32; 2]; count];
    for block in &file.blocks {
        let mesh = document.meshes().nth(block.mesh)?;
        let accessor = mesh.primitives().find_map(|primitive| {
            let position = primitive.get(&Semantic::Positions)?;
            if position.index() == block.accessor { primitive.get(&Semantic::TexCoords(0)) } else { None }
        })?;
        if accessor.count() != block.local.len() || accessor.dimensions() != Dimensions::Vec2 {
            return None;
        }
        let values: Vec<[f32; 2]> = match (accessor.data_type(), accessor.normalized()) {
            (DataType::F32, _) => {
                read(&accessor, &file.buffers, (MAX_VERTICES, "MAX_VERTICES"), |b| [f32_at(b, 0), f32_at(b, 4)])
            }
            (DataType::U8, true) => read(&accessor, &file.buffers, (MAX_VERTICES, "MAX_VERTICES"), |b| {
                [f32::from(b[0]) / 255.0, f32::from(b[1]) / 255.0]
            }),
            (DataType::U16, true) => read(&accessor, &file.buffers, (MAX_VERTICES, "MAX_VERTICES"), |b| {
                let at = |i: usize| f32::from(u16::from_le_bytes([b[i], b[i + 1]])) / 65535.0;
                [at(0), at(2)]
            }),
            _ => return None,
        }
        .ok()?;
        for (i, [u, v]) in values.into_iter().enumerate() {
            // glTF's v runs down the image; the OBJ form runs up.
            coords[block.first + i] = [u, 1.0 - v];
        }
    }
    let corners: Vec<u32> = faces.iter().flatten().copied().collect();
    corners.iter().all(|&v| (v as usize) < count).then_some(CornerTexcoords { coords, corners })
}
