//! The stock sizes chosen by cost: the cheapest nest over each size as the
//! first choice, its tail sheets repacked onto other sizes while that makes
//! it cheaper.

use super::binpack;
use super::ctx::Ctx;
use super::lanes::SheetPlan;
use super::model::SheetNest;
use super::skyline::Placed;
use super::stock::fits;
use crate::error::{Error, Result};

/// Rounds of tail improvement at most.
const TAIL_ROUNDS: usize = 8;

impl Ctx<'_> {
    /// The cheapest full nest over the sheet sizes: for each size as the
    /// first choice (best value first), the lane plan of [`Ctx::assign`],
    /// improved by [`Ctx::tail_variants`] while the whole nest gets
    /// cheaper, then `finish`ed (the passes by true outline); ties go to
    /// fewer sheets, then the earlier candidate.
    pub(super) fn sheets(&self, finish: &dyn Fn(&mut Vec<SheetNest>)) -> Result<Placed> {
        let all: Vec<usize> = (0..self.items.len()).collect();
        let total =
            |sheets: &[SheetNest]| -> f64 { sheets.iter().map(|s| self.sizes[s.size].cost).sum() };
        let better = |a: &Placed, b: &Placed| {
            let (ca, cb) = (total(&a.0), total(&b.0));
            ca < cb * (1.0 - 1e-12) || (ca <= cb * (1.0 + 1e-12) && a.0.len() < b.0.len())
        };
        let mut best: Option<Placed> = None;
        let mut first_err: Option<Error> = None;
        let firsts: Vec<usize> = if self.sizes.len() == 1 {
            vec![0]
        } else {
            self.by_value.clone()
        };
        for &p in &firsts {
            let mut order = vec![p];
            order.extend(self.by_value.iter().copied().filter(|&s| s != p));
            let mut left: Vec<usize> = self.sizes.iter().map(|s| s.limit).collect();
            let mut plan = match self.assign(all.clone(), &order, &mut left) {
                Ok(plan) => plan,
                Err(unplaced) => {
                    first_err.get_or_insert(self.shortfall_lamellas(&unplaced));
                    continue;
                }
            };
            let mut nest = match self.place(&plan) {
                Ok(n) => n,
                Err(e) => {
                    first_err.get_or_insert(e);
                    continue;
                }
            };
            for _ in 0..TAIL_ROUNDS {
                let mut improved = false;
                let base = self.cost(&plan);
                let mut variants = self.tail_variants(&plan);
                variants.sort_by(|a, b| self.cost(a).total_cmp(&self.cost(b)));
                for v in variants {
                    if self.cost(&v) >= base {
                        continue;
                    }
                    if let Ok(n) = self.place(&v) {
                        if better(&n, &nest) {
                            (plan, nest, improved) = (v, n, true);
                            break;
                        }
                    }
                }
                if !improved {
                    break;
                }
            }
            finish(&mut nest.0);
            if best.as_ref().is_none_or(|b| better(&nest, b)) {
                best = Some(nest);
            }
        }
        match (best, first_err) {
            (Some(b), _) => Ok(b),
            (None, Some(e)) => Err(e),
            (None, None) => Ok((Vec::new(), 0)),
        }
    }

    /// What the sheets of a lane plan cost (as [`super::stock::Size::cost`]).
    fn cost(&self, sheets: &[SheetPlan]) -> f64 {
        sheets.iter().map(|s| self.sizes[s.size].cost).sum()
    }

    /// The count limits' one-line error for lamellas left without a sheet.
    fn shortfall_lamellas(&self, unplaced: &[usize]) -> Error {
        let length: f64 = unplaced
            .iter()
            .map(|&i| self.kit.parts[self.items[i].0].length_mm)
            .sum();
        // How many more sheets of the best-value size that holds them.
        let more = self
            .by_value
            .iter()
            .map(|&s| &self.sizes[s])
            .find(|z| z.lanes > 0 && unplaced.iter().all(|&i| fits(self.item_len[i], z.cap)))
            .map(|z| {
                let sizes: Vec<f64> = unplaced.iter().map(|&i| self.item_len[i]).collect();
                let lanes = binpack::pack(&sizes, z.cap).map_or(sizes.len(), |p| p.bins.len());
                format!(
                    "; about {} more sheet(s) of {}",
                    lanes.div_ceil(z.lanes),
                    z.label
                )
            })
            .unwrap_or_default();
        self.fail_stock(format!(
            "the count limits ({}) do not hold the kit: {} lamella(s), {:.1} m, have no sheet left{more}",
            self.limits(),
            unplaced.len(),
            length / 1000.0
        ))
    }
}
