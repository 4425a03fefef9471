//! Composes each WGSL kernel from the files in `shaders/` and validates it with naga, so a
//! kernel that does not parse or validate is a build error with naga's diagnostic. The composed
//! sources land in `$OUT_DIR/<kernel>.wgsl`, which `src/gpu/shaders.rs` includes.

use std::path::Path;

/// Each kernel and the files it is composed of, shared files first, its entry point last.
const KERNELS: &[(&str, &[&str])] = &[
    ("bind", &["layout.wgsl", "cells_storage.wgsl", "sweep_eval.wgsl", "angle.wgsl", "bind.wgsl"]),
    ("deform_uniform", &["layout.wgsl", "cells_uniform.wgsl", "sweep_eval.wgsl", "deform.wgsl", "deform_groups.wgsl"]),
    ("deform_storage", &["layout.wgsl", "cells_storage.wgsl", "sweep_eval.wgsl", "deform.wgsl", "deform_groups.wgsl"]),
    (
        "deform_normals_uniform",
        &[
            "layout.wgsl",
            "cells_uniform.wgsl",
            "sweep_eval.wgsl",
            "jacobian.wgsl",
            "deform_normals.wgsl",
            "deform_normals_groups.wgsl",
        ],
    ),
    (
        "deform_normals_storage",
        &[
            "layout.wgsl",
            "cells_storage.wgsl",
            "sweep_eval.wgsl",
            "jacobian.wgsl",
            "deform_normals.wgsl",
            "deform_normals_groups.wgsl",
        ],
    ),
    (
        "normal_coords_uniform",
        &["layout.wgsl", "cells_uniform.wgsl", "sweep_eval.wgsl", "jacobian.wgsl", "normal_coords.wgsl"],
    ),
    (
        "normal_coords_storage",
        &["layout.wgsl", "cells_storage.wgsl", "sweep_eval.wgsl", "jacobian.wgsl", "normal_coords.wgsl"],
    ),
    (
        "band_uniform",
        &["layout.wgsl", "cells_uniform.wgsl", "rest_cells_uniform.wgsl", "sweep_eval.wgsl", "blend.wgsl", "band.wgsl"],
    ),
    (
        "band_storage",
        &["layout.wgsl", "cells_storage.wgsl", "rest_cells_storage.wgsl", "sweep_eval.wgsl", "blend.wgsl", "band.wgsl"],
    ),
    ("band_pack", &["layout.wgsl", "band_pack.wgsl"]),
    ("cell_order", &["layout.wgsl", "cell_order.wgsl"]),
    ("band_flags", &["layout.wgsl", "band_flags.wgsl"]),
    ("normals_one_window", &["layout.wgsl", "normals.wgsl", "positions_one_window.wgsl"]),
    ("normals_two_windows", &["layout.wgsl", "normals.wgsl", "positions_two_windows.wgsl"]),
    ("bounds", &["layout.wgsl", "bounds.wgsl"]),
    ("bounds_finalize", &["layout.wgsl", "bounds_finalize.wgsl"]),
    ("copy", &["layout.wgsl", "copy.wgsl"]),
    ("copy_wide", &["layout.wgsl", "copy_wide.wgsl"]),
    ("skinning", &["layout.wgsl", "skinning.wgsl"]),
    ("tangents", &["layout.wgsl", "tangents.wgsl"]),
    ("jacobian_probe", &["layout.wgsl", "jacobian_probe.wgsl"]),
];

fn main() {
    println!("cargo::rerun-if-changed=shaders");
    let out_dir = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    for (kernel, files) in KERNELS {
        let mut source = String::new();
        for file in *files {
            let path = Path::new("shaders").join(file);
            let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
            source.push_str(&format!("// ---- shaders/{file}\n"));
            source.push_str(&text);
            source.push('\n');
        }
        validate(kernel, &source);
        let target = Path::new(&out_dir).join(format!("{kernel}.wgsl"));
        std::fs::write(&target, &source).unwrap_or_else(|e| panic!("cannot write {}: {e}", target.display()));
    }
}

fn validate(kernel: &str, source: &str) {
    let name = format!("{kernel}.wgsl (composed)");
    let module = naga::front::wgsl::parse_str(source).unwrap_or_else(|e| {
        panic!("WGSL kernel {kernel} does not parse:\n{}", e.emit_to_string_with_path(source, &name))
    });
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
        .validate(&module)
        .unwrap_or_else(|e| {
            panic!("WGSL kernel {kernel} does not validate:\n{}", e.emit_to_string_with_path(source, &name))
        });
}
