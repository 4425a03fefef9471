//! Which meshes a glTF scene draws, and where: node hierarchy → (mesh, world matrix).

use glam::DMat4;

use super::GltfDataError;

/// Each mesh instance of the default scene (else the first scene; else every root node) as
/// (mesh index, world matrix in f64), depth first in node order. A file with meshes but no
/// node gives each mesh once with the identity.
pub(super) fn instances(document: &::gltf::Document) -> Result<Vec<(usize, DMat4)>, GltfDataError> {
    if document.nodes().len() == 0 {
        return Ok(document.meshes().map(|mesh| (mesh.index(), DMat4::IDENTITY)).collect());
    }
    let roots: Vec<::gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let mut child = vec![false; document.nodes().len()];
            for node in document.nodes() {
                for c in node.children() {
                    child[c.index()] = true;
                }
            }
            document.nodes().filter(|n| !child[n.index()]).collect()
        }
    };
    let mut out = Vec::new();
    for root in roots {
        visit(&root, DMat4::IDENTITY, 0, document.nodes().len(), &mut out)?;
    }
    Ok(out)
}

/// Adds the instances of `node` and its descendants; deeper than the node count means a cycle.
fn visit(
    node: &::gltf::Node,
    parent: DMat4,
    depth: usize,
    limit: usize,
    out: &mut Vec<(usize, DMat4)>,
) -> Result<(), GltfDataError> {
    if depth > limit {
        return Err(GltfDataError::NodeCycle { node: node.index() });
    }
    let local = node.transform().matrix().map(|column| column.map(f64::from));
    let world = parent * DMat4::from_cols_array_2d(&local);
    if let Some(mesh) = node.mesh() {
        out.push((mesh.index(), world));
    }
    for child in node.children() {
        visit(&child, world, depth + 1, limit, out)?;
    }
    Ok(())
}
