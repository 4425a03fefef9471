//! The WGSL kernels without a device: each parses and validates with naga, its workgroup size
//! is the Rust constant, and every buffer struct it shares with Rust has the same size and
//! member offsets as the `#[repr(C)]` struct in `src/layout.rs`.

use std::mem::{offset_of, size_of};

use sweepffd::coeffs::{
    BAND_FLAG, BandFlag, BandRecord, BindSegment, CELL_BITS, CELL_GROUP, CELL_MASK, CellCoeffs, CellOrderParams,
    DispatchParams, GpuBinding, INSTANCES_PER_INVOCATION, InstanceParams, Joint, KEEPS_REST, PARAMETER_BITS,
    PARAMETER_MAX, PARAMETER_SCALE, SkinInfluence, SweepInfo, UNIFORM_CELL_CAPACITY, UNOWNED, WORKGROUP_SIZE,
};
use sweepffd::gpu::shaders;
use sweepffd::normals::{FAN_CLOSE, FAN_END, FAN_INDEX, FAN_START};

/// (struct name, size, [(member, offset)]) of a Rust buffer struct.
type RustLayout = (&'static str, usize, Vec<(&'static str, usize)>);

macro_rules! layout {
    ($ty:ident { $($field:ident),* $(,)? }) => {
        (stringify!($ty), size_of::<$ty>(), vec![$((stringify!($field), offset_of!($ty, $field))),*])
    };
}

fn rust_layouts() -> Vec<RustLayout> {
    vec![
        layout!(CellCoeffs { radius, curve, rotation }),
        layout!(SweepInfo { first_segment, segment_count, first_cell, samples }),
        layout!(BindSegment { origin, normal, e_low, e_high, e9, t0, t1, degree }),
        layout!(GpuBinding { cell, s, phi, d, h }),
        layout!(BandRecord { vertex, weight, cell, s_phi }),
        layout!(BandFlag { vertex, x, y, z }),
        layout!(DispatchParams { vertex_count, first_vertex, window_split, _pad }),
        layout!(CellOrderParams {
            vertex_count,
            cell_count,
            slot_count,
            block_size,
            max_workgroups,
            dispatch_count,
            _pad0,
            _pad1
        }),
        layout!(InstanceParams {
            vertex_count,
            cells_per_instance,
            instance_stride,
            first_instance,
            instance_count,
            _pad0,
            _pad1,
            _pad2
        }),
        layout!(SkinInfluence { joints, weights }),
        layout!(Joint { rows }),
    ]
}

fn parse(name: &str, source: &str) -> naga::Module {
    naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)))
}

#[test]
fn every_kernel_validates_with_naga() {
    for (name, source, entry) in shaders::ALL {
        let module = parse(name, source);
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        assert!(module.entry_points.iter().any(|e| e.name == entry), "{name}: no entry point {entry}");
    }
}

#[test]
fn workgroup_size_is_the_rust_constant() {
    for (name, source, _) in shaders::ALL {
        let module = parse(name, source);
        for entry in &module.entry_points {
            assert_eq!(entry.workgroup_size, [WORKGROUP_SIZE, 1, 1], "{name}: {}", entry.name);
        }
    }
}

#[test]
fn shared_structs_have_the_rust_layout() {
    let layouts = rust_layouts();
    let mut checked = 0;
    for (name, source, _) in shaders::ALL {
        let module = parse(name, source);
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).unwrap();
        for (handle, ty) in module.types.iter() {
            let naga::TypeInner::Struct { members, .. } = &ty.inner else {
                continue;
            };
            let Some(type_name) = ty.name.as_deref() else {
                continue;
            };
            let Some((_, size, fields)) = layouts.iter().find(|(n, _, _)| *n == type_name) else {
                continue;
            };
            assert_eq!(layouter[handle].size as usize, *size, "{name}: size of {type_name}");
            let wgsl: Vec<(&str, usize)> =
                members.iter().map(|m| (m.name.as_deref().unwrap_or("?"), m.offset as usize)).collect();
            assert_eq!(&wgsl, fields, "{name}: members of {type_name}");
            checked += 1;
        }
    }
    // layout.wgsl declares all eleven structs and is part of every kernel.
    assert_eq!(checked, 11 * shaders::ALL.len());
}

/// The value of the `u32` constant `name` in a kernel, if it declares it.
fn u32_constant(module: &naga::Module, name: &str) -> Option<u32> {
    let (_, constant) = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name))?;
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::U32(value)) => Some(value),
        _ => None,
    }
}

/// The value of the `f32` constant `name` in a kernel, if it declares it.
fn f32_constant(module: &naga::Module, name: &str) -> Option<f32> {
    let (_, constant) = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name))?;
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::F32(value)) => Some(value),
        _ => None,
    }
}

#[test]
fn shared_constants_have_the_rust_values() {
    for (name, source, _) in shaders::ALL {
        let module = parse(name, source);
        assert_eq!(u32_constant(&module, "UNIFORM_CELL_CAPACITY"), Some(UNIFORM_CELL_CAPACITY), "{name}");
        assert_eq!(u32_constant(&module, "UNOWNED"), Some(UNOWNED), "{name}");
        assert_eq!(u32_constant(&module, "BAND_FLAG"), Some(BAND_FLAG), "{name}");
        assert_eq!(u32_constant(&module, "KEEPS_REST"), Some(KEEPS_REST), "{name}");
        let per_invocation = u32_constant(&module, "INSTANCES_PER_INVOCATION");
        assert_eq!(per_invocation, Some(INSTANCES_PER_INVOCATION), "{name}");
        assert_eq!(u32_constant(&module, "CELL_GROUP"), Some(CELL_GROUP), "{name}");
        assert_eq!(u32_constant(&module, "CELL_BITS"), Some(CELL_BITS), "{name}");
        assert_eq!(u32_constant(&module, "CELL_MASK"), Some(CELL_MASK), "{name}");
        assert_eq!(u32_constant(&module, "LOW_BITS"), Some(PARAMETER_BITS - 16), "{name}");
        assert_eq!(u32_constant(&module, "LOW_MASK"), Some((1 << (PARAMETER_BITS - 16)) - 1), "{name}");
        assert_eq!(f32_constant(&module, "PARAMETER_MAX"), Some(PARAMETER_MAX as f32), "{name}");
        assert_eq!(f32_constant(&module, "PARAMETER_SCALE"), Some(PARAMETER_SCALE), "{name}");
    }
    let order = parse("cell_order", shaders::CELL_ORDER);
    assert_eq!(u32_constant(&order, "SCAN_RUN"), Some(sweepffd::coeffs::SCAN_RUN));
    for source in [shaders::NORMALS_ONE_WINDOW, shaders::NORMALS_TWO_WINDOWS] {
        let normals = parse("normals", source);
        assert_eq!(u32_constant(&normals, "FAN_START"), Some(FAN_START));
        assert_eq!(u32_constant(&normals, "FAN_CLOSE"), Some(FAN_CLOSE));
        assert_eq!(u32_constant(&normals, "FAN_END"), Some(FAN_END));
        assert_eq!(u32_constant(&normals, "FAN_INDEX"), Some(FAN_INDEX));
    }
}
