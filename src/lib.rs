//! lamella: fabrication CAM for gridshells built from flat, straight strips
//! laid along the asymptotic curves of a minimal surface.
//!
//! Stages (see ARCHITECTURE.md), one folder each:
//! * [`design`]: analytic minimal surfaces, tracing, clips, periodic unfolding
//!   → a network file;
//! * [`io`]: file formats only (network files in, plan.json out, profiles,
//!   trace specs) → [`network::Network`] in mm, validated;
//! * [`geom`]: smooth curves through samples, smoothed to their precision;
//! * [`analysis`]: nodes ([`analysis::topology`]), Darboux frames and
//!   curvatures ([`analysis::strip`], [`analysis::normal_field`]), lamella
//!   lines and the finished model ([`analysis::model`]);
//! * [`check`]: the elastic check of every lamella against a [`profile`];
//! * [`fabricate`]: flat parts per profile; [`nest`]: parts onto stock;
//! * [`emit`]: cutting files, takeoff, safe output; `lamella build`.

#![warn(missing_docs)]

pub mod analysis;
pub mod check;
pub mod design;
pub mod emit;
pub mod error;
pub mod fabricate;
pub mod flat;
pub mod geom;
pub mod io;
pub mod mesh;
pub mod minimal;
pub mod nest;
pub mod network;
pub mod profile;

/// Every program built on lamella (the CLI, the tests and the benchmarks)
/// allocates through mimalloc: writing a big kit's files makes and frees
/// hundreds of thousands of small buffers a second, which glibc's
/// allocator served at about a tenth of the build's CPU time.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

pub use analysis::{analyze, Analysis, AnalysisOptions};
pub use error::{Error, Result};
pub use network::{Family, Network};
