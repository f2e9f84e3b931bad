//! Geometry shared by the stages: smooth curves through samples.

pub mod closest;
pub mod curve;
pub mod nurbs;
