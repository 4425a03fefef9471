//! Reading an accessor's elements with every offset, stride and count checked against the
//! bytes present, dense or sparse, without the `gltf` crate's readers (which index slices
//! unchecked and panic on component types they do not expect).
//!
//! Element `i` of a dense accessor is the `size` bytes at `offset + i · stride` of its buffer
//! view (stride: the view's `byteStride`, else `size`); an accessor without a buffer view is
//! all zeros. A sparse accessor then replaces the elements its strictly increasing indices
//! name with its values. No allocation is sized by a count before the count is checked
//! against the bytes that hold the elements or against a limit.

use ::gltf::accessor::{DataType, Dimensions};

use super::GltfDataError;

/// Zero bytes standing for the elements of an accessor without a buffer view (the largest
/// element is a MAT4 of f32: 64 bytes).
const ZEROS: [u8; 64] = [0; 64];

/// The elements of `accessor`, each decoded from its bytes by `decode`, after checking that
/// it has at most `limit` elements (`name`: the limit's name in [`crate::limits`]).
///
/// # Errors
///
/// [`GltfDataError::AccessorTooLarge`], or an error of [`visit`]; a vector that cannot be
/// reserved is [`GltfDataError::AccessorTooLarge`] too.
pub(super) fn read<T>(
    accessor: &::gltf::Accessor,
    buffers: &[Vec<u8>],
    (limit, name): (usize, &'static str),
    decode: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, GltfDataError> {
    let too_large =
        || GltfDataError::AccessorTooLarge { accessor: accessor.index(), count: accessor.count(), limit, name };
    if accessor.count() > limit {
        return Err(too_large());
    }
    // Check every bound before allocating.
    visit(accessor, buffers, |_, _| Ok(()))?;
    let mut out = Vec::new();
    out.try_reserve_exact(accessor.count()).map_err(|_| too_large())?;
    visit(accessor, buffers, |i, bytes| {
        match out.get_mut(i) {
            Some(slot) => *slot = decode(bytes),
            None => out.push(decode(bytes)),
        }
        Ok(())
    })?;
    Ok(out)
}

/// Calls `f(i, bytes)` for each element `i` of `accessor` in order, then, for a sparse
/// accessor, for each substituted element with its new bytes.
///
/// # Errors
///
/// [`GltfDataError::AccessorOutOfBounds`] when an element lies past its buffer view or a view
/// past its buffer; [`GltfDataError::AccessorLayout`] for a stride shorter than an element,
/// or sparse indices that do not strictly increase or reach past the count; any error of `f`.
pub(super) fn visit(
    accessor: &::gltf::Accessor,
    buffers: &[Vec<u8>],
    mut f: impl FnMut(usize, &[u8]) -> Result<(), GltfDataError>,
) -> Result<(), GltfDataError> {
    let (index, count, size) = (accessor.index(), accessor.count(), accessor.size());
    let layout = |reason: String| GltfDataError::AccessorLayout { accessor: index, reason };
    match accessor.view() {
        Some(view) => {
            let stride = view.stride().unwrap_or(size);
            if stride < size {
                return Err(layout(format!(
                    "its buffer view's byteStride {stride} is less than its element size {size}"
                )));
            }
            let data = view_bytes(index, &view, buffers)?;
            let at = accessor.offset();
            within(index, "its data", span(at, stride, count, size), data.len(), view.index())?;
            for i in 0..count {
                f(i, &data[at + i * stride..][..size])?;
            }
        }
        None => {
            for i in 0..count {
                f(i, &ZEROS[..size.min(ZEROS.len())])?;
            }
        }
    }
    let Some(sparse) = accessor.sparse() else { return Ok(()) };
    let n = sparse.count();
    if n > count {
        return Err(layout(format!("its sparse count {n} is more than its count {count}")));
    }
    let indices = sparse.indices();
    let index_size = indices.index_type().size();
    let index_view = indices.view();
    let index_data = view_bytes(index, &index_view, buffers)?;
    let index_at = indices.offset();
    within(
        index,
        "its sparse indices",
        span(index_at, index_size, n, index_size),
        index_data.len(),
        index_view.index(),
    )?;
    let values = sparse.values();
    let value_view = values.view();
    let value_data = view_bytes(index, &value_view, buffers)?;
    let value_at = values.offset();
    within(index, "its sparse values", span(value_at, size, n, size), value_data.len(), value_view.index())?;
    let mut previous = None;
    for k in 0..n {
        let bytes = &index_data[index_at + k * index_size..][..index_size];
        let target = bytes.iter().rev().fold(0usize, |v, &b| (v << 8) | usize::from(b));
        if target >= count || previous.is_some_and(|p| target <= p) {
            return Err(layout(format!(
                "sparse index {k} is {target}: sparse indices must increase strictly and stay below the count {count}"
            )));
        }
        previous = Some(target);
        f(target, &value_data[value_at + k * size..][..size])?;
    }
    Ok(())
}

/// The bytes of `view` in its buffer.
fn view_bytes<'b>(
    accessor: usize,
    view: &::gltf::buffer::View,
    buffers: &'b [Vec<u8>],
) -> Result<&'b [u8], GltfDataError> {
    let buffer = view.buffer().index();
    let data = buffers.get(buffer).map_or(&[][..], Vec::as_slice);
    let end = view.offset().saturating_add(view.length());
    data.get(view.offset()..end).ok_or_else(|| GltfDataError::AccessorOutOfBounds {
        accessor,
        what: "its buffer view",
        needed: end,
        holder: format!("buffer {buffer}"),
        available: data.len(),
    })
}

/// Bytes from the view's start to the end of the last of `count` elements of `size` bytes
/// spaced `stride` apart from `at`, saturating.
fn span(at: usize, stride: usize, count: usize, size: usize) -> usize {
    match count {
        0 => 0,
        _ => at.saturating_add(stride.saturating_mul(count - 1)).saturating_add(size),
    }
}

/// Refuses a span longer than the view.
fn within(
    accessor: usize,
    what: &'static str,
    needed: usize,
    available: usize,
    view: usize,
) -> Result<(), GltfDataError> {
    if needed > available {
        return Err(GltfDataError::AccessorOutOfBounds {
            accessor,
            what,
            needed,
            holder: format!("buffer view {view}"),
            available,
        });
    }
    Ok(())
}

/// The accessor's component type and type as the glTF spec spells them, e.g. `FLOAT VEC3`.
pub(super) fn describe(accessor: &::gltf::Accessor) -> String {
    let component = match accessor.data_type() {
        DataType::I8 => "BYTE",
        DataType::U8 => "UNSIGNED_BYTE",
        DataType::I16 => "SHORT",
        DataType::U16 => "UNSIGNED_SHORT",
        DataType::U32 => "UNSIGNED_INT",
        DataType::F32 => "FLOAT",
    };
    let kind = match accessor.dimensions() {
        Dimensions::Scalar => "SCALAR",
        Dimensions::Vec2 => "VEC2",
        Dimensions::Vec3 => "VEC3",
        Dimensions::Vec4 => "VEC4",
        Dimensions::Mat2 => "MAT2",
        Dimensions::Mat3 => "MAT3",
        Dimensions::Mat4 => "MAT4",
    };
    format!("{component} {kind}")
}

/// A little-endian f32 at `at` of `bytes`.
pub(super) fn f32_at(bytes: &[u8], at: usize) -> f32 {
    f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}
