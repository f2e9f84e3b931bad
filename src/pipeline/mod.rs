//! The pipeline: every stage from the input files to the kit.

pub mod build;
