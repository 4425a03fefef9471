//! What an application can get wrong when it builds or drives a GPU deformer: each fault a
//! variant carrying the values at fault, as [`RigErrorKind`](crate::rig::RigErrorKind) does.

use thiserror::Error;

/// A fault in the input handed to the GPU deformer (wrapped in [`GpuError::Input`]).
///
/// [`GpuError::Input`]: super::GpuError::Input
#[derive(Debug, Error, Clone, PartialEq)]
pub enum InputError {
    #[error("the mesh has no vertices")]
    NoVertices,
    #[error("{vertices} vertices are more than the GPU path indexes")]
    TooManyVertices { vertices: usize },
    #[error("vertex {vertex} has a non-finite position")]
    PositionNotFinite { vertex: usize },
    #[error("{owners} owners for {vertices} vertices")]
    OwnerCount { owners: usize, vertices: usize },
    #[error("vertex {vertex} is owned by sweep {sweep}, but the rig has {sweeps}")]
    OwnerOutOfRange { vertex: usize, sweep: u32, sweeps: usize },
    #[error("{bindings} bindings for {vertices} vertices")]
    BindingCount { bindings: usize, vertices: usize },
    #[error("binding {binding} refers to radius cell {cell} of {cells}")]
    BindingCellOutOfRange { binding: usize, cell: u32, cells: usize },
    #[error("the rig has {cells} radius cells; the GPU engine binds to at most {max}")]
    TooManyCells { cells: usize, max: u32 },
    #[error("the falloff bands are not sorted, owned and in range")]
    BandsOutOfOrder,
    #[error("the band records are not sorted, bound and in range")]
    BandRecordsOutOfOrder,
    #[error("{indices} triangle indices is not a multiple of 3")]
    TriangleIndexCount { indices: usize },
    #[error("triangle {triangle} refers to vertex {vertex}, but the mesh has {vertices}")]
    TriangleVertexOutOfRange { triangle: usize, vertex: u32, vertices: usize },
    #[error("{instances} instances and {pose_uploads} pose uploads: each needs at least one")]
    NoInstances { instances: u32, pose_uploads: u32 },
    #[error("instance {instance} of a deformer of {instances} instances")]
    InstanceOutOfRange { instance: u32, instances: u32 },
    #[error("Jacobian normals need triangles: they start from the rest normals")]
    JacobianNormalsWithoutTriangles,
    #[error("rest tangents need triangles: tangents turn with the normals")]
    TangentsWithoutTriangles,
    #[error("{tangents} rest tangents for {vertices} vertices")]
    TangentCount { tangents: usize, vertices: u32 },
    #[error("rest tangent {index} is not finite")]
    TangentNotFinite { index: usize },
    #[error("previous positions with the application's output need two buffers (with_outputs)")]
    PreviousPositionsNeedTwoOutputs,
    #[error("the two output buffers of previous positions are one buffer; they must differ")]
    PreviousOutputIsTheOutput,
    #[error("the output buffer has usage {usage:?}; the deformer needs STORAGE | COPY_DST")]
    OutputUsage { usage: wgpu::BufferUsages },
    #[error("the output offset {offset} is not a multiple of the device's storage offset alignment {alignment}")]
    OutputOffsetMisaligned { offset: u64, alignment: u64 },
    #[error("the output buffer holds {size} bytes; the positions need {needed} from offset {offset}")]
    OutputTooSmall { size: u64, needed: u64, offset: u64 },
    #[error("the device allows {allowed} storage buffers per shader stage; binding needs {needed}")]
    TooFewStorageBuffers { allowed: u32, needed: u32 },
    #[error("{vertices} vertices in all instances are more than the normals index")]
    TooManyNormalVertices { vertices: u64 },
    #[error("a vertex has more incident triangles than one storage binding holds")]
    TriangleFanTooLarge,
    #[error("a vertex's tangent does not fit one storage binding")]
    TangentTooLarge,
    #[error("{positions} rest positions for a deformer of {vertices} vertices")]
    RestPositionCount { positions: usize, vertices: u32 },
    #[error("new falloff bands on a deformer with Jacobian normals: build a new deformer with them")]
    BandsWithJacobianNormals,
}
