//! Fabrication: every strip turned into the flat parts a laser or waterjet
//! cuts (fabrication.md).

pub mod edge_strip;
pub mod part;
pub mod slots;
pub mod stud;
pub mod washer;
