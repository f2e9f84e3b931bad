//! The erected grid as a frame: will it carry its own weight, snow and wind?
//!
//! Every lamella is a chain of 3D beam elements on its own offset line,
//! joints and shear blocks tie them rigidly (releases are springs), the
//! strips' erection moments and
//! torques are the initial state; the solver runs linear statics, the
//! critical load factor (buckling) and second order on that model.
//!
//! * [`model`]: the plain data a solver takes (N, mm; OpenSees' local
//!   axes, so the model exports one to one);
//! * [`build`]: that model from the analysis, the profile and the kit
//!   (lamella chains with their erection state, joints, shear blocks,
//!   tributary areas and weights);
//! * [`loads`]: a loads file applied to it (load cases, EN 1990
//!   combinations, supports, deflection limit);
//! * [`solve`]: element matrices, assembly, the sparse Cholesky
//!   factorisation, static solves, section forces, reactions, mechanisms;
//! * [`buckling`]: the critical load factors and modes;
//! * [`second_order`]: equilibrium on the imperfect, deformed geometry;
//! * [`tension`]: statics with tension-only cables (bracing), their
//!   taut set iterated;
//! * [`bracing`]: diagonal cables on the quads: candidates, layouts, the
//!   designed layout, pretension and size;
//! * [`verdict`]: cross-section and member checks of an upright strip;
//! * [`analyse`]: every analysis of every combination, and the verdict;
//! * [`stage`]: a network under a loads file, from model to verdict;
//! * [`opensees`]: the model exported to OpenSeesPy, to check the solver.

pub mod analyse;
pub mod bracing;
pub mod buckling;
pub mod build;
pub mod loads;
pub mod model;
pub mod opensees;
pub mod second_order;
pub mod solve;
pub mod stage;
pub mod tension;
pub mod verdict;
