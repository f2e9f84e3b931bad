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
pub mod lattice;
pub mod outline;

use crate::error::{Error, Result};
use crate::fabricate::part::{Part, PartKind};
use crate::fabricate::{net_area_mm2, Kit};
use crate::profile::Profile;
use kurbo::Point;

/// One copy of a part on a sheet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Index into the kit's parts.
    pub part: usize,
    /// Which copy (0-based, below the part's count).
    pub copy: u32,
    /// Translation after the rotation, sheet frame, mm.
    pub x_mm: f64,
    /// Translation after the rotation, sheet frame, mm.
    pub y_mm: f64,
    /// Counter-clockwise rotation about the part's origin, degrees (a
    /// quarter turn multiple from the profile's allowed rotations).
    pub rotation_deg: u32,
}

/// One sheet of stock (a coil: one piece cut from it) and what is cut
/// from it.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetNest {
    /// `S01`, `S02`, …
    pub id: String,
    /// Index of its size in the profile's `stock.sizes`.
    pub size: usize,
    /// The size's label: its name, else `length × width` (`3000 × 1500`;
    /// a coil cut to any length: `coil 1500`).
    pub stock: String,
    /// Along the sheet's y, mm.
    pub width_mm: f64,
    /// Along the sheet's x, mm (a coil piece: the length cut).
    pub length_mm: f64,
    /// What this sheet costs, if priced: the size's price (a coil priced
    /// per metre: the price of the length cut).
    pub price_per_unit: Option<f64>,
    /// Everything cut from it.
    pub placements: Vec<Placement>,
    /// Net area of those parts (outline less holes), mm².
    pub part_area_mm2: f64,
}

impl SheetNest {
    /// Part area over the sheet's whole area.
    pub fn utilization(&self) -> f64 {
        self.part_area_mm2 / (self.width_mm * self.length_mm)
    }
}

/// The nest's figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NestSummary {
    /// Sheets with at least one part.
    pub sheets_used: usize,
    /// The larger of the area and lane bounds.
    pub lower_bound_sheets: usize,
    /// ⌈Σ part area / usable sheet area⌉ (several sizes: of the size with
    /// the largest usable area).
    pub area_bound_sheets: usize,
    /// ⌈L2(lamella lanes) / lanes per sheet⌉ (several sizes: L2 at the
    /// longest lane, over the most lanes any size has).
    pub lane_bound_sheets: usize,
    /// Lanes that fit across one sheet (several sizes: the most of any).
    pub lanes_per_sheet: usize,
    /// Lanes the lamellas fill.
    pub lanes_used: usize,
    /// Martello–Toth L2 on the lanes (several sizes: at the longest lane).
    pub lane_bound_lanes: usize,
    /// Part area over the area of the sheets used.
    pub utilization: f64,
    /// Area of the stock used (bought), mm².
    pub stock_area_mm2: f64,
    /// What the sheets cost, when every size is priced.
    pub cost: Option<f64>,
    /// A lower bound on the cost, when priced: the larger of Σ part area
    /// at the lowest price per usable area and Σ lane length at the lowest
    /// price per lane length (coil: the price of `length_bound_mm`).
    pub cost_bound: Option<f64>,
    /// A coil: the length cut from it, Σ over its pieces, mm.
    pub length_used_mm: Option<f64>,
    /// A coil: a lower bound on that length (the mean lane, the longest
    /// lamella and the parts' area over the usable width, plus the
    /// margins), mm.
    pub length_bound_mm: Option<f64>,
    /// Wall-clock time of the nest, s (not part of any output that must be
    /// byte-stable).
    pub seconds: f64,
}

/// The sheets of one stock size the nest uses.
#[derive(Debug, Clone, PartialEq)]
pub struct StockUse {
    /// Index of the size in the profile's `stock.sizes`.
    pub size: usize,
    /// The size's label (as [`SheetNest::stock`]).
    pub stock: String,
    /// Sheets (coil: pieces) of it.
    pub sheets: usize,
    /// Σ of their lengths, mm.
    pub length_mm: f64,
    /// Their width, mm.
    pub width_mm: f64,
    /// The price of one sheet, if priced (a coil per metre: of the first piece).
    pub price_per_unit: Option<f64>,
    /// What they cost, if priced.
    pub cost: Option<f64>,
}

/// The nest of a kit.
#[derive(Debug, Clone, PartialEq)]
pub struct Nest {
    /// Sheets in order (by stock size, then as filled).
    pub sheets: Vec<SheetNest>,
    /// Counts, bounds, utilisation, cost.
    pub summary: NestSummary,
    /// Sheets per stock size, in size order.
    pub stock_used: Vec<StockUse>,
    /// Currency of the prices, if the profile names one.
    pub currency: Option<String>,
}

/// Bounding box of a part's outline in its own frame.
fn bbox(p: &Part) -> (f64, f64, f64, f64) {
    p.outline_part_mm.iter().fold(
        (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), q| (a.min(q.x), b.min(q.y), c.max(q.x), d.max(q.y)),
    )
}

/// A point turned counter-clockwise by a quarter-turn multiple.
pub fn rotate(q: Point, rotation_deg: u32) -> Point {
    match rotation_deg % 360 {
        90 => Point::new(-q.y, q.x),
        180 => Point::new(-q.x, -q.y),
        270 => Point::new(q.y, -q.x),
        _ => q,
    }
}

/// The sheet-frame bounding box of a placed part.
pub fn placed_bbox(p: &Part, pl: &Placement) -> (f64, f64, f64, f64) {
    let (x0, y0, x1, y1) = bbox(p);
    let a = rotate(Point::new(x0, y0), pl.rotation_deg);
    let b = rotate(Point::new(x1, y1), pl.rotation_deg);
    (
        a.x.min(b.x) + pl.x_mm,
        a.y.min(b.y) + pl.y_mm,
        a.x.max(b.x) + pl.x_mm,
        a.y.max(b.y) + pl.y_mm,
    )
}

/// The placement that puts part `p` turned by `rot` with its bounding box's
/// lower-left corner at (x, y).
fn place_at(part: usize, p: &Part, copy: u32, rot: u32, x: f64, y: f64) -> Placement {
    let probe = placed_bbox(
        p,
        &Placement {
            part,
            copy,
            x_mm: 0.0,
            y_mm: 0.0,
            rotation_deg: rot,
        },
    );
    Placement {
        part,
        copy,
        x_mm: x - probe.0,
        y_mm: y - probe.1,
        rotation_deg: rot,
    }
}

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

/// One stock size as the nest sees it.
#[derive(Debug, Clone)]
struct Size {
    /// Full length (infinite for a coil cut to any length) and width, mm.
    length: f64,
    width: f64,
    /// Usable length and width (less the margins), mm.
    lu: f64,
    wu: f64,
    /// Lamella lanes across it.
    lanes: usize,
    /// Lane capacity for the bin packing: usable length + one gap.
    cap: f64,
    /// What a sheet costs: its price, else its area (mm²).
    cost: f64,
    /// The profile's price of one, if any.
    price: Option<f64>,
    /// Sheets of it at most.
    limit: usize,
    label: String,
}

/// Lanes of lamellas assigned to one sheet of a size.
#[derive(Debug, Clone)]
struct SheetPlan {
    size: usize,
    /// Indices into the lamella items, one list per lane.
    lanes: Vec<Vec<usize>>,
}

/// What one nest needs to know, built once.
struct Ctx<'a> {
    kit: &'a Kit,
    profile: &'a Profile,
    margin: f64,
    gap: f64,
    height: f64,
    rotations: Vec<u32>,
    lamella_rot: u32,
    sizes: Vec<Size>,
    /// Sizes by cost per usable area, ties by index.
    by_value: Vec<usize>,
    /// (part, copy) of every lamella copy.
    items: Vec<(usize, u32)>,
    /// Item sizes for the lanes: length + gap.
    item_len: Vec<f64>,
    /// Other parts, largest bounding box first.
    others: Vec<usize>,
    /// Per part: the lattice blocks its copies may go in, for star
    /// washers that pack denser with their arms interleaved
    /// ([`lattice`]); empty for every other part.
    blocks: Vec<Vec<lattice::Block>>,
    /// Per part: its net area, mm² (`net_area_mm2`, taken once).
    areas: Vec<f64>,
}

/// Sheets and the number of lamella lanes on them.
type Placed = (Vec<SheetNest>, usize);

/// Rounds of tail improvement at most.
const TAIL_ROUNDS: usize = 8;
/// The tail improvement replaces at most this many sheets of one size.
const TAIL_SHEETS: usize = 2;

impl<'a> Ctx<'a> {
    fn new(kit: &'a Kit, profile: &'a Profile) -> Result<Ctx<'a>> {
        let c = &profile.cutting;
        let m = c.edge_margin_mm;
        let g = c.kerf_mm + c.part_spacing_mm;
        let h = profile.section.height_mm;
        let st = &profile.stock;
        let sizes: Vec<Size> = st
            .sizes
            .iter()
            .map(|z| {
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
            })
            .collect();
        let mut by_value: Vec<usize> = (0..sizes.len()).collect();
        by_value.sort_by(|&a, &b| {
            let v = |s: &Size| s.cost / (s.lu * s.wu);
            v(&sizes[a]).total_cmp(&v(&sizes[b])).then(a.cmp(&b))
        });
        let rotations = c.allowed_rotations_deg.clone();
        let fail = |part: &str, what: String| Error::fabrication_part(&profile.source, part, what);
        // Every part must fit some size in an allowed rotation.
        for p in &kit.parts {
            let (x0, y0, x1, y1) = bbox(p);
            let (w, ht) = (x1 - x0, y1 - y0);
            if !st.holds(w, ht, m, &rotations) {
                let usable = if sizes.len() == 1 {
                    format!(
                        "the {:.0} × {:.0} mm usable sheet",
                        sizes[0].lu, sizes[0].wu
                    )
                } else {
                    let list: Vec<String> = sizes
                        .iter()
                        .map(|s| format!("{}: {:.0} × {:.0} mm", s.label, s.lu, s.wu))
                        .collect();
                    format!("the usable area of any stock size ({})", list.join(", "))
                };
                return Err(fail(
                    &p.id,
                    format!(
                        "{w:.0} × {ht:.0} mm does not fit {usable} in any allowed rotation \
                         ({rotations:?}°)"
                    ),
                ));
            }
        }
        let mut items: Vec<(usize, u32)> = Vec::new();
        for (i, p) in kit.parts.iter().enumerate() {
            if p.kind == PartKind::Lamella {
                for copy in 0..p.count {
                    items.push((i, copy));
                }
            }
        }
        let item_len: Vec<f64> = items
            .iter()
            .map(|&(i, _)| kit.parts[i].length_mm + g)
            .collect();
        if let Some(&(first, _)) = items.first() {
            let id = &kit.parts[first].id;
            if !rotations.iter().any(|r| r % 180 == 0) {
                return Err(fail(
                    id,
                    "lamellas lie along the sheet, but the profile allows neither 0° nor 180°"
                        .into(),
                ));
            }
            if sizes.iter().all(|s| s.lanes == 0) {
                let wu = sizes.iter().map(|s| s.wu).fold(0.0, f64::max);
                return Err(fail(
                    id,
                    format!("a {h} mm lamella does not fit across the {wu:.0} mm usable sheet"),
                ));
            }
            // Each lamella into the lanes of some size.
            for (k, &(i, _)) in items.iter().enumerate() {
                if !sizes
                    .iter()
                    .any(|s| s.lanes > 0 && fits(item_len[k], s.cap))
                {
                    return Err(fail(
                        &kit.parts[i].id,
                        format!(
                            "a {:.0} mm lamella fits the lanes of no stock size",
                            kit.parts[i].length_mm
                        ),
                    ));
                }
            }
        }
        let mut others: Vec<usize> = (0..kit.parts.len())
            .filter(|&i| kit.parts[i].kind != PartKind::Lamella)
            .collect();
        let area = |i: usize| {
            let (x0, y0, x1, y1) = bbox(&kit.parts[i]);
            (x1 - x0) * (y1 - y0)
        };
        others.sort_by(|&a, &b| area(b).total_cmp(&area(a)).then(a.cmp(&b)));
        let blocks = kit
            .parts
            .iter()
            .map(|p| lattice_blocks(p, g, &rotations, &sizes))
            .collect();
        Ok(Ctx {
            kit,
            profile,
            margin: m,
            gap: g,
            height: h,
            lamella_rot: if rotations.contains(&0) { 0 } else { 180 },
            rotations,
            sizes,
            by_value,
            items,
            item_len,
            others,
            blocks,
            areas: kit.parts.iter().map(net_area_mm2).collect(),
        })
    }

    fn fail_stock(&self, what: String) -> Error {
        Error::Fabrication {
            profile: self.profile.source.clone(),
            at: "stock".into(),
            node: None,
            what: crate::error::one_line(&what),
        }
    }

    /// A part's bounding box size turned by `rot`.
    fn dims(&self, i: usize, rot: u32) -> (f64, f64) {
        let (x0, y0, x1, y1) = bbox(&self.kit.parts[i]);
        if rot % 180 == 90 {
            (y1 - y0, x1 - x0)
        } else {
            (x1 - x0, y1 - y0)
        }
    }

    fn cost(&self, sheets: &[SheetPlan]) -> f64 {
        sheets.iter().map(|s| self.sizes[s.size].cost).sum()
    }

    /// Lamella `items` into lanes and sheets: the first size of `order`
    /// with sheets left takes the items that fit its lanes (packed by
    /// [`binpack::pack`]); items too long for it go first to the longer
    /// sizes after it in `order`, whose free lanes then take its lanes
    /// first; lanes beyond its count limit go on to the next sizes. `Err`
    /// holds the items no sheet is left for.
    fn assign(
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
    fn tail_variants(&self, plan: &[SheetPlan]) -> Vec<Vec<SheetPlan>> {
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

    /// The sheets of a lane plan with the lamellas in their lanes, then
    /// every other part by its bounding box onto the skylines (new sheets
    /// of the best-value size with sheets left that holds the part), then
    /// sheets holding no lamella moved to a cheaper size where all their
    /// parts fit it.
    fn place(&self, plan: &[SheetPlan]) -> Result<Placed> {
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

    fn new_sheet(&self, size: usize) -> SheetNest {
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

    /// `max_count 3 of 3000 × 1500, …` for the sizes with a limit.
    fn limits(&self) -> String {
        let list: Vec<String> = self
            .sizes
            .iter()
            .filter(|z| z.limit < usize::MAX)
            .map(|z| format!("{} of {}", z.limit, z.label))
            .collect();
        format!("max_count {}", list.join(", "))
    }

    /// The cheapest full nest over the sheet sizes: for each size as the
    /// first choice (best value first), the lane plan of [`Ctx::assign`],
    /// improved by [`Ctx::tail_variants`] while the whole nest gets
    /// cheaper, then `finish`ed (the passes by true outline); ties go to
    /// fewer sheets, then the earlier candidate.
    fn sheets(&self, finish: &dyn Fn(&mut Vec<SheetNest>)) -> Result<Placed> {
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

    /// A coil cut to any length: one sheet of the coil's width, the
    /// lamellas balanced over its lanes (MULTIFIT: the shortest lane
    /// length at which [`binpack::pack`] needs no more lanes than fit
    /// across, by bisection from the longest-first greedy), the other parts
    /// after them; its length is what is used.
    fn coil(&self) -> Result<Placed> {
        let lanes = balance(&self.item_len, self.sizes[0].lanes);
        self.place(&[SheetPlan { size: 0, lanes }])
    }
}

/// Lattice blocks tried, width (along the sheet) × height, mm: squares big enough to pack densely on bare stock, and long low
/// blocks for the lamella sheets' lane tails (a strip of height H holds
/// about (H − 90)/2973 washers per mm by the lattice against 1/93.2 by
/// boxes, so from about 125 mm up the lattice wins there too).
const BLOCKS_MM: [(f64, f64); 8] = [
    (400.0, 400.0),
    (800.0, 200.0),
    (800.0, 150.0),
    (300.0, 300.0),
    (400.0, 200.0),
    (400.0, 150.0),
    (200.0, 200.0),
    (150.0, 150.0),
];

/// Fewest copies of a star washer worth packing in lattice blocks.
const MIN_BLOCK_COPIES: u32 = 4;

/// Lattice blocks of part `p`'s copies: only for star
/// washers with enough copies, where the profile allows them unturned
/// and the lattice beats boxes ([`lattice::star_lattice`]).
fn lattice_blocks(p: &Part, gap: f64, rotations: &[u32], sizes: &[Size]) -> Vec<lattice::Block> {
    if p.kind != PartKind::Washer || p.count < MIN_BLOCK_COPIES || !rotations.contains(&0) {
        return Vec::new();
    }
    let Some(lat) = lattice::star_lattice(&p.outline_part_mm, gap) else {
        return Vec::new();
    };
    let (x0, y0, x1, y1) = bbox(p);
    let (w, h) = (x1 - x0, y1 - y0);
    // Every block fits every size's usable sheet.
    let (room_x, room_y) = sizes
        .iter()
        .fold((f64::INFINITY, f64::INFINITY), |(x, y), z| {
            (x.min(z.lu), y.min(z.wu))
        });
    BLOCKS_MM
        .iter()
        .filter(|&&(bw, bh)| bw <= room_x && bh <= room_y)
        .map(|&(bw, bh)| lattice::block(&lat, w, h, bw, bh))
        // A block must hold more than boxes would in its square.
        .filter(|b| {
            let (bw, bh) = b.extent_mm(b.len());
            let by_boxes =
                (((bw + gap) / (w + gap)).floor() * ((bh + gap) / (h + gap)).floor()) as usize;
            b.len() > by_boxes
        })
        .collect()
}

/// Whether an item fits a lane of capacity `cap` (to the bin packing's
/// tolerance).
fn fits(item: f64, cap: f64) -> bool {
    item <= cap * (1.0 + binpack::FIT_TOLERANCE)
}

/// Items of `sizes` over `k` lanes of any length, the longest lane as short
/// as MULTIFIT finds it (Coffman, Garey & Johnson 1978): the longest-first
/// greedy (each item onto the shortest lane) bounds it from above, the
/// larger of the longest item and the mean from below; bisection to 0.5 mm
/// on the capacity at which [`binpack::pack`] needs at most `k` bins.
fn balance(sizes: &[f64], k: usize) -> Vec<Vec<usize>> {
    if sizes.is_empty() || k == 0 {
        return Vec::new();
    }
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

/// The nest's figures and bounds.
fn summarize(
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

/// Named invariant: every part inside its sheet's margins, in an allowed
/// rotation, placed exactly its count of times, and no two parts' true
/// outlines closer than kerf + spacing (polygon-to-polygon distance, where
/// their bounding boxes come closer than that; boxes apart means the true
/// shapes are).
pub fn check_nest(kit: &Kit, nest: &Nest, profile: &Profile) -> std::result::Result<(), String> {
    let c = &profile.cutting;
    let m = c.edge_margin_mm;
    let g = c.kerf_mm + c.part_spacing_mm;
    let eps = 1e-6;
    let mut placed: Vec<u32> = vec![0; kit.parts.len()];
    let mut seen: std::collections::HashSet<(usize, u32)> = std::collections::HashSet::new();
    for s in &nest.sheets {
        let mut boxes: Vec<((f64, f64, f64, f64), usize)> = Vec::with_capacity(s.placements.len());
        let mut outlines: Vec<Option<Vec<Point>>> = vec![None; s.placements.len()];
        for (k, pl) in s.placements.iter().enumerate() {
            let p = &kit.parts[pl.part];
            if !c.allowed_rotations_deg.contains(&pl.rotation_deg) {
                return Err(format!(
                    "{}: {} turned {}°, not allowed",
                    s.id, p.id, pl.rotation_deg
                ));
            }
            if !seen.insert((pl.part, pl.copy)) || pl.copy >= p.count {
                return Err(format!(
                    "{}: {} copy {} placed twice or beyond its count",
                    s.id, p.id, pl.copy
                ));
            }
            placed[pl.part] += 1;
            let b = placed_bbox(p, pl);
            if b.0 < m - eps
                || b.1 < m - eps
                || b.2 > s.length_mm - m + eps
                || b.3 > s.width_mm - m + eps
            {
                return Err(format!(
                    "{}: {} at {:?} is outside the margins",
                    s.id, p.id, b
                ));
            }
            boxes.push((b, k));
        }
        // Sweep along x: boxes whose x-extents come within the gap.
        boxes.sort_by(|a, b| a.0 .0.total_cmp(&b.0 .0));
        let mut active: Vec<((f64, f64, f64, f64), usize)> = Vec::new();
        for (b, k) in boxes {
            active.retain(|a| a.0 .2 + g > b.0 + eps);
            for &(a, j) in &active {
                let apart_y = a.3 + g <= b.1 + eps || b.3 + g <= a.1 + eps;
                let apart_x = a.2 + g <= b.0 + eps;
                if apart_y || apart_x {
                    continue;
                }
                // Boxes closer than the gap: the true outlines decide.
                for q in [j, k] {
                    if outlines[q].is_none() {
                        let pl = &s.placements[q];
                        outlines[q] = Some(outline::placed_outline(&kit.parts[pl.part], pl));
                    }
                }
                let (Some(oa), Some(ob)) = (&outlines[j], &outlines[k]) else {
                    continue;
                };
                let d = outline::distance(oa, ob, g);
                if d < g - eps {
                    return Err(format!(
                        "{}: {} is {d:.3} mm from {}, closer than {g} mm",
                        s.id,
                        kit.parts[s.placements[k].part].id,
                        kit.parts[s.placements[j].part].id
                    ));
                }
            }
            active.push((b, k));
        }
    }
    for (i, p) in kit.parts.iter().enumerate() {
        if placed[i] != p.count {
            return Err(format!(
                "{}: placed {} times, count {}",
                p.id, placed[i], p.count
            ));
        }
    }
    Ok(())
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
