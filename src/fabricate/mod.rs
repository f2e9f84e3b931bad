//! Fabrication: every strip turned into the flat parts a laser or waterjet
//! cuts (fabrication.md).

pub mod slots;
pub mod part;
pub mod blocks;
