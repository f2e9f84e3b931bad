//! The sheets of a lane plan: the lamellas in their lanes, then every other
//! part by its bounding box onto a skyline of each sheet's free space (star
//! washers first in lattice blocks, placed where they waste least).

use super::ctx::Ctx;
use super::lanes::SheetPlan;
use super::lattice;
use super::model::{bbox, place_at, Placement, SheetNest};
use super::stock::Size;
use crate::error::{Error, Result};

/// Free space of one sheet as a skyline over its width: piecewise-constant
/// levels (the first free x) on [y_lo, y_hi).
#[derive(Debug, Clone)]
struct Skyline {
    /// (start y, level x), by y; each segment runs to the next's start.
    segs: Vec<(f64, f64)>,
    y_hi: f64,
}

impl Skyline {
    fn new(y_lo: f64, y_hi: f64, level: f64) -> Skyline {
        Skyline {
            segs: vec![(y_lo, level)],
            y_hi,
        }
    }

    /// Nothing placed yet: one segment at the sheet's margin.
    fn is_bare(&self, margin: f64) -> bool {
        self.segs.len() == 1 && (self.segs[0].1 - margin).abs() < 1e-9
    }

    /// Raise [y0, y1) to at least `x`.
    fn raise(&mut self, y0: f64, y1: f64, x: f64) {
        let y1 = y1.min(self.y_hi);
        let mut out: Vec<(f64, f64)> = Vec::with_capacity(self.segs.len() + 2);
        for (k, &(s, l)) in self.segs.iter().enumerate() {
            let e = self.segs.get(k + 1).map_or(self.y_hi, |n| n.0);
            // Up to three pieces: below y0, inside, above y1.
            if s < y0 {
                out.push((s, l));
            }
            let (a, b) = (s.max(y0), e.min(y1));
            if a < b {
                out.push((a, l.max(x)));
            }
            if e > y1 && s.max(y1) < e {
                out.push((s.max(y1), l));
            }
        }
        // Merge equal neighbours.
        out.dedup_by(|b, a| (a.1 - b.1).abs() < 1e-12);
        self.segs = out;
    }

    /// The places for a box ht high with `gap` above it and y + ht ≤
    /// y_max, one at each segment start s: (s, the level over
    /// [s, s + ht + gap) — the segments from s on that start inside it, a
    /// window, not the whole skyline — and the index past the window).
    fn windows(
        &self,
        ht: f64,
        gap: f64,
        y_max: f64,
    ) -> impl Iterator<Item = (f64, f64, std::ops::Range<usize>)> + '_ {
        (0..self.segs.len())
            .map(|i| (i, self.segs[i].0))
            .take_while(move |&(_, s)| s + ht <= y_max + 1e-9)
            .map(move |(i, s)| {
                let top = (s + ht + gap).min(self.y_hi);
                let end = i + self.segs[i..]
                    .iter()
                    .take_while(|seg| seg.0 < top - 1e-9)
                    .count();
                let x = self.segs[i..end]
                    .iter()
                    .fold(f64::NEG_INFINITY, |x, seg| x.max(seg.1));
                (s, x, i..end)
            })
    }

    /// Lowest place (x, y) for a box w × ht with `gap` above it, within
    /// x ≤ x_max and y + ht ≤ y_max: candidates at segment starts.
    fn fit(&self, w: f64, ht: f64, gap: f64, x_max: f64, y_max: f64) -> Option<(f64, f64)> {
        let mut best: Option<(f64, f64)> = None;
        for (s, x, _) in self.windows(ht, gap, y_max) {
            if x + w <= x_max + 1e-9 && best.is_none_or(|b| x < b.0 - 1e-9) {
                best = Some((x, s));
            }
        }
        best
    }

    /// The place (x, y) for a box w × ht with `gap` above it, within
    /// x ≤ x_max and y + ht ≤ y_max, that wastes least: the free area left
    /// of it that it shadows (its level less the skyline's, over its
    /// height and the gap), with that area; ties by lower x, then y.
    fn fit_least_waste(
        &self,
        w: f64,
        ht: f64,
        gap: f64,
        x_max: f64,
        y_max: f64,
    ) -> Option<(f64, f64, f64)> {
        let mut best: Option<(f64, f64, f64)> = None;
        for (s, x, window) in self.windows(ht, gap, y_max) {
            if x + w > x_max + 1e-9 {
                continue;
            }
            let top = (s + ht + gap).min(self.y_hi);
            let waste: f64 = window
                .map(|k| {
                    let end = self.segs.get(k + 1).map_or(self.y_hi, |q| q.0).min(top);
                    (end - self.segs[k].0) * (x - self.segs[k].1)
                })
                .sum();
            let better = best.is_none_or(|(bx, by, bw)| {
                waste < bw - 1e-6 || (waste <= bw + 1e-6 && (x, s) < (bx, by))
            });
            if better {
                best = Some((x, s, waste));
            }
        }
        best
    }
}

/// Sheets and the number of lamella lanes on them.
pub(super) type Placed = (Vec<SheetNest>, usize);

impl Ctx<'_> {
    /// A part's bounding box size turned by `rot`.
    fn dims(&self, i: usize, rot: u32) -> (f64, f64) {
        let (x0, y0, x1, y1) = bbox(&self.kit.parts[i]);
        if rot % 180 == 90 {
            (y1 - y0, x1 - x0)
        } else {
            (x1 - x0, y1 - y0)
        }
    }

    /// The sheets of a lane plan with the lamellas in their lanes, then
    /// every other part by its bounding box onto the skylines (new sheets
    /// of the best-value size with sheets left that holds the part), then
    /// sheets holding no lamella moved to a cheaper size where all their
    /// parts fit it.
    pub(super) fn place(&self, plan: &[SheetPlan]) -> Result<Placed> {
        let (m, g, h) = (self.margin, self.gap, self.height);
        let mut left: Vec<usize> = self.sizes.iter().map(|s| s.limit).collect();
        let mut sheets: Vec<SheetNest> = Vec::new();
        let mut skylines: Vec<Skyline> = Vec::new();
        for sp in plan {
            left[sp.size] -= 1;
            let mut sheet = self.new_sheet(sp.size);
            let z = &self.sizes[sp.size];
            let mut sky = Skyline::new(m, m + z.wu, m);
            for (j, lane) in sp.lanes.iter().enumerate() {
                let y = m + j as f64 * (h + g);
                let mut x = m;
                for &item in lane {
                    let (i, copy) = self.items[item];
                    let p = &self.kit.parts[i];
                    sheet
                        .placements
                        .push(place_at(i, p, copy, self.lamella_rot, x, y));
                    x += p.length_mm + g;
                }
                sky.raise(y, y + h + g, x);
            }
            sheets.push(sheet);
            skylines.push(sky);
        }
        let lamella_sheets = sheets.len();
        // Other parts, largest first: each copy at the lowest level (then
        // the lowest y) it fits, in the allowed rotation that gets it
        // lowest, on the first sheet with room from where the part's
        // previous copy went, else on a new sheet.
        for &i in &self.others {
            let p = &self.kit.parts[i];
            let mut first_sheet = 0;
            let blocked = self.place_blocks(i, &mut sheets, &mut skylines, &mut left)?;
            for copy in blocked..p.count {
                let mut k = first_sheet;
                loop {
                    if k == skylines.len() {
                        let Some(s) = self.new_size_for(i, &left) else {
                            return Err(self.shortfall_others(i, copy, &sheets));
                        };
                        left[s] -= 1;
                        sheets.push(self.new_sheet(s));
                        let z = &self.sizes[s];
                        skylines.push(Skyline::new(m, m + z.wu, m));
                    }
                    let z = &self.sizes[sheets[k].size];
                    if let Some(pl) = self.put(&mut skylines[k], i, copy, z) {
                        sheets[k].placements.push(pl);
                        first_sheet = k;
                        break;
                    }
                    if skylines[k].is_bare(m) && k + 1 == skylines.len() {
                        return Err(Error::fabrication_part(
                            &self.profile.source,
                            &p.id,
                            "does not fit an empty sheet in any allowed rotation",
                        ));
                    }
                    k += 1;
                }
            }
        }
        // Sheets of other parts only: a cheaper size that holds them all.
        for k in lamella_sheets..sheets.len() {
            let s = sheets[k].size;
            left[s] += 1;
            for &q in &self.by_value {
                let z = &self.sizes[q];
                if q == s || left[q] == 0 || z.cost >= self.sizes[s].cost {
                    continue;
                }
                let mut sky = Skyline::new(m, m + z.wu, m);
                let moved: Option<Vec<Placement>> = sheets[k]
                    .placements
                    .iter()
                    .map(|pl| self.put(&mut sky, pl.part, pl.copy, z))
                    .collect();
                if let Some(pls) = moved {
                    let mut sheet = self.new_sheet(q);
                    sheet.placements = pls;
                    sheets[k] = sheet;
                    break;
                }
            }
            left[sheets[k].size] -= 1;
        }
        let lanes = plan.iter().map(|s| s.lanes.len()).sum();
        Ok((sheets, lanes))
    }

    /// Part `i`'s copies in its lattice blocks ([`lattice`]), each block
    /// by its box onto the skylines like a part, on the first sheet where
    /// one fits (else a new sheet): of the blocks (or the first rows of
    /// one, for the last copies) the one, and the place, whose box plus
    /// the free area it shadows on its left is least per copy. Returns
    /// how many copies it placed: 0 for a part without blocks, fewer than
    /// all only where no block fits a bare sheet (the rest then go one by
    /// one).
    fn place_blocks(
        &self,
        i: usize,
        sheets: &mut Vec<SheetNest>,
        skylines: &mut Vec<Skyline>,
        left: &mut [usize],
    ) -> Result<u32> {
        let menu = &self.blocks[i];
        let p = &self.kit.parts[i];
        let (m, g) = (self.margin, self.gap);
        let mut copy = 0u32;
        let mut k = 0usize;
        while copy < p.count && !menu.is_empty() {
            if k == skylines.len() {
                let Some(s) = self.new_size_for(i, left) else {
                    return Err(self.shortfall_others(i, copy, sheets));
                };
                left[s] -= 1;
                sheets.push(self.new_sheet(s));
                let z = &self.sizes[s];
                skylines.push(Skyline::new(m, m + z.wu, m));
            }
            let z = &self.sizes[sheets[k].size];
            let rest = (p.count - copy) as usize;
            // The block and place that waste least per copy: the free
            // area a block shadows on its left counts with its own box.
            let mut fit: Option<(&lattice::Block, usize, f64, f64, f64, f64)> = None;
            let mut best_cost = f64::INFINITY;
            for b in menu {
                let n = b.len().min(rest);
                let (w, ht) = b.extent_mm(n);
                if let Some((x, y, waste)) =
                    skylines[k].fit_least_waste(w, ht, g, m + z.lu, m + z.wu)
                {
                    let cost = (waste + (w + g) * (ht + g)) / n as f64;
                    if cost < best_cost - 1e-9 {
                        best_cost = cost;
                        fit = Some((b, n, w, ht, x, y));
                    }
                }
            }
            match fit {
                Some((b, n, w, ht, x, y)) => {
                    skylines[k].raise(y, y + ht + g, x + w + g);
                    for c in &b.corners_mm[..n] {
                        sheets[k]
                            .placements
                            .push(place_at(i, p, copy, 0, x + c.x, y + c.y));
                        copy += 1;
                    }
                }
                // No block fits even a bare sheet: the rest one by one.
                None if skylines[k].is_bare(m) && k + 1 == skylines.len() => break,
                None => k += 1,
            }
        }
        Ok(copy)
    }

    /// Copy `copy` of part `i` onto a skyline of size `z`, in the rotation
    /// that puts it lowest; the placement, or `None` where it does not fit.
    fn put(&self, sky: &mut Skyline, i: usize, copy: u32, z: &Size) -> Option<Placement> {
        let (m, g) = (self.margin, self.gap);
        let (x, y, r, w, ht) = self
            .rotations
            .iter()
            .filter_map(|&r| {
                let (w, ht) = self.dims(i, r);
                sky.fit(w, ht, g, m + z.lu, m + z.wu)
                    .map(|(x, y)| (x, y, r, w, ht))
            })
            .min_by(|a, b| {
                a.0.total_cmp(&b.0)
                    .then(a.1.total_cmp(&b.1))
                    .then(a.2.cmp(&b.2))
            })?;
        sky.raise(y, y + ht + g, x + w + g);
        Some(place_at(i, &self.kit.parts[i], copy, r, x, y))
    }

    /// The best-value size with sheets left whose bare sheet holds part `i`.
    fn new_size_for(&self, i: usize, left: &[usize]) -> Option<usize> {
        self.by_value.iter().copied().find(|&s| {
            let z = &self.sizes[s];
            left[s] > 0
                && self.rotations.iter().any(|&r| {
                    let (w, ht) = self.dims(i, r);
                    w <= z.lu + 1e-9 && ht <= z.wu + 1e-9
                })
        })
    }

    pub(super) fn new_sheet(&self, size: usize) -> SheetNest {
        let z = &self.sizes[size];
        SheetNest {
            id: String::new(),
            size,
            stock: z.label.clone(),
            width_mm: z.width,
            length_mm: z.length,
            price_per_unit: z.price,
            placements: Vec::new(),
            part_area_mm2: 0.0,
        }
    }

    /// The count limits' one-line error for other parts left without a sheet.
    fn shortfall_others(&self, part: usize, copy: u32, sheets: &[SheetNest]) -> Error {
        let pos = self.others.iter().position(|&i| i == part).unwrap_or(0);
        let mut copies = u64::from(self.kit.parts[part].count - copy);
        let mut area = copies as f64 * self.areas[part];
        for &i in &self.others[pos + 1..] {
            copies += u64::from(self.kit.parts[i].count);
            area += f64::from(self.kit.parts[i].count) * self.areas[i];
        }
        self.fail_stock(format!(
            "the count limits ({}) do not hold the kit: after {} sheet(s), {copies} part \
             cop(ies) of {:.2} m² (from {}) have no sheet left",
            self.limits(),
            sheets.len(),
            area / 1e6,
            self.kit.parts[part].id
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::Skyline;

    /// A skyline over y ∈ [0, 300): levels 100 on [0, 100), 0 on
    /// [100, 200) (a free notch), 150 on [200, 300). A 50 × 100 box with
    /// no gap: the lowest-x rule (`fit`) puts it into the notch at x = 0
    /// with nothing shadowed; one 150 high cannot use the notch alone, and
    /// of its places the least shadow is at y = 0 (x = 100: the notch's
    /// 100 × 50 = 5000 mm² shadowed) against y = 100 (x = 150: 100 × 150
    /// = 15,000 mm²), by hand.
    #[test]
    fn least_waste_prefers_the_place_that_shadows_least() {
        let mut sky = Skyline::new(0.0, 300.0, 0.0);
        sky.raise(0.0, 100.0, 100.0);
        sky.raise(200.0, 300.0, 150.0);
        assert_eq!(sky.fit(50.0, 100.0, 0.0, 1000.0, 300.0), Some((0.0, 100.0)));
        assert_eq!(
            sky.fit_least_waste(50.0, 100.0, 0.0, 1000.0, 300.0),
            Some((0.0, 100.0, 0.0))
        );
        let (x, y, waste) = sky
            .fit_least_waste(50.0, 150.0, 0.0, 1000.0, 300.0)
            .expect("a place");
        assert_eq!((x, y), (100.0, 0.0));
        assert!((waste - 5000.0).abs() < 1e-9, "{waste}");
        // Nothing fits past x_max or above y_max.
        assert_eq!(sky.fit_least_waste(950.0, 150.0, 0.0, 1000.0, 300.0), None);
        assert_eq!(sky.fit_least_waste(10.0, 301.0, 0.0, 1000.0, 300.0), None);
    }
}
