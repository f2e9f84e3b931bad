//! Nesting the kit onto stock: [`binpack`] assigns long lamella parts to
//! lanes along a sheet (one-dimensional bin packing).

pub mod binpack;
