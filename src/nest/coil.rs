//! Coil stock cut to any length: one piece of the coil's width, its lanes
//! balanced.

use super::ctx::Ctx;
use super::lanes::{balance, SheetPlan};
use super::skyline::Placed;
use crate::error::Result;

impl<'a> Ctx<'a> {
    /// A coil cut to any length: one sheet of the coil's width, the
    /// lamellas balanced over its lanes (MULTIFIT: the shortest lane
    /// length at which [`binpack::pack`] needs no more lanes than fit
    /// across, by bisection from the longest-first greedy), the other parts
    /// after them; its length is what is used.
    pub(super) fn coil(&self) -> Result<Placed> {
        let lanes = balance(&self.item_len, self.sizes[0].lanes);
        self.place(&[SheetPlan { size: 0, lanes }])
    }
}
