//! Fabrication: every strip turned into the flat parts a laser or waterjet
//! cuts (fabrication.md).

pub mod blocks;
pub mod lamella;
pub mod part;
pub mod slots;
