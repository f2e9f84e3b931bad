//! Bars: parts sawn from bars of one length (studs) as a cut list, nested
//! in one dimension: every copy longest first onto the first bar with
//! room (first-fit decreasing), end to end a kerf apart from the bar's
//! start, the bar's edge margin at both ends.

use super::ctx::Ctx;
use super::model::{bbox, place_at, SheetNest};
use crate::error::Result;

impl Ctx<'_> {
    /// The bars of a bar group: one "sheet" per bar (its length × the
    /// section), the copies end to end along it.
    pub(super) fn bars(&self) -> Result<Vec<SheetNest>> {
        let z = &self.sizes[0];
        let kerf = self.profile.cutting.kerf_mm + self.profile.cutting.part_spacing_mm;
        let m = self.margin;
        let mut copies: Vec<(usize, u32, f64)> = Vec::new();
        for (i, p) in self.kit.parts.iter().enumerate() {
            let (x0, _, x1, _) = bbox(p);
            for copy in 0..p.count {
                copies.push((i, copy, x1 - x0));
            }
        }
        copies.sort_by(|a, b| b.2.total_cmp(&a.2).then(a.0.cmp(&b.0)).then(a.1.cmp(&b.1)));
        // Per bar: the first free x.
        let mut ends: Vec<f64> = Vec::new();
        let mut sheets: Vec<SheetNest> = Vec::new();
        for (i, copy, len) in copies {
            let fits = |end: f64| end + len <= z.length - m + 1e-9;
            let k = match ends.iter().position(|&e| fits(e)) {
                Some(k) => k,
                None => {
                    if !fits(m) {
                        return Err(self.fail_stock(format!(
                            "{} is {len:.0} mm long, longer than a {} mm bar",
                            self.kit.parts[i].id, z.length
                        )));
                    }
                    if sheets.len() >= z.limit {
                        return Err(self.fail_stock(format!(
                            "{} bars are not enough for the cut list ({})",
                            z.limit,
                            self.limits()
                        )));
                    }
                    ends.push(m);
                    sheets.push(self.new_sheet(0));
                    sheets.len() - 1
                }
            };
            let p = &self.kit.parts[i];
            sheets[k]
                .placements
                .push(place_at(i, p, copy, 0, ends[k], m));
            ends[k] += len + kerf;
        }
        Ok(sheets)
    }
}
