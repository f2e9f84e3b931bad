//! The erected grid as a frame: will it carry its own weight, snow and wind?
//!
//! Every lamella is a chain of 3D beam elements on its own offset line,
//! joints and shear blocks are springs, the strips' erection moments and
//! torques are the initial state; the solver runs linear statics, the
//! critical load factor (buckling) and second order on that model.
//!
//! [`model`] holds the plain data a solver takes (N, mm; OpenSees' local
//! axes, so the model exports one to one); [`build`] makes that model from
//! the analysis, the profile and the kit (lamella chains with their
//! erection state, joints, shear blocks, tributary areas and weights).

pub mod build;
pub mod model;
pub mod verdict;
