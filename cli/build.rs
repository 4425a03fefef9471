//! Validates the renderer's shader (`shaders/shade.wgsl`) with naga, so that a shader that does
//! not parse or validate is a build error with naga's diagnostic, and copies it to
//! `$OUT_DIR/shade.wgsl`, which `src/render/pipeline.rs` includes.

use std::path::Path;

fn main() {
    println!("cargo::rerun-if-changed=shaders");
    let out_dir = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let path = Path::new("shaders").join("shade.wgsl");
    let source = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| {
        panic!("shade.wgsl does not parse:\n{}", e.emit_to_string_with_path(&source, "shade.wgsl"))
    });
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
        .validate(&module)
        .unwrap_or_else(|e| {
            panic!("shade.wgsl does not validate:\n{}", e.emit_to_string_with_path(&source, "shade.wgsl"))
        });
    let target = Path::new(&out_dir).join("shade.wgsl");
    std::fs::write(&target, &source).unwrap_or_else(|e| panic!("cannot write {}: {e}", target.display()));
}
