//! Geometry every stage shares, knowing no stage and no file format:
//! smooth curves through samples ([`curve`]), NURBS evaluation ([`nurbs`]),
//! closest points of segments ([`closest`]), plane predicates on points,
//! segments and polygons ([`plane`]), eigenvectors of symmetric 3 × 3
//! matrices ([`eigen`]), the surface interface ([`surface`]) and triangle
//! meshes ([`mesh`]).

pub mod closest;
pub mod curve;
pub mod eigen;
pub mod mesh;
pub mod nurbs;
pub mod plane;
pub mod surface;
