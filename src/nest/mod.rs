//! Nesting the kit onto stock (issue 9): lamellas into lanes along the
//! sheets, small parts and edge bands into what is left.
//!
//! A sheet's usable area is its length × width less the edge margin all
//! round; parts keep kerf + part spacing (`gap`) from each other. Lamellas
//! (all one height h) lie along the sheet in lanes h apart plus the gap;
//! which lamella goes into which lane is one-dimensional bin packing
//! ([`binpack`]: item = length + gap, capacity = usable length + gap), and
//! lanes fill the sheets in order, fullest first. Other parts (shear
//! blocks, splice plates, washers, studs, edge strips) go by their bounding
//! boxes, in an allowed rotation, onto a skyline of each sheet's free
//! space (the lane tails first), first sheet with room, else a new sheet.
//! Then [`outline::place_bands`] places the edge bands again by their true
//! outlines (stacked in each other's bows, into the lamella sheets' free
//! width), and [`outline::eliminate`] empties sheets holding no lamella
//! into the free space of the others by the parts' true outlines, where all
//! of a sheet's parts find a place; with several sizes, on each
//! first-choice candidate before the cheapest is chosen.
//!
//! Several sheet sizes: the cheapest nest (by price, else by stock area)
//! over the sizes as first choice, each improved by repacking the
//! least-filled sheets onto another size (`Ctx::sheets`); count limits
//! hold throughout, and a kit they cannot hold is a one-line error. A coil
//! is one long sheet whose lanes are balanced (MULTIFIT), cut to the
//! length used.
//!
//! Lower bounds: the area bound ⌈Σ part area / usable sheet area⌉ and the
//! lane bound ⌈L2(lamellas) / lanes per sheet⌉ (Martello–Toth L2 on the lane
//! problem), with several sizes at the largest area and longest lane; a
//! bound on the cost; for a coil a bound on the length.
//!
//! Plain data in (`Kit`, `Profile`), plain data out ([`Nest`]);
//! deterministic (no threads, ties broken by index). A placement maps
//! part-local (x, y) to sheet coordinates by rotating about the origin by
//! `rotation_deg` (counter-clockwise), then translating by (x_mm, y_mm); the
//! sheet's x runs along its length.

pub mod binpack;
mod bounds;
mod check;
mod coil;
mod ctx;
mod lanes;
pub mod lattice;
mod model;
pub mod outline;
mod sizes;
mod skyline;
mod stock;

pub use check::check_nest;
pub use model::{placed_bbox, rotate, Nest, NestSummary, Placement, SheetNest, StockUse};

use crate::error::Result;
use crate::fabricate::Kit;
use crate::profile::Profile;
use bounds::summarize;
use ctx::Ctx;

/// Nest every part of the kit onto the profile's stock.
pub fn nest(kit: &Kit, profile: &Profile) -> Result<Nest> {
    let t0 = std::time::Instant::now();
    let ctx = Ctx::new(kit, profile)?;
    let st = &profile.stock;
    let coil = st.is_coil();
    // Each candidate nest: edge bands again by true outline, then sheets
    // of small parts emptied into the others.
    let finish = |sheets: &mut Vec<SheetNest>| {
        sheets.retain(|s| !s.placements.is_empty());
        outline::place_bands(kit, &ctx.areas, sheets, ctx.margin, ctx.gap, &ctx.rotations);
        outline::eliminate(kit, &ctx.areas, sheets, ctx.margin, ctx.gap, &ctx.rotations);
    };
    let (mut sheets, lanes_used) = if coil && st.sizes[0].length_mm.is_none() {
        ctx.coil()?
    } else {
        ctx.sheets(&finish)?
    };
    sheets.retain(|s| !s.placements.is_empty());
    sheets.sort_by_key(|s| s.size);
    let m = ctx.margin;
    // Once per part, not per copy placed.
    let areas = &ctx.areas;
    for (k, s) in sheets.iter_mut().enumerate() {
        s.id = format!("S{:02}", k + 1);
        s.part_area_mm2 = s.placements.iter().map(|pl| areas[pl.part]).sum();
        if coil {
            // Cut to the length used, in whole steps.
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
    }
    let summary = summarize(&ctx, &sheets, lanes_used, t0);
    let mut stock_used: Vec<StockUse> = Vec::new();
    for s in &sheets {
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
    let nest = Nest {
        sheets,
        summary,
        stock_used,
        currency: st.currency.clone(),
    };
    debug_assert_eq!(check_nest(kit, &nest, profile), Ok(()));
    Ok(nest)
}
