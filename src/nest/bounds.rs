//! The nest's figures and its lower bounds: on the sheets (by area and by
//! lanes), on the cost, and for a coil on the length; the stock used per
//! size.

use super::binpack;
use super::ctx::Ctx;
use super::model::{GroupNest, NestSummary, SheetNest, StockUse};
use super::stock::Size;

/// The nest's figures and bounds.
pub(super) fn summarize(
    ctx: &Ctx,
    sheets: &[SheetNest],
    lanes_used: usize,
    t0: std::time::Instant,
) -> NestSummary {
    let kit = ctx.kit;
    let st = &ctx.profile.stock;
    let total_area: f64 = kit
        .parts
        .iter()
        .zip(&ctx.areas)
        .map(|(p, a)| a * f64::from(p.count))
        .sum();
    let lane_sizes: Vec<&Size> = ctx.sizes.iter().filter(|z| z.lanes > 0).collect();
    let max_area = ctx.sizes.iter().map(|z| z.lu * z.wu).fold(0.0, f64::max);
    let area_bound_sheets = (total_area / max_area * (1.0 - 1e-12)).ceil() as usize;
    let lanes_per_sheet = lane_sizes.iter().map(|z| z.lanes).max().unwrap_or(0);
    let cap = lane_sizes.iter().map(|z| z.cap).fold(0.0, f64::max);
    let lane_bound_lanes = if ctx.items.is_empty() {
        0
    } else if cap.is_infinite() {
        // A coil cut to any length: its lanes are as long as needed.
        ctx.items.len().min(lanes_per_sheet)
    } else {
        binpack::lower_bound_l2(&ctx.item_len, cap)
    };
    let lane_bound_sheets = if lanes_per_sheet > 0 {
        lane_bound_lanes.div_ceil(lanes_per_sheet)
    } else {
        0
    };
    let used_area: f64 = sheets.iter().map(|s| s.length_mm * s.width_mm).sum();
    let lane_total: f64 = ctx.item_len.iter().sum();
    // Costs: any sheet of size s holds at most its usable area of parts
    // and k_s lanes of capacity C_s, at its cost c_s.
    // A coil: the longest lane is at least the mean lane and the longest
    // lamella; the parts' area needs its length of the usable width.
    let length_bound = st.is_coil().then(|| {
        let z = &ctx.sizes[0];
        let longest = ctx.item_len.iter().copied().fold(0.0, f64::max);
        let lanes = if z.lanes > 0 && !ctx.items.is_empty() {
            (lane_total / z.lanes as f64).max(longest) - ctx.gap
        } else {
            0.0
        };
        (total_area / z.wu).max(lanes) + 2.0 * ctx.margin
    });
    let cost_bound = if let Some(length) = length_bound {
        let z = &ctx.sizes[0];
        st.price_per_m
            .map(|per_m| per_m * length / 1000.0)
            .or_else(|| {
                z.price
                    .map(|p| p * (length / z.length * (1.0 - 1e-12)).ceil())
            })
    } else if st.priced() {
        let per_area = ctx
            .sizes
            .iter()
            .map(|z| z.cost / (z.lu * z.wu))
            .fold(f64::INFINITY, f64::min);
        let per_lane = lane_sizes
            .iter()
            .map(|z| z.cost / (z.lanes as f64 * z.cap))
            .fold(f64::INFINITY, f64::min);
        Some((total_area * per_area).max(if ctx.items.is_empty() {
            0.0
        } else {
            lane_total * per_lane
        }))
    } else {
        None
    };
    let cost = sheets
        .iter()
        .map(|s| s.price_per_unit)
        .sum::<Option<f64>>()
        .filter(|_| st.priced());
    NestSummary {
        sheets_used: sheets.len(),
        lower_bound_sheets: area_bound_sheets.max(lane_bound_sheets),
        area_bound_sheets,
        lane_bound_sheets,
        lanes_per_sheet,
        lanes_used,
        lane_bound_lanes,
        utilization: if used_area > 0.0 {
            total_area / used_area
        } else {
            0.0
        },
        stock_area_mm2: used_area,
        length_used_mm: st
            .is_coil()
            .then(|| sheets.iter().map(|s| s.length_mm).sum()),
        length_bound_mm: length_bound,
        cost,
        cost_bound,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

/// The sheets per stock size, of `sheets` in size order.
pub(super) fn stock_used(sheets: &[SheetNest]) -> Vec<StockUse> {
    let mut stock_used: Vec<StockUse> = Vec::new();
    for s in sheets {
        match stock_used.last_mut() {
            Some(u) if u.size == s.size => {
                u.sheets += 1;
                u.length_mm += s.length_mm;
                u.cost = u.cost.zip(s.price_per_unit).map(|(a, b)| a + b);
            }
            _ => stock_used.push(StockUse {
                size: s.size,
                stock: s.stock.clone(),
                sheets: 1,
                length_mm: s.length_mm,
                width_mm: s.width_mm,
                price_per_unit: s.price_per_unit,
                cost: s.price_per_unit,
            }),
        }
    }
    stock_used
}

/// The whole nest's figures from its groups': counts, bounds, areas and
/// costs summed (a sum of lower bounds is a lower bound on the sum); the
/// lanes are the lamella group's (the only one with lamellas); the cost
/// and its bound only when every group is priced; a coil's length summed
/// over the coil groups.
pub(super) fn total(groups: &[GroupNest], t0: std::time::Instant) -> NestSummary {
    let sum = |f: fn(&NestSummary) -> usize| groups.iter().map(|g| f(&g.summary)).sum::<usize>();
    let part_area: f64 = groups
        .iter()
        .map(|g| g.summary.utilization * g.summary.stock_area_mm2)
        .sum();
    let stock_area: f64 = groups.iter().map(|g| g.summary.stock_area_mm2).sum();
    let all = |f: fn(&NestSummary) -> Option<f64>| {
        groups.iter().map(|g| f(&g.summary)).sum::<Option<f64>>()
    };
    let coils = |f: fn(&NestSummary) -> Option<f64>| {
        groups
            .iter()
            .filter_map(|g| f(&g.summary))
            .reduce(|a, b| a + b)
    };
    NestSummary {
        sheets_used: sum(|s| s.sheets_used),
        lower_bound_sheets: sum(|s| s.lower_bound_sheets),
        area_bound_sheets: sum(|s| s.area_bound_sheets),
        lane_bound_sheets: sum(|s| s.lane_bound_sheets),
        lanes_per_sheet: groups
            .iter()
            .map(|g| g.summary.lanes_per_sheet)
            .max()
            .unwrap_or(0),
        lanes_used: sum(|s| s.lanes_used),
        lane_bound_lanes: sum(|s| s.lane_bound_lanes),
        utilization: if stock_area > 0.0 {
            part_area / stock_area
        } else {
            0.0
        },
        stock_area_mm2: stock_area,
        cost: all(|s| s.cost),
        cost_bound: all(|s| s.cost_bound),
        length_used_mm: coils(|s| s.length_used_mm),
        length_bound_mm: coils(|s| s.length_bound_mm),
        seconds: t0.elapsed().as_secs_f64(),
    }
}
