//! Geometry shared by the stages: smooth curves through samples.

pub mod curve;
