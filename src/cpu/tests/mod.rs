//! The f32 twins against the f64 reference: binding, round trips through Eq. 2, properties.

mod binding;
mod properties;
mod round_trip;
