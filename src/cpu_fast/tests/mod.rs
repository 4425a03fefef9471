//! The fast CPU path against the twins and the reference: bind, deform, bands, and the fused
//! deform with Jacobian normals on every instruction set this CPU has.

mod cpu_fast;
mod cpu_fast_normals;
