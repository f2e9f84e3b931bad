//! Fabrication: every strip turned into the flat parts a laser or waterjet
//! cuts (fabrication.md).

pub mod font;
pub mod invariants;
pub mod label;
pub mod part;
pub mod slots;
