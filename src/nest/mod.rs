//! Nesting the kit onto stock: lamellas into lanes along the sheets, small
//! parts and edge bands into what is left.
//!
//! A sheet's usable area is its length × width less the edge margin all
//! round; parts keep kerf + part spacing (`gap`) from each other. Lamellas
//! (all one height h) lie along the sheet in lanes h apart plus the gap;
//! which lamella goes into which lane is one-dimensional bin packing
//! ([`binpack`]: item = length + gap, capacity = usable length + gap), and
//! lanes fill the sheets in order, fullest first (`lanes.rs`). Other parts
//! (shear blocks, splice plates, washers, studs, edge strips) go by their
//! bounding boxes, in an allowed rotation, onto a skyline of each sheet's
//! free space (the lane tails first), first sheet with room, else a new
//! sheet; star washers go first in [`lattice`] blocks, each where it wastes
//! least (`skyline.rs`). Then `raster.rs` places the edge bands again by
//! their true outlines on occupancy rasters (the most bowed first, stacked
//! in each other's bows and under them, into the lamella sheets' lane
//! tails), and [`outline::eliminate`] empties sheets
//! holding no lamella into the free space of the others by the parts' true
//! outlines, where all of a sheet's parts find a place; with several sizes,
//! on each first-choice candidate before the cheapest is chosen.
//!
//! Several sheet sizes: the cheapest nest (by price, else by stock area)
//! over the sizes as first choice, each improved by repacking the
//! least-filled sheets onto another size (`sizes.rs`); count limits hold
//! throughout, and a kit they cannot hold is a one-line error. A coil is
//! one long sheet whose lanes are balanced (MULTIFIT), cut to the length
//! used (`coil.rs`).
//!
//! Lower bounds (`bounds.rs`): the area bound ⌈Σ part area / usable sheet
//! area⌉ and the lane bound ⌈L2(lamellas) / lanes per sheet⌉
//! (Martello–Toth L2 on the lane problem), with several sizes at the
//! largest area and longest lane; a bound on the cost; for a coil a bound
//! on the length.
//!
//! Stock groups: every part is of one material and thickness
//! ([`Profile::stock_groups`]); each group is nested on its own, onto its
//! own stock with its own cutting, and its sheets follow the previous
//! group's (`S01…` run on over the groups). A bar group (studs) is a cut
//! list: its copies end to end along bars (`bars.rs`). The figures and
//! bounds are per group, and summed.
//!
//! Plain data in (`Kit`, `Profile`), plain data out ([`Nest`]);
//! deterministic (no threads, ties broken by index). A placement maps
//! part-local (x, y) to sheet coordinates by rotating about the origin by
//! `rotation_deg` (counter-clockwise), then translating by (x_mm, y_mm); the
//! sheet's x runs along its length. [`check_nest`] checks the nest's
//! invariant on any nest.
//!
//! The files: `model.rs` the output types and the placement frame,
//! `stock.rs` one stock size as the nest sees it, `ctx.rs` what one nest
//! needs to know (built once, refusing what the stock cannot hold), then
//! `lanes.rs`, `skyline.rs`, `sizes.rs`, `coil.rs`, `bounds.rs` and
//! `check.rs` as above; this file is the driver.

mod bars;
pub mod binpack;
mod bounds;
mod check;
mod coil;
mod ctx;
mod lanes;
pub mod lattice;
mod model;
pub mod outline;
mod raster;
mod sizes;
mod skyline;
mod stock;

pub use check::check_nest;
pub use model::{
    placed_bbox, rotate, GroupNest, Nest, NestSummary, Placement, SheetNest, StockUse,
};

use crate::error::Result;
use crate::fabricate::{Kit, KitSummary};
use crate::profile::{Profile, StockForm};
use bounds::{stock_used, summarize};
use ctx::Ctx;

/// Nest every part of the kit, each stock group onto its own stock.
pub fn nest(kit: &Kit, profile: &Profile) -> Result<Nest> {
    let t0 = std::time::Instant::now();
    let groups = profile.stock_groups();
    let group_of: Vec<usize> = kit
        .parts
        .iter()
        .map(|p| Profile::group_of(&groups, p.kind.piece()))
        .collect();
    let mut sheets: Vec<SheetNest> = Vec::new();
    let mut out: Vec<GroupNest> = Vec::new();
    for (gi, g) in groups.iter().enumerate() {
        let members: Vec<usize> = (0..kit.parts.len())
            .filter(|&i| group_of[i] == gi)
            .collect();
        if members.is_empty() {
            continue;
        }
        let mut sub_profile = profile.clone();
        sub_profile.stock = g.stock.clone();
        sub_profile.cutting = g.cutting.clone();
        let whole = members.len() == kit.parts.len();
        let sub_kit;
        let group_kit = if whole {
            kit
        } else {
            sub_kit = Kit {
                parts: members.iter().map(|&i| kit.parts[i].clone()).collect(),
                summary: KitSummary::default(),
                warnings: Vec::new(),
            };
            &sub_kit
        };
        let (mut group_sheets, summary, used) = nest_group(group_kit, &sub_profile, g.form)?;
        let first = sheets.len();
        for (k, s) in group_sheets.iter_mut().enumerate() {
            s.id = format!("S{:02}", first + k + 1);
            for pl in &mut s.placements {
                pl.part = members[pl.part];
            }
        }
        sheets.extend(group_sheets);
        out.push(GroupNest {
            name: g.name.clone(),
            material: g.material.clone(),
            thickness_mm: g.thickness_mm,
            form: g.form,
            sheets: first..sheets.len(),
            summary,
            stock_used: used,
            cutting: g.cutting.clone(),
        });
    }
    let summary = bounds::total(&out, t0);
    let stock_used = out.iter().flat_map(|g| g.stock_used.clone()).collect();
    let nest = Nest {
        sheets,
        summary,
        stock_used,
        currency: profile.stock.currency.clone(),
        groups: out,
    };
    debug_assert_eq!(check_nest(kit, &nest, profile), Ok(()));
    Ok(nest)
}

/// Nest one group's parts (`kit`) onto its stock (`profile`'s, with its
/// cutting): its sheets `S01…` by size, its figures, its stock used.
fn nest_group(
    kit: &Kit,
    profile: &Profile,
    form: StockForm,
) -> Result<(Vec<SheetNest>, NestSummary, Vec<StockUse>)> {
    let t0 = std::time::Instant::now();
    let ctx = Ctx::new(kit, profile)?;
    let st = &profile.stock;
    let coil = st.is_coil();
    // Each candidate nest: edge bands again by true outline, then sheets
    // of small parts emptied into the others.
    let finish = |sheets: &mut Vec<SheetNest>| {
        sheets.retain(|s| !s.placements.is_empty());
        let setting = outline::Setting {
            kit,
            areas_mm2: &ctx.areas,
            margin_mm: ctx.margin,
            gap_mm: ctx.gap,
            rotations_deg: &ctx.rotations,
        };
        raster::place_bands(setting, sheets);
        outline::eliminate(setting, sheets);
    };
    let (mut sheets, lanes_used) = if form == StockForm::Bar {
        (ctx.bars()?, 0)
    } else if coil && st.sizes[0].length_mm.is_none() {
        ctx.coil()?
    } else {
        ctx.sheets(&finish)?
    };
    sheets.retain(|s| !s.placements.is_empty());
    sheets.sort_by_key(|s| s.size);
    // Once per part, not per copy placed.
    let areas = &ctx.areas;
    for (k, s) in sheets.iter_mut().enumerate() {
        s.id = format!("S{:02}", k + 1);
        s.part_area_mm2 = s.placements.iter().map(|pl| areas[pl.part]).sum();
        if coil {
            coil::cut_to_length(s, kit, ctx.margin, st);
        }
    }
    let mut summary = summarize(&ctx, &sheets, lanes_used, t0);
    if form == StockForm::Bar {
        // A cut list: the lengths (+ kerf) into the bar's usable length
        // (+ kerf), as the lanes' bound (Martello–Toth L2).
        let c = &profile.cutting;
        let kerf = c.kerf_mm + c.part_spacing_mm;
        let lengths: Vec<f64> = kit
            .parts
            .iter()
            .flat_map(|p| {
                let (x0, _, x1, _) = model::bbox(p);
                std::iter::repeat_n(x1 - x0 + kerf, p.count as usize)
            })
            .collect();
        let cap = ctx.sizes[0].lu + kerf;
        // Lengths all equal (studs): exactly ⌈n / ⌊cap / length⌋⌉.
        summary.lane_bound_sheets = match lengths.first() {
            Some(&l) if lengths.iter().all(|&x| x == l) && l <= cap => {
                lengths.len().div_ceil((cap / l).floor() as usize)
            }
            _ => binpack::lower_bound_l2(&lengths, cap),
        };
        summary.lower_bound_sheets = summary.area_bound_sheets.max(summary.lane_bound_sheets);
    }
    let used = stock_used(&sheets);
    Ok((sheets, summary, used))
}
