//! Small GLB files with hostile node graphs: one triangle drawn by the leaves of a long parent
//! chain, or of a graph that shares both children at every level (each level doubles the
//! instances).

/// A GLB of one triangle mesh whose scene holds node 0 of `nodes` (JSON objects).
pub fn triangle_glb(nodes: &[String]) -> Vec<u8> {
    let mut blob: Vec<u8> =
        [0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|c| c.to_le_bytes()).collect();
    let json = format!(
        concat!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{}],"#,
            r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],"#,
            r#""buffers":[{{"byteLength":36}}],"bufferViews":[{{"buffer":0,"byteLength":36}}],"#,
            r#""accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","#,
            r#""min":[0,0,0],"max":[1,1,0]}}]}}"#
        ),
        nodes.join(",")
    );
    let mut json = json.into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    blob.resize(blob.len().next_multiple_of(4), 0);
    let length = 12 + 8 + json.len() + 8 + blob.len();
    let mut glb = Vec::with_capacity(length);
    glb.extend_from_slice(b"glTF");
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&(length as u32).to_le_bytes());
    glb.extend_from_slice(&(json.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&(blob.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&blob);
    glb
}

/// `depth` nodes, each the parent of the next, the last drawing the mesh.
pub fn chain(depth: usize) -> Vec<String> {
    let mut nodes: Vec<String> = (1..depth).map(|i| format!(r#"{{"children":[{i}]}}"#)).collect();
    nodes.push(r#"{"mesh":0}"#.to_string());
    nodes
}

/// A root over `depth` levels of two nodes, each node the parent of both nodes of the next
/// level, the last level drawing the mesh: 2^depth instances from 2·depth + 1 nodes.
pub fn doubling(depth: usize) -> Vec<String> {
    let mut nodes = vec![r#"{"children":[1,2]}"#.to_string()];
    for level in 1..depth {
        let (a, b) = (2 * level + 1, 2 * level + 2);
        nodes.push(format!(r#"{{"children":[{a},{b}]}}"#));
        nodes.push(format!(r#"{{"children":[{a},{b}]}}"#));
    }
    nodes.push(r#"{"mesh":0}"#.to_string());
    nodes.push(r#"{"mesh":0}"#.to_string());
    nodes
}
