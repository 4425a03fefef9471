//! Reading a glTF or GLB file into a [`Mesh`] (see the module docs for what is read).

use std::collections::HashMap;
use std::path::Path;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::{Mode, Semantic};
use glam::{DMat4, DVec3};

use super::{Block, GltfDataError, GltfFile, PrimitiveRecord, Target, buffers, scene};
use crate::mesh::source::{Original, Source};
use crate::mesh::{FaceGroup, Faces, Mesh, MeshError};

/// Reads the glTF (JSON) or GLB (binary, by its `glTF` magic) file `bytes` read from `path`.
///
/// The `gltf` crate (1.4) can panic on some malformed documents (its validation indexes
/// arrays unchecked), so a panic while reading is caught and reported as
/// [`MeshError::InvalidGltf`]; the default panic hook still prints its message.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<Mesh, MeshError> {
    std::panic::catch_unwind(|| read_unguarded(path, bytes)).unwrap_or_else(|_| {
        let reason = "the glTF reader panicked on this malformed file".to_string();
        Err(MeshError::InvalidGltf { path: path.to_path_buf(), reason })
    })
}

/// [`read`] without the panic guard.
fn read_unguarded(path: &Path, bytes: &[u8]) -> Result<Mesh, MeshError> {
    let invalid = |reason: String| MeshError::InvalidGltf { path: path.to_path_buf(), reason };
    let data_error = |problem| MeshError::GltfData { path: path.to_path_buf(), problem };
    let gltf = ::gltf::Gltf::from_slice(bytes).map_err(|e| invalid(one_line(&e.to_string())))?;
    let json = json_value(bytes).map_err(invalid)?;
    let buffers = buffers::resolve(path, &gltf.document, gltf.blob.as_deref()).map_err(data_error)?;
    let mut builder = Builder::default();
    for (instance, (mesh, transform)) in scene::instances(&gltf.document).map_err(data_error)?.into_iter().enumerate() {
        let Some(mesh) = gltf.document.meshes().nth(mesh) else { continue };
        for primitive in mesh.primitives() {
            builder.add(instance, &mesh, &primitive, transform, &buffers).map_err(data_error)?;
        }
    }
    if builder.positions.is_empty() {
        return Err(MeshError::Empty { path: path.to_path_buf() });
    }
    if builder.positions.len() > u32::MAX as usize {
        return Err(MeshError::TooLarge { path: path.to_path_buf() });
    }
    let groups = builder.groups.into_iter().map(|(_, group)| group).collect();
    let mesh = Mesh { positions: builder.positions, faces: builder.faces, groups, source: Source::Code };
    let file = GltfFile { json, buffers, blocks: builder.blocks, primitives: builder.primitives };
    Ok(Mesh { source: Source::Gltf(Original::new(file, &mesh)), ..mesh })
}

/// The parser's message on one line.
fn one_line(message: &str) -> String {
    message.lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join("; ")
}

/// The JSON document of a glTF or GLB file, as a generic value (nothing dropped).
fn json_value(bytes: &[u8]) -> Result<serde_json::Value, String> {
    if bytes.starts_with(b"glTF") {
        let glb = ::gltf::binary::Glb::from_slice(bytes).map_err(|e| e.to_string())?;
        serde_json::from_slice(&glb.json).map_err(|e| e.to_string())
    } else {
        serde_json::from_slice(bytes).map_err(|e| e.to_string())
    }
}

/// Where a dense float VEC3 accessor's elements lie, or `None` (sparse, no buffer view, or
/// another type).
fn dense_target(accessor: &::gltf::Accessor) -> Option<Target> {
    if accessor.sparse().is_some() || accessor.data_type() != DataType::F32 || accessor.dimensions() != Dimensions::Vec3
    {
        return None;
    }
    let view = accessor.view()?;
    Some(Target {
        buffer: view.buffer().index(),
        offset: view.offset() + accessor.offset(),
        stride: view.stride().unwrap_or(12),
    })
}

/// The mesh being assembled, primitive by primitive.
#[derive(Default)]
struct Builder {
    positions: Vec<DVec3>,
    faces: Faces,
    /// (mesh index, its group), in order of first face.
    groups: Vec<(usize, FaceGroup)>,
    blocks: Vec<Block>,
    /// (instance, POSITION accessor) → block.
    block_of: HashMap<(usize, usize), usize>,
    primitives: Vec<PrimitiveRecord>,
}

impl Builder {
    /// Adds one primitive of the `instance`-th mesh instance.
    fn add(
        &mut self,
        instance: usize,
        mesh: &::gltf::Mesh,
        primitive: &::gltf::Primitive,
        transform: DMat4,
        buffers: &[Vec<u8>],
    ) -> Result<(), GltfDataError> {
        let (m, p) = (mesh.index(), primitive.index());
        let mode = match primitive.mode() {
            Mode::Lines => Some("LINES"),
            Mode::LineLoop => Some("LINE_LOOP"),
            Mode::LineStrip => Some("LINE_STRIP"),
            _ => None,
        };
        if let Some(mode) = mode {
            return Err(GltfDataError::UnsupportedMode { mesh: m, primitive: p, mode });
        }
        let accessor =
            primitive.get(&Semantic::Positions).ok_or(GltfDataError::NoPositions { mesh: m, primitive: p })?;
        if accessor.data_type() != DataType::F32 || accessor.dimensions() != Dimensions::Vec3 {
            return Err(GltfDataError::PositionType { mesh: m, primitive: p });
        }
        let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let block = match self.block_of.get(&(instance, accessor.index())) {
            Some(&block) => block,
            None => {
                let out_of_bounds = GltfDataError::AccessorOutOfBounds { accessor: accessor.index() };
                let local: Vec<[f32; 3]> = reader.read_positions().ok_or(out_of_bounds)?.collect();
                self.add_block(accessor.index(), local, transform, dense_target(&accessor))?;
                self.block_of.insert((instance, accessor.index()), self.blocks.len() - 1);
                self.blocks.len() - 1
            }
        };
        let count = self.blocks[block].local.len();
        let indices: Vec<u32> = match primitive.indices() {
            Some(a) => {
                let out_of_bounds = GltfDataError::AccessorOutOfBounds { accessor: a.index() };
                reader.read_indices().ok_or(out_of_bounds)?.into_u32().collect()
            }
            None => (0..count as u32).collect(),
        };
        if let Some(&index) = indices.iter().find(|&&i| i as usize >= count) {
            return Err(GltfDataError::IndexOutOfRange { mesh: m, primitive: p, index, count });
        }
        let first = self.blocks[block].first as u32;
        let start = self.faces.len();
        for triangle in triangles(primitive.mode(), &indices) {
            if !self.faces.try_push(&triangle.map(|i| first + i)) {
                return Err(GltfDataError::Buffer { buffer: 0, reason: "more than u32::MAX face indices".into() });
            }
        }
        let faces = start..self.faces.len();
        if faces.is_empty() {
            return Ok(());
        }
        self.group(mesh).faces.extend(faces.clone().map(|f| f as u32));
        let normal = primitive.get(&Semantic::Normals).and_then(|a| Some((a.count(), dense_target(&a)?)));
        self.primitives.push(PrimitiveRecord { block, faces, normal });
        Ok(())
    }

    /// Adds the vertices of a POSITION accessor, transformed to world space.
    fn add_block(
        &mut self,
        accessor: usize,
        local: Vec<[f32; 3]>,
        transform: DMat4,
        target: Option<Target>,
    ) -> Result<(), GltfDataError> {
        let first = self.positions.len();
        for (element, p) in local.iter().enumerate() {
            let world = transform.transform_point3(DVec3::from_array(p.map(f64::from)));
            if !world.is_finite() {
                return Err(GltfDataError::NonFinite { accessor, element });
            }
            self.positions.push(world);
        }
        self.blocks.push(Block { accessor, first, local, transform, target });
        Ok(())
    }

    /// The group of `mesh`, created on its first face: its name, or `mesh<index>`, made unique.
    fn group(&mut self, mesh: &::gltf::Mesh) -> &mut FaceGroup {
        let at = match self.groups.iter().position(|(m, _)| *m == mesh.index()) {
            Some(at) => at,
            None => {
                let mut name = mesh.name().map_or_else(|| format!("mesh{}", mesh.index()), str::to_string);
                if self.groups.iter().any(|(_, g)| g.name == name) {
                    name = format!("{name}.{}", mesh.index());
                }
                self.groups.push((mesh.index(), FaceGroup { name, faces: Vec::new() }));
                self.groups.len() - 1
            }
        };
        &mut self.groups[at].1
    }
}

/// The triangles of a primitive of `mode` (triangles, strip or fan; points give none), with
/// the orientation of the first triangle kept along strips.
fn triangles(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::Triangles => indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        Mode::TriangleStrip => indices
            .windows(3)
            .enumerate()
            .map(|(i, w)| if i % 2 == 0 { [w[0], w[1], w[2]] } else { [w[1], w[0], w[2]] })
            .collect(),
        Mode::TriangleFan => indices.windows(2).skip(1).map(|w| [indices[0], w[0], w[1]]).collect(),
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_alternate_and_fans_share_the_first_vertex() {
        assert_eq!(triangles(Mode::TriangleStrip, &[0, 1, 2, 3]), [[0, 1, 2], [2, 1, 3]]);
        assert_eq!(triangles(Mode::TriangleFan, &[0, 1, 2, 3]), [[0, 1, 2], [0, 2, 3]]);
        assert_eq!(triangles(Mode::Triangles, &[0, 1, 2, 3]), [[0, 1, 2]]);
        assert!(triangles(Mode::Points, &[0, 1, 2]).is_empty());
    }
}
