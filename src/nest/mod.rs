//! Nesting the kit onto stock (issue 9): lamellas into lanes along the
//! sheets, small parts and edge bands into what is left.
//!
//! A sheet's usable area is its length × width less the edge margin all
//! round; parts keep kerf + part spacing (`gap`) from each other. Lamellas
//! (all one height h) lie along the sheet in lanes h apart plus the gap;
//! which lamella goes into which lane is one-dimensional bin packing
//! ([`binpack`]: item = length + gap, capacity = usable length + gap), and
//! lanes fill the sheets in order. Other parts (shear blocks, splice plates,
//! washers, studs, edge strips) go by their bounding boxes, in an allowed
//! rotation, first into the lane tails (the free ends of the lanes, when
//! they are no taller than a lane), then in shelves over the free width of
//! the last sheet and new sheets.
//!
//! Lower bounds: the area bound ⌈Σ part area / usable sheet area⌉ and the
//! lane bound ⌈L2(lamellas) / lanes per sheet⌉ (Martello–Toth L2 on the lane
//! problem); the nest reports both and the gap to the larger.
//!
//! Plain data in (`Kit`, `Profile`), plain data out ([`Nest`]);
//! deterministic (no threads, ties broken by index). A placement maps
//! part-local (x, y) to sheet coordinates by rotating about the origin by
//! `rotation_deg` (counter-clockwise), then translating by (x_mm, y_mm); the
//! sheet's x runs along its length.

pub mod binpack;
pub mod export;

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

/// One sheet of stock and what is cut from it.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetNest {
    /// `S01`, `S02`, …
    pub id: String,
    /// Along the sheet's y, mm.
    pub width_mm: f64,
    /// Along the sheet's x, mm.
    pub length_mm: f64,
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
    /// ⌈Σ part area / usable sheet area⌉.
    pub area_bound_sheets: usize,
    /// ⌈L2(lamella lanes) / lanes per sheet⌉.
    pub lane_bound_sheets: usize,
    /// Lanes that fit across one sheet.
    pub lanes_per_sheet: usize,
    /// Lanes the lamellas fill.
    pub lanes_used: usize,
    /// Martello–Toth L2 on the lanes.
    pub lane_bound_lanes: usize,
    /// Part area over the area of the sheets used.
    pub utilization: f64,
    /// Wall-clock time of the nest, s (not part of any output that must be
    /// byte-stable).
    pub seconds: f64,
}

/// The nest of a kit.
#[derive(Debug, Clone, PartialEq)]
pub struct Nest {
    /// Sheets in order.
    pub sheets: Vec<SheetNest>,
    /// Counts, bounds, utilisation.
    pub summary: NestSummary,
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

    /// Lowest place (x, y) for a box w × ht with `gap` above it, within
    /// x ≤ x_max and y + ht ≤ y_max: candidates at segment starts.
    fn fit(&self, w: f64, ht: f64, gap: f64, x_max: f64, y_max: f64) -> Option<(f64, f64)> {
        let mut best: Option<(f64, f64)> = None;
        let n = self.segs.len();
        for i in 0..n {
            let s = self.segs[i].0;
            if s + ht > y_max + 1e-9 {
                break;
            }
            // The level over [s, s + ht + gap): the segments from i on that
            // start inside it (a window, not the whole skyline).
            let top = (s + ht + gap).min(self.y_hi);
            let mut x = f64::NEG_INFINITY;
            for &(start, level) in &self.segs[i..] {
                if start >= top - 1e-9 {
                    break;
                }
                x = x.max(level);
            }
            if x + w <= x_max + 1e-9 && best.is_none_or(|b| x < b.0 - 1e-9) {
                best = Some((x, s));
            }
        }
        best
    }
}

/// Nest every part of the kit onto the profile's stock.
pub fn nest(kit: &Kit, profile: &Profile) -> Result<Nest> {
    let t0 = std::time::Instant::now();
    let c = &profile.cutting;
    let (sheet_l, sheet_w) = (profile.stock.length_mm, profile.stock.width_mm);
    let m = c.edge_margin_mm;
    let g = c.kerf_mm + c.part_spacing_mm;
    let (lu, wu) = (sheet_l - 2.0 * m, sheet_w - 2.0 * m);
    let rotations: Vec<u32> = c.allowed_rotations_deg.clone();
    let quarter = rotations.iter().any(|r| r % 180 == 90);
    let h = profile.section.height_mm;
    let fail = |part: &str, what: String| Error::fabrication_part(&profile.source, part, what);

    // Every part must fit a sheet in some allowed rotation.
    let along_ok = rotations.iter().any(|r| r % 180 == 0);
    for p in &kit.parts {
        let (x0, y0, x1, y1) = bbox(p);
        let (w, ht) = (x1 - x0, y1 - y0);
        let fits_along = along_ok && w <= lu && ht <= wu;
        let fits_across = quarter && ht <= lu && w <= wu;
        if !fits_along && !fits_across {
            return Err(fail(
                &p.id,
                format!(
                    "{w:.0} × {ht:.0} mm does not fit the {lu:.0} × {wu:.0} mm usable sheet in any \
                     allowed rotation ({rotations:?}°)"
                ),
            ));
        }
    }
    // Lamellas lie along the sheet: 0° if allowed, else 180°.
    let lamella_rot: u32 = if rotations.contains(&0) { 0 } else { 180 };
    // Lamellas into lanes.
    let lanes_per_sheet = ((wu + g) / (h + g)).floor().max(0.0) as usize;
    let mut lamella_items: Vec<(usize, u32)> = Vec::new();
    for (i, p) in kit.parts.iter().enumerate() {
        if p.kind == PartKind::Lamella {
            for copy in 0..p.count {
                lamella_items.push((i, copy));
            }
        }
    }
    let sizes: Vec<f64> = lamella_items
        .iter()
        .map(|&(i, _)| kit.parts[i].length_mm + g)
        .collect();
    let capacity = lu + g;
    let (lanes, lane_bound_lanes) = if lamella_items.is_empty() {
        (Vec::new(), 0)
    } else {
        if !along_ok {
            return Err(fail(
                &kit.parts[lamella_items[0].0].id,
                "lamellas lie along the sheet, but the profile allows neither 0° nor 180°".into(),
            ));
        }
        if lanes_per_sheet == 0 {
            return Err(fail(
                &kit.parts[lamella_items[0].0].id,
                format!("a {h} mm lamella does not fit across the {wu:.0} mm usable sheet"),
            ));
        }
        let packing = binpack::pack(&sizes, capacity)
            .map_err(|e| fail(&kit.parts[lamella_items[0].0].id, e))?;
        (packing.bins, binpack::lower_bound_l2(&sizes, capacity))
    };
    let mut sheets: Vec<SheetNest> = Vec::new();
    let new_sheet = |k: usize| SheetNest {
        id: format!("S{:02}", k + 1),
        width_mm: sheet_w,
        length_mm: sheet_l,
        placements: Vec::new(),
        part_area_mm2: 0.0,
    };
    // Lane tails: (sheet, x where free space starts, lane bottom y).
    let mut tails: Vec<(usize, f64, f64)> = Vec::new();
    for (j, lane) in lanes.iter().enumerate() {
        let sheet = j / lanes_per_sheet;
        while sheets.len() <= sheet {
            sheets.push(new_sheet(sheets.len()));
        }
        let y = m + (j % lanes_per_sheet) as f64 * (h + g);
        let mut x = m;
        for &item in lane {
            let (i, copy) = lamella_items[item];
            let p = &kit.parts[i];
            sheets[sheet]
                .placements
                .push(place_at(i, p, copy, lamella_rot, x, y));
            x += p.length_mm + g;
        }
        tails.push((sheet, x, y));
    }

    // Other parts by their bounding boxes, largest first, into the free
    // space of the sheets: a skyline over the sheet's width whose level is
    // the first free x (the lanes' tails, then the bare sheet below them);
    // each part at the lowest level it fits (then the lowest y), in the
    // allowed rotation that gets it lowest, on the first sheet with room
    // (first fit per part, in sheet order), else on a new sheet.
    let mut skylines: Vec<Skyline> = (0..sheets.len())
        .map(|k| {
            let mut sky = Skyline::new(m, m + wu, m);
            for (j, t) in tails.iter().enumerate() {
                if t.0 == k {
                    let y0 = m + (j % lanes_per_sheet) as f64 * (h + g);
                    sky.raise(y0, y0 + h + g, t.1);
                }
            }
            sky
        })
        .collect();
    let mut others: Vec<usize> = (0..kit.parts.len())
        .filter(|&i| kit.parts[i].kind != PartKind::Lamella)
        .collect();
    let dims = |i: usize, rot: u32| {
        let (x0, y0, x1, y1) = bbox(&kit.parts[i]);
        if rot % 180 == 90 {
            (y1 - y0, x1 - x0)
        } else {
            (x1 - x0, y1 - y0)
        }
    };
    others.sort_by(|&a, &b| {
        let (wa, ha) = dims(a, 0);
        let (wb, hb) = dims(b, 0);
        (wb * hb).total_cmp(&(wa * ha)).then(a.cmp(&b))
    });
    for &i in &others {
        let p = &kit.parts[i];
        let mut first_sheet = 0;
        for copy in 0..p.count {
            let mut placed = false;
            let mut k = first_sheet;
            while !placed {
                if k == skylines.len() {
                    sheets.push(new_sheet(sheets.len()));
                    skylines.push(Skyline::new(m, m + wu, m));
                }
                // The best rotation on this sheet: lowest x, then lowest y.
                let best = rotations
                    .iter()
                    .filter_map(|&r| {
                        let (w, ht) = dims(i, r);
                        skylines[k]
                            .fit(w, ht, g, m + lu, m + wu)
                            .map(|(x, y)| (x, y, r, w, ht))
                    })
                    .min_by(|a, b| {
                        a.0.total_cmp(&b.0)
                            .then(a.1.total_cmp(&b.1))
                            .then(a.2.cmp(&b.2))
                    });
                match best {
                    Some((x, y, r, w, ht)) => {
                        sheets[k].placements.push(place_at(i, p, copy, r, x, y));
                        skylines[k].raise(y, y + ht + g, x + w + g);
                        placed = true;
                        first_sheet = k;
                    }
                    None if skylines[k].is_bare(m) => {
                        return Err(fail(
                            &p.id,
                            "does not fit an empty sheet in any allowed rotation".into(),
                        ));
                    }
                    None => k += 1,
                }
            }
        }
    }
    sheets.retain(|s| !s.placements.is_empty());
    for (k, s) in sheets.iter_mut().enumerate() {
        s.id = format!("S{:02}", k + 1);
        s.part_area_mm2 = s
            .placements
            .iter()
            .map(|pl| net_area_mm2(&kit.parts[pl.part]))
            .sum();
    }

    let total_area: f64 = kit
        .parts
        .iter()
        .map(|p| net_area_mm2(p) * f64::from(p.count))
        .sum();
    let area_bound_sheets = (total_area / (lu * wu) * (1.0 - 1e-12)).ceil() as usize;
    let lane_bound_sheets = if lanes_per_sheet > 0 {
        lane_bound_lanes.div_ceil(lanes_per_sheet)
    } else {
        0
    };
    let used_area = sheets.len() as f64 * sheet_l * sheet_w;
    let summary = NestSummary {
        sheets_used: sheets.len(),
        lower_bound_sheets: area_bound_sheets.max(lane_bound_sheets),
        area_bound_sheets,
        lane_bound_sheets,
        lanes_per_sheet,
        lanes_used: lanes.len(),
        lane_bound_lanes,
        utilization: if used_area > 0.0 {
            total_area / used_area
        } else {
            0.0
        },
        seconds: t0.elapsed().as_secs_f64(),
    };
    let nest = Nest { sheets, summary };
    debug_assert_eq!(check_nest(kit, &nest, profile), Ok(()));
    Ok(nest)
}

/// Named invariant: every part inside its sheet's margins, in an allowed
/// rotation, placed exactly its count of times, and no two parts' boxes
/// closer than kerf + spacing (boxes apart means the true shapes are).
pub fn check_nest(kit: &Kit, nest: &Nest, profile: &Profile) -> std::result::Result<(), String> {
    let c = &profile.cutting;
    let m = c.edge_margin_mm;
    let g = c.kerf_mm + c.part_spacing_mm;
    let eps = 1e-6;
    let mut placed: Vec<u32> = vec![0; kit.parts.len()];
    let mut seen: std::collections::HashSet<(usize, u32)> = std::collections::HashSet::new();
    for s in &nest.sheets {
        let mut boxes: Vec<((f64, f64, f64, f64), usize)> = Vec::with_capacity(s.placements.len());
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
        let mut active: Vec<(f64, f64, f64, f64)> = Vec::new();
        for (b, k) in boxes {
            active.retain(|a| a.2 + g > b.0 + eps);
            for a in &active {
                let apart_y = a.3 + g <= b.1 + eps || b.3 + g <= a.1 + eps;
                let apart_x = a.2 + g <= b.0 + eps;
                if !apart_y && !apart_x {
                    return Err(format!(
                        "{}: {} is closer than {g} mm to another part",
                        s.id, kit.parts[s.placements[k].part].id
                    ));
                }
            }
            active.push(b);
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
