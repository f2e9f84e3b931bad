//! The edge-band pass by occupancy rasters ([`place_bands`]).
//!
//! Edge bands are long, thin, bowed strips: their boxes are mostly empty,
//! and they pack only as far as each one finds the room under another's
//! bow. Every band is taken off the sheets and placed again, the most bowed
//! first, on the first sheet where a bottom-left search finds room: the
//! lowest place, then the leftmost, over every allowed rotation, including
//! places under an overhang (a hole under a placed band's bow) and in the
//! lamella sheets' lane tails.
//!
//! Each sheet is a raster of columns [`CELL_X_MM`] wide and rows
//! [`CELL_Y_MM`] high (coarser on large sheets, at most [`MAX_COLUMNS`] ×
//! [`MAX_ROWS`] cells) over its usable area grown by half the gap. A part
//! occupies, in each column, every row between the lowest and the highest
//! point of its outline over the column widened by half the gap on each
//! side, then grown by half the gap up and down: a superset of its outline
//! grown by half the gap. Two parts whose cells are disjoint are at least
//! the gap apart, so the search is conservative; each place it chooses is
//! then confirmed in f64 by
//! [`polygon_distance`](plane::polygon_distance) against the neighbours.
//! A band moves by whole cells from the margin corner, so its cells are
//! made once per rotation and shifted.
//!
//! The search in a column is a drop: from the bottom row, test the band's
//! columns; at an occupied cell, jump to the lowest place clear of it, which
//! never skips a free place; the first place with no conflict is the lowest
//! in that column. Deterministic: fixed orders, ties by index.

use super::model::{bounds, place_at, rotate, Placement, SheetNest};
use super::outline::{placed_outline, Setting};
use crate::fabricate::part::{Part, PartKind};
use crate::geom::plane;
use kurbo::Point;

/// Column width of a sheet's raster, mm (coarser where the sheet is longer
/// than [`MAX_COLUMNS`] columns).
pub const CELL_X_MM: f64 = 1.0;
/// Row height of a sheet's raster, mm (coarser where the sheet is wider
/// than [`MAX_ROWS`] rows).
pub const CELL_Y_MM: f64 = 0.25;
/// Columns of a raster at most.
pub const MAX_COLUMNS: f64 = 4096.0;
/// Rows of a raster at most.
pub const MAX_ROWS: f64 = 2048.0;
/// Clearance added to half the gap beyond what the raster already keeps,
/// mm: the f64 confirmation's margin over its 10⁻⁶ mm tolerance.
const SAFETY_MM: f64 = 0.001;
/// The slide to contact stops at steps this small, mm.
const SLIDE_STOP_MM: f64 = 0.02;
/// Columns between the places tried along a row (each then refined by one
/// column).
const STEP_COLUMNS: usize = 8;

/// The cell size and origin of rasters of one sheet size.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Cells {
    /// Lower-left corner of cell (0, 0), sheet frame, mm.
    x0_mm: f64,
    y0_mm: f64,
    /// Column width and row height, mm.
    dx_mm: f64,
    dy_mm: f64,
    /// Half the gap plus the safety, mm.
    half_gap_mm: f64,
    columns: usize,
    rows: usize,
}

impl Cells {
    fn new(s: &SheetNest, margin_mm: f64, gap_mm: f64) -> Self {
        let half = 0.5 * gap_mm + SAFETY_MM;
        let (lu, wu) = (s.length_mm - 2.0 * margin_mm, s.width_mm - 2.0 * margin_mm);
        let dx = CELL_X_MM.max((lu + 2.0 * half) / MAX_COLUMNS);
        let dy = CELL_Y_MM.max((wu + 2.0 * half) / MAX_ROWS);
        Cells {
            x0_mm: margin_mm - half,
            y0_mm: margin_mm - half,
            dx_mm: dx,
            dy_mm: dy,
            half_gap_mm: half,
            columns: ((lu + 2.0 * half) / dx).ceil() as usize + 1,
            rows: ((wu + 2.0 * half) / dy).ceil() as usize + 1,
        }
    }

    /// The cells of `outline` (sheet frame) grown by half the gap: for each
    /// column it reaches, the lowest and highest row, clamped to the raster.
    fn footprint(&self, outline: &[Point]) -> Footprint {
        let h = self.half_gap_mm;
        let b = bounds(outline);
        let col = |x: f64| ((x - self.x0_mm) / self.dx_mm).floor();
        let c0 = col(b.0 - h).max(0.0) as usize;
        let c1 = (col(b.2 + h).max(0.0) as usize).min(self.columns - 1);
        let n = c1 + 1 - c0.min(c1 + 1);
        let mut lo = vec![f64::INFINITY; n];
        let mut hi = vec![f64::NEG_INFINITY; n];
        let m = outline.len();
        for k in 0..m {
            let (p, q) = (outline[k], outline[(k + 1) % m]);
            let (xa, xb) = (p.x.min(q.x) - h, p.x.max(q.x) + h);
            let ca = (col(xa).max(c0 as f64) as usize).max(c0);
            let cb = (col(xb).max(0.0) as usize).min(c1);
            for c in ca..=cb {
                // The edge over the column widened by h each side.
                let wa = self.x0_mm + c as f64 * self.dx_mm - h;
                let wb = wa + self.dx_mm + 2.0 * h;
                let (ya, yb) = clip_y(p, q, wa, wb);
                let i = c - c0;
                lo[i] = lo[i].min(ya.min(yb));
                hi[i] = hi[i].max(ya.max(yb));
            }
        }
        let row = |y: f64| ((y - self.y0_mm) / self.dy_mm).floor();
        let last = (self.rows - 1) as f64;
        let spans = lo
            .iter()
            .zip(&hi)
            .map(|(&a, &b)| {
                if a > b {
                    (1, 0)
                } else {
                    (
                        row(a - h).clamp(0.0, last) as u32,
                        row(b + h).clamp(0.0, last) as u32,
                    )
                }
            })
            .collect();
        Footprint { first: c0, spans }
    }
}

/// The y of segment p–q at the ends of its part within x ∈ [a, b]
/// (the segment's own ends where it is vertical or inside).
fn clip_y(p: Point, q: Point, a: f64, b: f64) -> (f64, f64) {
    if (q.x - p.x).abs() < 1e-12 {
        return (p.y, q.y);
    }
    let at = |x: f64| p.y + (x - p.x) * (q.y - p.y) / (q.x - p.x);
    let (xl, xr) = (p.x.min(q.x).max(a), p.x.max(q.x).min(b));
    (at(xl), at(xr))
}

/// A part's cells: from column `first`, per column the lowest and highest
/// row (lowest > highest where the column is empty).
#[derive(Clone, Debug)]
struct Footprint {
    first: usize,
    spans: Vec<(u32, u32)>,
}

/// One sheet's occupied cells, column by column.
struct Raster {
    cells: Cells,
    words: usize,
    bits: Vec<u64>,
}

impl Raster {
    fn new(cells: Cells) -> Self {
        let words = cells.rows.div_ceil(64);
        Raster {
            cells,
            words,
            bits: vec![0; words * cells.columns],
        }
    }

    /// Marks `fp` moved by (`di`, `dj`) cells.
    fn mark(&mut self, fp: &Footprint, di: usize, dj: usize) {
        for (k, &(lo, hi)) in fp.spans.iter().enumerate() {
            if lo > hi {
                continue;
            }
            let c = fp.first + k + di;
            let col = &mut self.bits[c * self.words..(c + 1) * self.words];
            let (a, b) = (lo as usize + dj, hi as usize + dj);
            for (w, word) in col.iter_mut().enumerate().take(b / 64 + 1).skip(a / 64) {
                let mut v = !0u64;
                if w == b / 64 && b % 64 != 63 {
                    v &= (1u64 << (b % 64 + 1)) - 1;
                }
                if w == a / 64 {
                    v &= !0u64 << (a % 64);
                }
                *word |= v;
            }
        }
    }

    /// The highest occupied row of column `c` in rows `a..=b`.
    fn highest(&self, c: usize, a: usize, b: usize) -> Option<usize> {
        let col = &self.bits[c * self.words..(c + 1) * self.words];
        let (wa, wb) = (a / 64, b / 64);
        for w in (wa..=wb).rev() {
            let mut v = col[w];
            if w == wb && b % 64 != 63 {
                v &= (1u64 << (b % 64 + 1)) - 1;
            }
            if w == wa {
                v &= !0u64 << (a % 64);
            }
            if v != 0 {
                return Some(w * 64 + 63 - v.leading_zeros() as usize);
            }
        }
        None
    }

    /// The lowest row shift below `below` at which `fp` moved by `di`
    /// columns is clear, rows `0..=dj_max`.
    fn drop_at(&self, fp: &Footprint, di: usize, dj_max: usize, below: usize) -> Option<usize> {
        let mut dj = 0;
        let mut hint = 0;
        let n = fp.spans.len();
        'drop: while dj <= dj_max && dj < below {
            for k in (hint..n).chain(0..hint) {
                let (lo, hi) = fp.spans[k];
                if lo > hi {
                    continue;
                }
                let c = fp.first + k + di;
                if let Some(r) = self.highest(c, lo as usize + dj, hi as usize + dj) {
                    dj = r + 1 - lo as usize;
                    hint = k;
                    continue 'drop;
                }
            }
            return Some(dj);
        }
        None
    }

    /// Whether `fp` moved by (`di`, `dj`) is clear.
    fn clear(&self, fp: &Footprint, di: usize, dj: usize) -> bool {
        fp.spans.iter().enumerate().all(|(k, &(lo, hi))| {
            lo > hi
                || self
                    .highest(fp.first + k + di, lo as usize + dj, hi as usize + dj)
                    .is_none()
        })
    }
}

/// A band turned by one rotation, its box's lower-left corner at the
/// margin corner.
struct Turned {
    rot: u32,
    /// Outline turned, box lower-left at the origin.
    outline: Vec<Point>,
    width_mm: f64,
    height_mm: f64,
}

impl Turned {
    fn new(p: &Part, rot: u32) -> Self {
        let o: Vec<Point> = p.outline_part_mm.iter().map(|&q| rotate(q, rot)).collect();
        let b = bounds(&o);
        Turned {
            rot,
            outline: o.iter().map(|q| Point::new(q.x - b.0, q.y - b.1)).collect(),
            width_mm: b.2 - b.0,
            height_mm: b.3 - b.1,
        }
    }
}

/// A box: (x0, y0, x1, y1), mm.
type BBox = (f64, f64, f64, f64);

/// A sheet as the pass works on it.
struct Board {
    raster: Raster,
    /// True outlines (sheet frame) and their boxes.
    placed: Vec<(Vec<Point>, BBox)>,
    /// Usable area less the parts' net area, mm².
    free_mm2: f64,
}

impl Board {
    fn new(setting: &Setting, s: &SheetNest) -> Self {
        let m = setting.margin_mm;
        let mut raster = Raster::new(Cells::new(s, m, setting.gap_mm));
        let mut placed = Vec::with_capacity(s.placements.len());
        let mut area = 0.0;
        for pl in &s.placements {
            let o = placed_outline(&setting.kit.parts[pl.part], pl);
            raster.mark(&raster.cells.footprint(&o), 0, 0);
            let b = bounds(&o);
            placed.push((o, b));
            area += setting.areas_mm2[pl.part];
        }
        Board {
            raster,
            placed,
            free_mm2: (s.length_mm - 2.0 * m) * (s.width_mm - 2.0 * m) - area,
        }
    }

    /// The lowest, then leftmost, clear place of a band in any of its
    /// rotations on `s`: (row shift, column shift, rotation index).
    fn find(
        &self,
        s: &SheetNest,
        margin_mm: f64,
        turned: &[Turned],
        footprints: &mut Vec<(Cells, Vec<Footprint>)>,
    ) -> Option<(usize, usize, usize)> {
        let cells = &self.raster.cells;
        let (lu, wu) = (s.length_mm - 2.0 * margin_mm, s.width_mm - 2.0 * margin_mm);
        // The band's cells at the margin corner, made once per raster size.
        let at = match footprints.iter().position(|(c, _)| c == cells) {
            Some(k) => k,
            None => {
                let fps = turned
                    .iter()
                    .map(|t| {
                        let corner: Vec<Point> = t
                            .outline
                            .iter()
                            .map(|q| Point::new(q.x + margin_mm, q.y + margin_mm))
                            .collect();
                        cells.footprint(&corner)
                    })
                    .collect();
                footprints.push((*cells, fps));
                footprints.len() - 1
            }
        };
        let mut best: Option<(usize, usize, usize)> = None;
        for (r, t) in turned.iter().enumerate() {
            if t.width_mm > lu + 1e-9 || t.height_mm > wu + 1e-9 {
                continue;
            }
            let fp = &footprints[at].1[r];
            let di_max = ((lu - t.width_mm) / cells.dx_mm + 1e-9).floor() as usize;
            let dj_max = ((wu - t.height_mm) / cells.dy_mm + 1e-9).floor() as usize;
            let mut here: Option<(usize, usize)> = None;
            let mut di = 0;
            loop {
                let below = here.map_or(usize::MAX, |h| h.0);
                if let Some(dj) = self.raster.drop_at(fp, di, dj_max, below) {
                    here = Some((dj, di));
                    if dj == 0 {
                        break;
                    }
                }
                if di == di_max {
                    break;
                }
                di = (di + STEP_COLUMNS).min(di_max);
            }
            let Some((dj, mut di)) = here else {
                continue;
            };
            // The columns the step passed over, at the same row.
            while di > 0 && self.raster.clear(fp, di - 1, dj) {
                di -= 1;
            }
            if best.as_ref().is_none_or(|b| (dj, di) < (b.0, b.1)) {
                best = Some((dj, di, r));
            }
        }
        best
    }

    /// `pl` (its box's lower-left corner at `corner`, a clear place) slid
    /// down, then left, then down again, to contact in f64: by halving
    /// steps from a cell (`cell`), each place confirmed, never past the
    /// margin `m`. The raster's cells leave up to a cell's slack each way;
    /// this takes it back.
    fn slide(
        &self,
        p: &Part,
        pl: Placement,
        corner: (f64, f64),
        cell: (f64, f64),
        m: f64,
        gap_mm: f64,
    ) -> Placement {
        let mut pl = pl;
        let (mut x, mut y) = corner;
        for (axis, first) in [(1, cell.1), (0, cell.0), (1, cell.1)] {
            let mut d = 2.0 * first;
            while d > SLIDE_STOP_MM {
                let at = if axis == 0 { x } else { y };
                let to = (at - d).max(m);
                if to < at {
                    let mut trial = pl;
                    if axis == 0 {
                        trial.x_mm -= at - to;
                    } else {
                        trial.y_mm -= at - to;
                    }
                    if self.confirm(&placed_outline(p, &trial), gap_mm) {
                        pl = trial;
                        if axis == 0 {
                            x = to;
                        } else {
                            y = to;
                        }
                        continue;
                    }
                }
                d *= 0.5;
            }
        }
        pl
    }

    /// Whether outline `o` (sheet frame) is at least the gap from every
    /// part on the board, in f64.
    fn confirm(&self, o: &[Point], gap_mm: f64) -> bool {
        let b = bounds(o);
        let g = gap_mm;
        self.placed.iter().all(|(q, qb)| {
            qb.2 + g <= b.0
                || b.2 + g <= qb.0
                || qb.3 + g <= b.1
                || b.3 + g <= qb.1
                || plane::polygon_distance(o, q, g) >= g + 1e-6
        })
    }
}

/// The edge-band pass: every edge band (`PartKind::EdgeStrip`) taken off
/// the sheets and placed again, the most bowed first (the lower of its
/// boxes' heights over the allowed rotations; then the longest; then by
/// index), on the first sheet where [`Board::find`] gives it a place
/// confirmed in f64: the sheets that keep other parts, in order, then the
/// sheets the bands left empty, in order. Sheets left without a part are
/// dropped. Where a band finds no place at all the sheets stay as they
/// were. Returns how many sheets were dropped.
pub fn place_bands(setting: Setting, sheets: &mut Vec<SheetNest>) -> usize {
    let kit = setting.kit;
    let is_band = |pl: &Placement| kit.parts[pl.part].kind == PartKind::EdgeStrip;
    let mut bands: Vec<Placement> = sheets
        .iter()
        .flat_map(|s| s.placements.iter().filter(|pl| is_band(pl)).copied())
        .collect();
    if bands.is_empty() {
        return 0;
    }
    let turned = |i: usize| -> Vec<Turned> {
        setting
            .rotations_deg
            .iter()
            .map(|&r| Turned::new(&kit.parts[i], r))
            .collect()
    };
    let bow = |i: usize| {
        turned(i)
            .iter()
            .map(|t| t.height_mm)
            .fold(f64::INFINITY, f64::min)
    };
    let len = |i: usize| kit.parts[i].length_mm;
    let keys: Vec<(f64, f64)> = bands
        .iter()
        .map(|pl| (bow(pl.part), len(pl.part)))
        .collect();
    let mut order: Vec<usize> = (0..bands.len()).collect();
    order.sort_by(|&a, &b| {
        keys[b]
            .0
            .total_cmp(&keys[a].0)
            .then(keys[b].1.total_cmp(&keys[a].1))
            .then(bands[a].part.cmp(&bands[b].part))
            .then(bands[a].copy.cmp(&bands[b].copy))
    });
    bands = order.into_iter().map(|k| bands[k]).collect();

    let mut work: Vec<SheetNest> = Vec::with_capacity(sheets.len());
    let mut spare: Vec<SheetNest> = Vec::new();
    for s in sheets.iter() {
        let mut s = s.clone();
        s.placements.retain(|pl| !is_band(pl));
        if s.placements.is_empty() {
            spare.push(s);
        } else {
            work.push(s);
        }
    }
    let mut boards: Vec<Board> = work.iter().map(|s| Board::new(&setting, s)).collect();
    let m = setting.margin_mm;
    for pl in bands {
        let t = turned(pl.part);
        let area = setting.areas_mm2[pl.part];
        let mut placed = false;
        let mut footprints = Vec::new();
        let mut k = 0;
        while k < work.len() + spare.len() && !placed {
            if k == work.len() {
                // Open the next spare sheet.
                let s = spare.remove(0);
                boards.push(Board::new(&setting, &s));
                work.push(s);
            }
            let b = &mut boards[k];
            if b.free_mm2 + 1e-6 >= area {
                if let Some((dj, di, r)) = b.find(&work[k], m, &t, &mut footprints) {
                    let c = &b.raster.cells;
                    let x = m + di as f64 * c.dx_mm;
                    let y = m + dj as f64 * c.dy_mm;
                    let part = &kit.parts[pl.part];
                    let mut new = place_at(pl.part, part, pl.copy, t[r].rot, x, y);
                    let o = placed_outline(part, &new);
                    if !b.confirm(&o, setting.gap_mm) {
                        return 0;
                    }
                    new = b.slide(part, new, (x, y), (c.dx_mm, c.dy_mm), m, setting.gap_mm);
                    let o = placed_outline(part, &new);
                    b.raster.mark(&b.raster.cells.footprint(&o), 0, 0);
                    let ob = bounds(&o);
                    b.placed.push((o, ob));
                    b.free_mm2 -= area;
                    work[k].placements.push(new);
                    placed = true;
                }
            }
            k += 1;
        }
        if !placed {
            return 0;
        }
    }
    let dropped = sheets.len() - work.len();
    *sheets = work;
    dropped
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cells() -> Cells {
        Cells {
            x0_mm: 0.0,
            y0_mm: 0.0,
            dx_mm: 1.0,
            dy_mm: 0.25,
            half_gap_mm: 0.8,
            columns: 400,
            rows: 600,
        }
    }

    /// A bowed band: the ring sector between radii 480 and 500 mm over
    /// 20°–160°, lifted into the raster.
    fn arc() -> Vec<Point> {
        let (c, r0, r1) = (Point::new(200.0, -380.0), 480.0, 500.0);
        let at = |r: f64, deg: f64| {
            let t = deg.to_radians();
            Point::new(c.x + r * t.cos(), c.y + r * t.sin())
        };
        let mut o: Vec<Point> = (0..=70).map(|k| at(r1, 70.0 + k as f64 * 0.5)).collect();
        o.extend((0..=70).rev().map(|k| at(r0, 70.0 + k as f64 * 0.5)));
        o
    }

    /// Every point within half the gap of the outline lies in a marked
    /// cell: the outline's vertices, its edges' midpoints and both moved
    /// by h in 16 directions, each looked up by its own cell.
    #[test]
    fn the_cells_hold_the_outline_grown_by_half_the_gap() {
        let c = cells();
        let o = arc();
        let fp = c.footprint(&o);
        let mut r = Raster::new(c);
        r.mark(&fp, 0, 0);
        let mut tested = 0;
        for k in 0..o.len() {
            let (p, q) = (o[k], o[(k + 1) % o.len()]);
            for base in [p, p.midpoint(q)] {
                for d in 0..16 {
                    let t = d as f64 * std::f64::consts::PI / 8.0;
                    let h = 0.8 - 1e-9;
                    let x = base.x + h * t.cos();
                    let y = base.y + h * t.sin();
                    let (col, row) = ((x / c.dx_mm).floor(), (y / c.dy_mm).floor());
                    assert!(col >= 0.0 && row >= 0.0);
                    let (col, row) = (col as usize, row as usize);
                    assert_eq!(r.highest(col, row, row), Some(row), "({x}, {y})");
                    tested += 1;
                }
            }
        }
        assert!(tested > 4000);
    }

    /// The drop on hand-made rasters: a 5-row, 3-column part below,
    /// between and above blocks of occupied rows.
    #[test]
    fn the_drop_finds_the_lowest_clear_row_and_no_hole_is_skipped() {
        let c = cells();
        let part = Footprint {
            first: 10,
            spans: vec![(0, 4), (1, 0), (0, 4), (0, 4)],
        };
        let block = |rows: (u32, u32)| Footprint {
            first: 0,
            spans: vec![rows; 40],
        };
        // Rows 10–20 taken: rows 0–4 are clear under them.
        let mut r = Raster::new(c);
        r.mark(&block((10, 20)), 0, 0);
        assert_eq!(r.drop_at(&part, 0, 300, usize::MAX), Some(0));
        // Rows 3–20 taken: the hole below is 3 rows, too low; row 21.
        let mut r = Raster::new(c);
        r.mark(&block((3, 20)), 0, 0);
        assert_eq!(r.drop_at(&part, 0, 300, usize::MAX), Some(21));
        // …unless 21 is not below the bound given.
        assert_eq!(r.drop_at(&part, 0, 300, 21), None);
        // Rows 0–2 and 8–40 taken: the 5-row hole 3–7 holds it.
        let mut r = Raster::new(c);
        r.mark(&block((0, 2)), 0, 0);
        r.mark(&block((8, 40)), 0, 0);
        assert_eq!(r.drop_at(&part, 0, 300, usize::MAX), Some(3));
        // A 4-row hole (3–6) does not: above 40.
        r.mark(&block((7, 7)), 0, 0);
        assert_eq!(r.drop_at(&part, 0, 300, usize::MAX), Some(41));
        // Moved right past the blocks' 40 columns (part columns 10–13 at
        // shift 27 are columns 37–40, one of them, 40, clear): the empty
        // column 38 does not matter, column 37 still does.
        assert_eq!(r.drop_at(&part, 27, 300, usize::MAX), Some(41));
        assert_eq!(r.drop_at(&part, 30, 300, usize::MAX), Some(0));
        // No room below the top: none.
        assert_eq!(r.drop_at(&part, 0, 40, usize::MAX), None);
        // Words: a span across a 64-row boundary.
        let mut r = Raster::new(c);
        r.mark(&block((60, 130)), 0, 0);
        assert_eq!(r.highest(5, 0, 59), None);
        assert_eq!(r.highest(5, 0, 64), Some(64));
        assert_eq!(r.highest(5, 100, 300), Some(130));
        assert_eq!(r.drop_at(&part, 0, 300, usize::MAX), Some(0));
        r.mark(&block((0, 59)), 0, 0);
        assert_eq!(r.drop_at(&part, 0, 300, usize::MAX), Some(131));
    }
}
