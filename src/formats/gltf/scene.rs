//! Which meshes a glTF scene draws, and where: node hierarchy → (node, mesh, world matrix).
//!
//! The graph is measured first ([`graph::measure`]): a scene that would give more mesh
//! instances, vertices, triangles or node visits than [`crate::limits`] allow is refused
//! before any matrix is multiplied. The expansion then walks the graph with an explicit
//! stack, skipping subtrees without a mesh.

use ::gltf::mesh::{Mode, Semantic};
use ::gltf::scene::Transform;
use glam::DMat4;

use super::GltfDataError;
use super::graph::{self, Graph, Totals};
use crate::limits::{
    MAX_FACES, MAX_GLTF_EXPANSION, MAX_GLTF_INSTANCES, MAX_GLTF_NODE_INSTANCES, MAX_GLTF_UNSTORED, MAX_VERTICES,
};

/// One mesh drawn by one node (or, in a file without nodes, by none).
#[derive(Clone, Copy, Debug)]
pub(super) struct Instance {
    /// The node drawing the mesh, `None` in a file without nodes.
    pub node: Option<usize>,
    /// The mesh index.
    pub mesh: usize,
    /// The node's world matrix, in f64.
    pub world: DMat4,
}

/// Each mesh instance of the default scene (else the first scene; else every root node),
/// depth first in node order. A file with meshes but no node gives each mesh once with the
/// identity.
///
/// # Errors
///
/// A cycle or a node too deep ([`graph::measure`]); [`GltfDataError::SceneTooLarge`] for a
/// scene over a limit; [`GltfDataError::NodeTransform`] for a non-finite local transform and
/// [`GltfDataError::NodeWorldOverflow`] for a world matrix that overflows.
pub(super) fn instances(document: &::gltf::Document) -> Result<Vec<Instance>, GltfDataError> {
    let meshes: Vec<Totals> = document.meshes().map(|m| mesh_totals(&m)).collect();
    let stored = stored(document);
    if document.nodes().len() == 0 {
        let totals = meshes.iter().fold(Totals::default(), |sum, m| sum.plus(*m));
        check(totals)?;
        check_expansion(totals, stored)?;
        return Ok((0..meshes.len()).map(|mesh| Instance { node: None, mesh, world: DMat4::IDENTITY }).collect());
    }
    let graph = Graph {
        children: document.nodes().map(|n| n.children().map(|c| c.index()).collect()).collect(),
        mesh: document.nodes().map(|n| n.mesh().map(|m| m.index())).collect(),
    };
    let roots = roots(document, &graph);
    let totals = graph::measure(&graph, &roots, &meshes)?;
    let scene = roots.iter().fold(Totals::default(), |sum, &r| sum.plus(totals[r]));
    check(scene)?;
    check_expansion(scene, stored)?;
    let locals = document.nodes().map(|n| local_matrix(&n)).collect::<Vec<_>>();
    let mut out = Vec::new();
    let mut stack: Vec<(usize, DMat4)> = roots.iter().rev().map(|&r| (r, DMat4::IDENTITY)).collect();
    while let Some((node, parent)) = stack.pop() {
        if totals[node].instances == 0 {
            continue;
        }
        let world = parent * locals[node].clone()?;
        if let Some(&value) = world.to_cols_array().iter().find(|v| !v.is_finite()) {
            return Err(GltfDataError::NodeWorldOverflow { node, value });
        }
        if let Some(mesh) = graph.mesh[node] {
            out.push(Instance { node: Some(node), mesh, world });
        }
        stack.extend(graph.children[node].iter().rev().map(|&c| (c, world)));
    }
    Ok(out)
}

/// The root nodes: those of the default scene, else of the first scene, else every node that
/// is no node's child.
fn roots(document: &::gltf::Document, graph: &Graph) -> Vec<usize> {
    if let Some(scene) = document.default_scene().or_else(|| document.scenes().next()) {
        return scene.nodes().map(|n| n.index()).collect();
    }
    let mut child = vec![false; graph.children.len()];
    for &c in graph.children.iter().flatten() {
        child[c] = true;
    }
    (0..child.len()).filter(|&n| !child[n]).collect()
}

/// Refuses totals over the limits on instances, vertices, triangles and node visits.
fn check(totals: Totals) -> Result<(), GltfDataError> {
    let limits = [
        ("mesh instances", totals.instances, MAX_GLTF_INSTANCES, "MAX_GLTF_INSTANCES"),
        ("vertices", totals.vertices, MAX_VERTICES, "MAX_VERTICES"),
        ("triangles", totals.triangles, MAX_FACES, "MAX_FACES"),
        ("node instances", totals.visits, MAX_GLTF_NODE_INSTANCES, "MAX_GLTF_NODE_INSTANCES"),
    ];
    match limits.into_iter().find(|(_, count, limit, _)| count > limit) {
        Some((what, count, limit, name)) => Err(GltfDataError::SceneTooLarge { what, count, limit, name }),
        None => Ok(()),
    }
}

/// The vertices and triangles the file's bytes hold: over every distinct POSITION accessor
/// and every primitive, the elements backed by a buffer view (else only the sparse ones).
fn stored(document: &::gltf::Document) -> Totals {
    let backed = |accessor: &::gltf::Accessor| match accessor.view() {
        Some(_) => accessor.count(),
        None => accessor.sparse().map_or(0, |sparse| sparse.count()),
    };
    let mut positions: Vec<usize> = Vec::new();
    let mut totals = Totals::default();
    for primitive in document.meshes().flat_map(|m| m.primitives().collect::<Vec<_>>()) {
        let Some(accessor) = primitive.get(&Semantic::Positions) else { continue };
        if !positions.contains(&accessor.index()) {
            positions.push(accessor.index());
            totals.vertices = totals.vertices.saturating_add(backed(&accessor));
        }
        let corners = primitive.indices().map_or_else(|| backed(&accessor), |a| backed(&a));
        totals.triangles = totals.triangles.saturating_add(corners / 3);
    }
    totals
}

/// Refuses a scene that gives more than [`MAX_GLTF_EXPANSION`] times the vertices or triangles
/// its file stores, beyond [`MAX_GLTF_UNSTORED`].
fn check_expansion(scene: Totals, stored: Totals) -> Result<(), GltfDataError> {
    for (what, count, held) in
        [("vertices", scene.vertices, stored.vertices), ("triangles", scene.triangles, stored.triangles)]
    {
        if count > MAX_GLTF_UNSTORED.max(held.saturating_mul(MAX_GLTF_EXPANSION)) {
            return Err(GltfDataError::SceneExpands {
                what,
                count,
                stored: held,
                expansion: MAX_GLTF_EXPANSION,
                unstored: MAX_GLTF_UNSTORED,
            });
        }
    }
    Ok(())
}

/// What one instance of `mesh` gives, from its accessors' declared counts: the vertices of
/// each distinct POSITION accessor and the triangles of each primitive.
fn mesh_totals(mesh: &::gltf::Mesh) -> Totals {
    let mut positions: Vec<usize> = Vec::new();
    let mut totals = Totals { instances: 1, ..Totals::default() };
    for primitive in mesh.primitives() {
        let Some(accessor) = primitive.get(&Semantic::Positions) else { continue };
        if !positions.contains(&accessor.index()) {
            positions.push(accessor.index());
            totals.vertices = totals.vertices.saturating_add(accessor.count());
        }
        let n = primitive.indices().map_or(accessor.count(), |a| a.count());
        let triangles = match primitive.mode() {
            Mode::Triangles => n / 3,
            Mode::TriangleStrip | Mode::TriangleFan => n.saturating_sub(2),
            _ => 0,
        };
        totals.triangles = totals.triangles.saturating_add(triangles);
    }
    totals
}

/// The local matrix of `node` in f64, or the error naming its non-finite property.
fn local_matrix(node: &::gltf::Node) -> Result<DMat4, GltfDataError> {
    let bad = |property, values: &[f32]| {
        let value = *values.iter().find(|v| !v.is_finite())?;
        Some(GltfDataError::NodeTransform { node: node.index(), property, value })
    };
    let error = match node.transform() {
        Transform::Matrix { matrix } => bad("matrix", matrix.as_flattened()),
        Transform::Decomposed { translation, rotation, scale } => {
            bad("translation", &translation).or_else(|| bad("rotation", &rotation)).or_else(|| bad("scale", &scale))
        }
    };
    if let Some(error) = error {
        return Err(error);
    }
    let local = node.transform().matrix().map(|column| column.map(f64::from));
    Ok(DMat4::from_cols_array_2d(&local))
}
