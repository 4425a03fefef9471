//! Which property of a PLY face element lists its vertices, for both readers ([`super::direct`]
//! and [`super::read`]).

use ply_rs_bw::ply::{ElementDef, PropertyType, ScalarType};

/// The names of the face index list, in order of preference.
const INDEX_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// The place among the face element's properties of its vertex index list: the first of
/// [`INDEX_LISTS`] that is a list of integers.
pub(crate) fn index_list(face: &ElementDef) -> Option<usize> {
    INDEX_LISTS.into_iter().find_map(|name| {
        let (place, _, def) = face.properties.get_full(name)?;
        match &def.data_type {
            PropertyType::List(_, t) if !matches!(t, ScalarType::Float | ScalarType::Double) => Some(place),
            _ => None,
        }
    })
}
