//! Reading a glTF or GLB file into a [`Mesh`] (see the module docs for what is read).
//!
//! Order of the checks, so that no hostile file costs more than its size: the GLB container
//! ([`container::split_glb`]), the JSON ([`precheck`]), the `gltf` crate's validation, the
//! node graph and what it would expand to ([`scene::instances`]), the buffers
//! ([`buffers::resolve`]), then each accessor as it is read ([`accessor`]).

use std::collections::{HashMap, HashSet};
use std::path::Path;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::{Mode, Semantic};
use glam::{DMat4, DVec3};

use super::accessor::{self, f32_at};
use super::scene::Instance;
use super::{Block, GltfDataError, GltfFile, PrimitiveRecord, Target, buffers, container, precheck, quiet, scene};
use crate::formats::MeshError;
use crate::formats::loaded::{LoadedMesh, Original, Source};
use crate::limits::{MAX_FACES, MAX_VERTICES};
use crate::mesh::{FaceGroup, Faces, Mesh};

/// Reads the glTF (JSON) or GLB (binary, by its `glTF` magic) file `bytes` read from `path`.
///
/// What the `gltf` crate (1.4) is known to panic on is checked before it is called. A panic
/// it did not foresee is still caught and reported as [`MeshError::InvalidGltf`], and the
/// panic hook stays silent for it ([`quiet`]): only the error reaches the user.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<LoadedMesh, MeshError> {
    quiet::catch_quietly(|| read_unguarded(path, bytes)).unwrap_or_else(|_| {
        let reason = "the glTF reader panicked on this malformed file".to_string();
        Err(MeshError::InvalidGltf { path: path.to_path_buf(), reason })
    })
}

/// [`read`] without the panic guard.
fn read_unguarded(path: &Path, bytes: &[u8]) -> Result<LoadedMesh, MeshError> {
    let invalid = |reason: String| MeshError::InvalidGltf { path: path.to_path_buf(), reason };
    let data_error = |problem| MeshError::GltfData { path: path.to_path_buf(), problem };
    let (text, blob) =
        if bytes.starts_with(b"glTF") { container::split_glb(bytes).map_err(invalid)? } else { (bytes, None) };
    let json: serde_json::Value = serde_json::from_slice(text).map_err(|e| invalid(e.to_string()))?;
    precheck::check(&json).map_err(invalid)?;
    let gltf = ::gltf::Gltf::from_slice(text).map_err(|e| invalid(one_line(&e.to_string())))?;
    let instances = scene::instances(&gltf.document).map_err(data_error)?;
    let buffers = buffers::resolve(path, &gltf.document, blob).map_err(data_error)?;
    let mut builder = Builder::default();
    for (number, instance) in instances.iter().enumerate() {
        let Some(mesh) = gltf.document.meshes().nth(instance.mesh) else { continue };
        for primitive in mesh.primitives() {
            builder.add(number, instance, &mesh, &primitive, &buffers).map_err(data_error)?;
        }
    }
    if builder.positions.is_empty() {
        return Err(MeshError::Empty { path: path.to_path_buf() });
    }
    if builder.positions.len() > u32::MAX as usize {
        return Err(MeshError::TooLarge { path: path.to_path_buf() });
    }
    let groups = builder.groups.into_iter().map(|(_, group)| group).collect();
    let mesh = Mesh { positions: builder.positions, faces: builder.faces, groups };
    let file = GltfFile { json, buffers, blocks: builder.blocks, primitives: builder.primitives };
    Ok(LoadedMesh { source: Source::Gltf(Original::new(file, &mesh)), mesh })
}

/// The parser's message on one line.
fn one_line(message: &str) -> String {
    message.lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join("; ")
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
    /// Float attribute accessors already checked to be finite.
    checked: HashSet<usize>,
}

/// Which primitive of which mesh, drawn by which node: what errors name.
#[derive(Clone, Copy)]
struct Site {
    mesh: usize,
    primitive: usize,
    node: Option<usize>,
}

impl Builder {
    /// Adds one primitive of the `number`-th mesh instance.
    fn add(
        &mut self,
        number: usize,
        instance: &Instance,
        mesh: &::gltf::Mesh,
        primitive: &::gltf::Primitive,
        buffers: &[Vec<u8>],
    ) -> Result<(), GltfDataError> {
        let site = Site { mesh: mesh.index(), primitive: primitive.index(), node: instance.node };
        let (m, p) = (site.mesh, site.primitive);
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
        self.check_attributes(site, primitive, buffers)?;
        let block = match self.block_of.get(&(number, accessor.index())) {
            Some(&block) => block,
            None => {
                let decode = |b: &[u8]| [f32_at(b, 0), f32_at(b, 4), f32_at(b, 8)];
                let local = accessor::read(&accessor, buffers, (MAX_VERTICES, "MAX_VERTICES"), decode)?;
                self.add_block(site, accessor.index(), local, instance.world, dense_target(&accessor))?;
                self.block_of.insert((number, accessor.index()), self.blocks.len() - 1);
                self.blocks.len() - 1
            }
        };
        let count = self.blocks[block].local.len();
        let indices: Vec<u32> = match primitive.indices() {
            Some(a) => read_indices(site, &a, buffers)?,
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
        let normal = primitive.get(&Semantic::Normals).and_then(|a| Some((a.index(), a.count(), dense_target(&a)?)));
        self.primitives.push(PrimitiveRecord { block, faces, normal });
        Ok(())
    }

    /// Refuses a float attribute other than POSITION (NORMAL, TEXCOORD_n, COLOR_n, …) with a
    /// non-finite component: the faithful writer would copy it through.
    fn check_attributes(
        &mut self,
        site: Site,
        primitive: &::gltf::Primitive,
        buffers: &[Vec<u8>],
    ) -> Result<(), GltfDataError> {
        for (semantic, accessor) in primitive.attributes() {
            if semantic == Semantic::Positions
                || accessor.data_type() != DataType::F32
                || !self.checked.insert(accessor.index())
            {
                continue;
            }
            accessor::visit(&accessor, buffers, |element, bytes| {
                let bad = (0..bytes.len() / 4).map(|k| f32_at(bytes, 4 * k)).find(|v| !v.is_finite());
                match bad {
                    Some(value) => Err(GltfDataError::NonFinite {
                        mesh: site.mesh,
                        primitive: site.primitive,
                        attribute: semantic.to_string(),
                        accessor: accessor.index(),
                        element,
                        value,
                    }),
                    None => Ok(()),
                }
            })?;
        }
        Ok(())
    }

    /// Adds the vertices of a POSITION accessor, transformed to world space.
    fn add_block(
        &mut self,
        site: Site,
        accessor: usize,
        local: Vec<[f32; 3]>,
        transform: DMat4,
        target: Option<Target>,
    ) -> Result<(), GltfDataError> {
        let first = self.positions.len();
        self.positions.try_reserve(local.len()).map_err(|_| GltfDataError::AccessorTooLarge {
            accessor,
            count: local.len(),
            limit: MAX_VERTICES,
            name: "MAX_VERTICES",
        })?;
        for (element, p) in local.iter().enumerate() {
            if let Some(&value) = p.iter().find(|c| !c.is_finite()) {
                let attribute = "POSITION".to_string();
                let (mesh, primitive) = (site.mesh, site.primitive);
                return Err(GltfDataError::NonFinite { mesh, primitive, attribute, accessor, element, value });
            }
            let world = transform.transform_point3(DVec3::from_array(p.map(f64::from)));
            if let Some(&value) = world.to_array().iter().find(|c| !c.is_finite()) {
                return Err(GltfDataError::WorldOverflow {
                    mesh: site.mesh,
                    primitive: site.primitive,
                    accessor,
                    element,
                    node: site.node.unwrap_or_default(),
                    value,
                });
            }
            self.positions.push(world);
        }
        self.blocks.push(Block { accessor, mesh: site.mesh, node: site.node, first, local, transform, target });
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

/// The elements of the index accessor `accessor` of a primitive, as u32.
fn read_indices(site: Site, accessor: &::gltf::Accessor, buffers: &[Vec<u8>]) -> Result<Vec<u32>, GltfDataError> {
    let decode: fn(&[u8]) -> u32 = match (accessor.data_type(), accessor.dimensions()) {
        (DataType::U8, Dimensions::Scalar) => |b| u32::from(b[0]),
        (DataType::U16, Dimensions::Scalar) => |b| u32::from(u16::from_le_bytes([b[0], b[1]])),
        (DataType::U32, Dimensions::Scalar) => |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        _ => {
            return Err(GltfDataError::IndexType {
                mesh: site.mesh,
                primitive: site.primitive,
                accessor: accessor.index(),
                found: accessor::describe(accessor),
            });
        }
    };
    accessor::read(accessor, buffers, (3 * MAX_FACES, "3 × MAX_FACES"), decode)
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
