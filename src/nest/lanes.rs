//! Lamellas in lanes: which lamella goes into which lane of which sheet
//! (one-dimensional bin packing per size, count limits passed on to the
//! next size), the cheaper variants of a plan's tail sheets, and the lanes
//! of a coil balanced by MULTIFIT.

use super::binpack;
use super::ctx::Ctx;
use super::stock::fits;

/// Lanes of lamellas assigned to one sheet of a size.
#[derive(Debug, Clone)]
pub(super) struct SheetPlan {
    pub(super) size: usize,
    /// Indices into the lamella items, one list per lane.
    pub(super) lanes: Vec<Vec<usize>>,
}

/// The tail improvement replaces at most this many sheets of one size.
const TAIL_SHEETS: usize = 2;

impl Ctx<'_> {
    /// Lamella `items` into lanes and sheets: the first size of `order`
    /// with sheets left takes the items that fit its lanes (packed by
    /// [`binpack::pack`]); items too long for it go first to the longer
    /// sizes after it in `order`, whose free lanes then take its lanes
    /// first; lanes beyond its count limit go on to the next sizes. `Err`
    /// holds the items no sheet is left for.
    pub(super) fn assign(
        &self,
        items: Vec<usize>,
        order: &[usize],
        left: &mut [usize],
    ) -> std::result::Result<Vec<SheetPlan>, Vec<usize>> {
        if items.is_empty() {
            return Ok(Vec::new());
        }
        let Some(pos) = order
            .iter()
            .position(|&s| left[s] > 0 && self.sizes[s].lanes > 0)
        else {
            return Err(items);
        };
        let p = order[pos];
        let rest = &order[pos + 1..];
        let (cap, k) = (self.sizes[p].cap, self.sizes[p].lanes);
        let (short, long): (Vec<usize>, Vec<usize>) = items
            .into_iter()
            .partition(|&i| fits(self.item_len[i], cap));
        let mut sheets = Vec::new();
        if !long.is_empty() {
            let longer: Vec<usize> = rest
                .iter()
                .copied()
                .filter(|&s| self.sizes[s].cap > cap)
                .collect();
            sheets = self.assign(long, &longer, left).map_err(|mut u| {
                u.extend(&short);
                u
            })?;
        }
        let lanes: Vec<Vec<usize>> = if short.is_empty() {
            Vec::new()
        } else {
            let sizes: Vec<f64> = short.iter().map(|&i| self.item_len[i]).collect();
            binpack::pack(&sizes, cap)
                .map(|pk| {
                    pk.bins
                        .into_iter()
                        .map(|b| b.into_iter().map(|j| short[j]).collect())
                        .collect()
                })
                .unwrap_or_else(|_| short.iter().map(|&i| vec![i]).collect())
        };
        // Fullest lanes first: the last sheet takes the emptiest, and those
        // are what goes on to other sizes past a count limit.
        let lane_load = |l: &Vec<usize>| -> f64 { l.iter().map(|&i| self.item_len[i]).sum() };
        let mut lanes = lanes;
        lanes.sort_by(|a, b| lane_load(b).total_cmp(&lane_load(a)));
        let mut lanes = lanes.into_iter();
        for sh in sheets.iter_mut() {
            while sh.lanes.len() < self.sizes[sh.size].lanes {
                match lanes.next() {
                    Some(l) => sh.lanes.push(l),
                    None => break,
                }
            }
        }
        let lanes: Vec<Vec<usize>> = lanes.collect();
        let take = lanes.len().div_ceil(k).min(left[p]);
        left[p] -= take;
        let mut lanes = lanes.into_iter();
        for _ in 0..take {
            sheets.push(SheetPlan {
                size: p,
                lanes: lanes.by_ref().take(k).collect(),
            });
        }
        let overflow: Vec<usize> = lanes.flatten().collect();
        if !overflow.is_empty() {
            sheets.extend(self.assign(overflow, rest, left)?);
        }
        Ok(sheets)
    }

    /// Variants of a lane plan whose lamellas cost less: the `t` ≤
    /// [`TAIL_SHEETS`] least-filled sheets of one size and every sheet of
    /// another size, repacked onto sheets of that other size (which must
    /// hold them all, within its count limit).
    pub(super) fn tail_variants(&self, plan: &[SheetPlan]) -> Vec<Vec<SheetPlan>> {
        let mut out = Vec::new();
        let load = |j: usize| -> f64 {
            plan[j]
                .lanes
                .iter()
                .flatten()
                .map(|&i| self.item_len[i])
                .sum()
        };
        for s in 0..self.sizes.len() {
            let mut mine: Vec<usize> = (0..plan.len()).filter(|&j| plan[j].size == s).collect();
            mine.sort_by(|&a, &b| load(a).total_cmp(&load(b)).then(b.cmp(&a)));
            for t in 1..=TAIL_SHEETS.min(mine.len()) {
                for q in 0..self.sizes.len() {
                    let z = &self.sizes[q];
                    if q == s || z.lanes == 0 {
                        continue;
                    }
                    let gone: Vec<usize> = (0..plan.len())
                        .filter(|&j| mine[..t].contains(&j) || plan[j].size == q)
                        .collect();
                    let items: Vec<usize> = gone
                        .iter()
                        .flat_map(|&j| plan[j].lanes.iter().flatten().copied())
                        .collect();
                    if items.iter().any(|&i| !fits(self.item_len[i], z.cap)) {
                        continue;
                    }
                    let sizes: Vec<f64> = items.iter().map(|&i| self.item_len[i]).collect();
                    let Ok(pk) = binpack::pack(&sizes, z.cap) else {
                        continue;
                    };
                    let n = pk.bins.len().div_ceil(z.lanes);
                    let was: f64 = gone.iter().map(|&j| self.sizes[plan[j].size].cost).sum();
                    if n > z.limit || n as f64 * z.cost >= was * (1.0 - 1e-12) {
                        continue;
                    }
                    let mut v: Vec<SheetPlan> = (0..plan.len())
                        .filter(|j| !gone.contains(j))
                        .map(|j| plan[j].clone())
                        .collect();
                    let mut bins = pk.bins.into_iter();
                    for _ in 0..n {
                        v.push(SheetPlan {
                            size: q,
                            lanes: bins
                                .by_ref()
                                .take(z.lanes)
                                .map(|b| b.into_iter().map(|j| items[j]).collect())
                                .collect(),
                        });
                    }
                    out.push(v);
                }
            }
        }
        out
    }
}

/// Items of `sizes` over `k` lanes of any length, the longest lane as short
/// as MULTIFIT finds it (Coffman, Garey & Johnson 1978): the longest-first
/// greedy (each item onto the shortest lane) bounds it from above, the
/// larger of the longest item and the mean from below; bisection to 0.5 mm
/// on the capacity at which [`binpack::pack`] needs at most `k` bins.
pub(super) fn balance(sizes: &[f64], k: usize) -> Vec<Vec<usize>> {
    if sizes.is_empty() || k == 0 {
        return Vec::new();
    }
    // More lanes than items stay empty (and are dropped at the end): the
    // lanes a profile's width allows are not allocated beyond the items.
    let k = k.min(sizes.len());
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by(|&a, &b| sizes[b].total_cmp(&sizes[a]).then(a.cmp(&b)));
    let mut lanes: Vec<Vec<usize>> = vec![Vec::new(); k];
    let mut loads = vec![0.0f64; k];
    for &i in &order {
        let j = (0..k)
            .min_by(|&a, &b| loads[a].total_cmp(&loads[b]).then(a.cmp(&b)))
            .unwrap_or(0);
        lanes[j].push(i);
        loads[j] += sizes[i];
    }
    let mut hi = loads.iter().copied().fold(0.0, f64::max);
    let total: f64 = sizes.iter().sum();
    let mut lo = sizes.iter().copied().fold(total / k as f64, f64::max);
    let mut best = lanes;
    for _ in 0..40 {
        if hi - lo <= 0.5 {
            break;
        }
        let mid = 0.5 * (lo + hi);
        match binpack::pack(sizes, mid) {
            Ok(p) if p.bins.len() <= k => {
                hi = p
                    .bins
                    .iter()
                    .map(|b| b.iter().map(|&i| sizes[i]).sum::<f64>())
                    .fold(0.0, f64::max)
                    .min(mid);
                best = p.bins;
            }
            _ => lo = mid,
        }
    }
    best.retain(|l| !l.is_empty());
    best
}

#[cfg(test)]
mod tests {
    use super::balance;

    #[test]
    fn lanes_beyond_the_items_are_not_made() {
        // A coil whose width holds ~1e13 lanes of a tiny lamella: once a
        // vector of that many lanes; now each item its own lane, at once.
        let lanes = balance(&[300.0, 500.0, 100.0], 10_000_000_000_000);
        assert_eq!(lanes, vec![vec![1], vec![0], vec![2]]);
        assert_eq!(balance(&[300.0, 500.0, 100.0], 3), lanes);
    }
}
