//! One stock size as the nest sees it: its usable area, its lamella lanes
//! and what a sheet of it costs.

use super::binpack;

/// One stock size as the nest sees it.
#[derive(Debug, Clone)]
pub(super) struct Size {
    /// Full length (infinite for a coil cut to any length) and width, mm.
    pub(super) length: f64,
    pub(super) width: f64,
    /// Usable length and width (less the margins), mm.
    pub(super) lu: f64,
    pub(super) wu: f64,
    /// Lamella lanes across it.
    pub(super) lanes: usize,
    /// Lane capacity for the bin packing: usable length + one gap.
    pub(super) cap: f64,
    /// What a sheet costs: its price, else its area (mm²).
    pub(super) cost: f64,
    /// The profile's price of one, if any.
    pub(super) price: Option<f64>,
    /// Sheets of it at most.
    pub(super) limit: usize,
    pub(super) label: String,
}

/// Whether an item fits a lane of capacity `cap` (to the bin packing's
/// tolerance).
pub(super) fn fits(item: f64, cap: f64) -> bool {
    item <= cap * (1.0 + binpack::FIT_TOLERANCE)
}
