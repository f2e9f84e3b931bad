//! Geometry shared by the stages, free of file formats and of the network:
//! smooth curves through samples ([`curve`]), NURBS evaluation ([`nurbs`]),
//! closest points of segments ([`closest`]).

pub mod closest;
pub mod curve;
pub mod nurbs;
