//! Checks on the JSON document for what the `gltf` crate (1.4) would panic on while
//! validating it, made before the crate sees the document.
//!
//! Its validation indexes `accessors` with a primitive's POSITION index unchecked
//! (`gltf-json` `mesh.rs`, `primitive_validate_hook`). Everything else it validates is
//! bounds-checked. The node graph is not walked recursively by the crate (children are
//! validated as plain indices), so deep hierarchies need no check here.

use serde_json::Value;

/// Refuses a primitive whose POSITION names an accessor past the end of `accessors`.
///
/// # Errors
///
/// A one-line reason naming the mesh, primitive and index.
pub(super) fn check(json: &Value) -> Result<(), String> {
    let accessors = json.get("accessors").and_then(Value::as_array).map_or(0, Vec::len);
    let meshes = json.get("meshes").and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
    for (m, mesh) in meshes.iter().enumerate() {
        let primitives = mesh.get("primitives").and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
        for (p, primitive) in primitives.iter().enumerate() {
            let position = primitive.pointer("/attributes/POSITION").and_then(Value::as_u64);
            if let Some(index) = position.filter(|&i| i >= accessors as u64) {
                return Err(format!(
                    "mesh {m} primitive {p}: POSITION is accessor {index} but the file has {accessors} accessors"
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_position_past_the_accessors_is_refused() {
        let json = serde_json::json!({"accessors": [{}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}, {"attributes": {"POSITION": 1}}]}]});
        assert_eq!(
            check(&json).unwrap_err(),
            "mesh 0 primitive 1: POSITION is accessor 1 but the file has 1 accessors"
        );
        assert_eq!(check(&serde_json::json!({"meshes": 3})), Ok(()));
    }
}
