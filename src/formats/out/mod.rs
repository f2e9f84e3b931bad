//! Writing files: staged into a folder beside the output and moved into
//! place once complete, big files past the page cache.

pub mod direct;
pub mod staging;
