//! lamella: fabrication CAM for gridshells built from flat, straight strips
//! laid along the asymptotic curves of a minimal surface.
//!
//! Stages (see ARCHITECTURE.md): [`io`] reads a network into a validated
//! [`network::Network`] in mm; [`curve`] interpolates every curve smoothly;
//! [`topology`] finds the nodes; [`strip`] computes Darboux frames,
//! curvatures and node-to-node lengths; [`analyze`] runs them in order;
//! [`model`] gathers the finished model (lamella lines, summary, check);
//! [`io::plan`] writes it as plan.json. [`synth`] makes networks from closed forms
//! for tests, benchmarks and samples.

pub mod analyze;
pub mod check;
pub mod curve;
pub mod design;
pub mod error;
pub mod io;
pub mod model;
pub mod network;
pub mod normal_field;
pub mod periodic;
pub mod profile;
pub mod strip;
pub mod surface;
pub mod synth;
pub mod topology;
pub mod trace;

pub use analyze::{analyze, Analysis, AnalysisOptions};
pub use error::{Error, Result};
pub use network::{Family, Network};
