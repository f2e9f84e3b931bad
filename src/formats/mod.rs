//! File formats, apart from the working types: readers build the models
//! (network, profile, trace spec, meshes) from files; writers format a
//! finished plan; `out` is the one way files are written.

pub mod out;
pub mod read;
pub mod text;
pub mod write;
