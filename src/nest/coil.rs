//! Coil stock: cut to any length, one piece of the coil's width with its
//! lanes balanced; every piece cut to the length its parts use.

use super::ctx::Ctx;
use super::lanes::{balance, SheetPlan};
use super::model::{placed_bbox, SheetNest};
use super::skyline::Placed;
use crate::error::Result;
use crate::fabricate::Kit;
use crate::profile::Stock;

impl Ctx<'_> {
    /// A coil cut to any length: one sheet of the coil's width, the
    /// lamellas balanced over its lanes (MULTIFIT: the shortest lane
    /// length at which [`binpack::pack`](super::binpack::pack) needs no more lanes than fit
    /// across, by bisection from the longest-first greedy), the other parts
    /// after them; its length is what is used.
    pub(super) fn coil(&self) -> Result<Placed> {
        let lanes = balance(&self.item_len, self.sizes[0].lanes);
        self.place(&[SheetPlan { size: 0, lanes }])
    }
}

/// A piece of coil `st` cut to the length its parts use (up to the last
/// part's end plus the margin `m`, in whole length steps, never longer
/// than it was), priced by the metre where the coil is.
pub(super) fn cut_to_length(s: &mut SheetNest, kit: &Kit, m: f64, st: &Stock) {
    let used = s
        .placements
        .iter()
        .map(|pl| placed_bbox(&kit.parts[pl.part], pl).2)
        .fold(m, f64::max)
        + m;
    let step = st.length_step();
    s.length_mm = s.length_mm.min((used / step * (1.0 - 1e-12)).ceil() * step);
    if let Some(per_m) = st.price_per_m {
        s.price_per_unit = Some(per_m * s.length_mm / 1000.0);
    }
}
