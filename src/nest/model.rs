//! What the nest gives back: the placements on each sheet, the sheets, the
//! figures and the stock used; and the placement's frame (a part turned
//! about its origin, then translated).

use crate::fabricate::part::Part;
use crate::geom::plane;
use crate::profile::{Cutting, StockForm};
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

/// The nest of a kit. What [`nest`](super::nest) returns holds the
/// invariant [`check_nest`](super::check_nest) checks: every copy of every
/// part placed exactly once, in an allowed rotation, inside its sheet's
/// margins, and no two parts' true outlines closer than kerf + part
/// spacing; every sheet holds at least one part; the same kit and profile
/// give the same nest, placement for placement.
#[derive(Debug, Clone, PartialEq)]
pub struct Nest {
    /// Sheets in order (by stock size, then as filled), `S01`, `S02`, ….
    pub sheets: Vec<SheetNest>,
    /// Counts, bounds, utilisation, cost.
    pub summary: NestSummary,
    /// Sheets per stock size, in size order.
    pub stock_used: Vec<StockUse>,
    /// Currency of the prices, if the profile names one.
    pub currency: Option<String>,
    /// The stock groups nested, in the profile's group order (those with
    /// parts): each one material and thickness, its sheets a run of
    /// `sheets`.
    pub groups: Vec<GroupNest>,
}

/// The nest of one stock group: its parts (one material, one thickness)
/// on its own stock.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupNest {
    /// The group's name (`lamella-1.5`, `washer-3`, …).
    pub name: String,
    /// Its material.
    pub material: String,
    /// Its thickness (a bar: the section's side), mm.
    pub thickness_mm: f64,
    /// Sheets, coil or bars.
    pub form: StockForm,
    /// Its sheets: indices into [`Nest::sheets`].
    pub sheets: std::ops::Range<usize>,
    /// Its figures and bounds (on its own stock).
    pub summary: NestSummary,
    /// Its sheets per stock size (`size` indexes the group's sizes).
    pub stock_used: Vec<StockUse>,
    /// The cutting its sheets were nested with.
    pub cutting: Cutting,
}

impl Nest {
    /// The group of sheet `k` (index into [`Nest::groups`]).
    pub fn group_of_sheet(&self, k: usize) -> usize {
        self.groups
            .iter()
            .position(|g| g.sheets.contains(&k))
            .unwrap_or(0)
    }
}

/// Bounding box (x0, y0, x1, y1) of points ([`plane::bounds`]).
pub(crate) fn bounds(v: &[Point]) -> (f64, f64, f64, f64) {
    let r = plane::bounds(v);
    (r.x0, r.y0, r.x1, r.y1)
}

/// Bounding box of a part's outline in its own frame.
pub(super) fn bbox(p: &Part) -> (f64, f64, f64, f64) {
    bounds(&p.outline_part_mm)
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
pub(super) fn place_at(part: usize, p: &Part, copy: u32, rot: u32, x: f64, y: f64) -> Placement {
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
