//! Emit: the files a workshop cuts and buys from (issue 10). Plain data in
//! (a plan with parts and sheets, the kit, the nest), files out:
//!
//! * [`drawing`]: every placed part in sheet coordinates, by operation;
//! * [`dxf_out`], [`svg_out`]: one cutting file per sheet in each format;
//! * [`takeoff`]: parts, stock, hardware and totals as CSV and JSON;
//! * [`outdir`]: staging beside the output directory, moved into place
//!   only once complete;
//! * [`build`]: `lamella build`, every stage from the network to the files.

pub mod build;
pub mod drawing;
pub mod dxf_out;
pub mod outdir;
pub mod svg_out;
pub mod takeoff;
