//! One stock size as the nest sees it: its usable area, its lamella lanes
//! and what a sheet of it costs.

use super::binpack;
use crate::profile::StockSize;

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
    /// Its name, else `length × width` (as [`StockSize::label`]).
    pub(super) label: String,
}

impl Size {
    /// The profile's stock size `z` for an edge margin `m`, a gap
    /// (kerf + part spacing) `g` and lamellas `h` high, mm.
    pub(super) fn new(z: &StockSize, m: f64, g: f64, h: f64) -> Size {
        let (lu, wu) = (z.usable_length_mm(m), z.usable_width_mm(m));
        let length = z.length_mm.unwrap_or(f64::INFINITY);
        Size {
            length,
            width: z.width_mm,
            lu,
            wu,
            lanes: ((wu + g) / (h + g)).floor().max(0.0) as usize,
            cap: lu + g,
            cost: z.price_per_unit.unwrap_or(length * z.width_mm),
            price: z.price_per_unit,
            limit: z.max_count.map_or(usize::MAX, |n| n as usize),
            label: z.label(),
        }
    }
}

/// The indices of `sizes` by cost per usable area, ties by index.
pub(super) fn by_value(sizes: &[Size]) -> Vec<usize> {
    let mut by_value: Vec<usize> = (0..sizes.len()).collect();
    by_value.sort_by(|&a, &b| {
        let v = |s: &Size| s.cost / (s.lu * s.wu);
        v(&sizes[a]).total_cmp(&v(&sizes[b])).then(a.cmp(&b))
    });
    by_value
}

/// Whether an item fits a lane of capacity `cap` (to the bin packing's
/// tolerance).
pub(super) fn fits(item: f64, cap: f64) -> bool {
    item <= cap * (1.0 + binpack::FIT_TOLERANCE)
}
