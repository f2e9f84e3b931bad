//! Strip sheets: every lamella of every A and B strip drawn flat, to scale,
//! from plan.json's parts (outline with its slots, holes, shear blocks),
//! its pieces laid end to end along its line.
//!
//! Layout rule (the tests recompute the page count from it):
//! * scale 1:d, d the largest of 1, 2, 5, 10, 20 at which the lamella's
//!   height is at least [`MIN_HEIGHT_ON_PAPER_MM`] on paper (1:1 if none);
//! * a lamella runs from its first piece's start to its last piece's end
//!   and is broken into rows of (content width − [`LABEL_COLUMN_MM`]) × d
//!   of its length; each lamella starts a new row;
//! * a row is [`ROW_ABOVE_MM`] (stations and crossing ids) + the height on
//!   paper + [`ROW_BELOW_MM`] (piece ids, gap) high; as many rows per page
//!   as fit in the content height less [`STRIP_HEAD_MM`];
//! * strips follow each other in plan order: a strip (its line of
//!   [`STRIP_HEAD_MM`] and its rows) that does not fit in what is left of
//!   the page starts a new one; a strip longer than a page fills pages of
//!   `rows_per_page` rows, each with the strip's line again.
//!
//! At each node: a tick, the distance from its piece's cut start end (mm,
//! x = 0 of the piece, the end its engraved orientation arrow points from:
//! the one datum of every station in the kit) and the crossing strip's id,
//! written upright along the tick; a 0 at every piece's start end and the
//! last piece's length at its far end; labels too close to read are moved
//! right along a leader.

use super::canvas::{Align, Canvas, BLACK, BLUE, GREY};
use super::{mm0, Frame, Page, SealedPage};
use crate::plan::{Plan, PlanFeatureKind, PlanHoleUse, PlanPart};
use rayon::prelude::*;
use std::collections::HashMap;

/// Smallest height of a lamella on paper when choosing the scale, mm.
pub const MIN_HEIGHT_ON_PAPER_MM: f64 = 4.0;
/// The column left of every row holding the lamella's name, mm.
pub const LABEL_COLUMN_MM: f64 = 28.0;
/// Room above a lamella for the stations and the crossing ids, mm.
pub const ROW_ABOVE_MM: f64 = 20.0;
/// Room below a lamella for piece ids and the gap to the next row, mm.
pub const ROW_BELOW_MM: f64 = 9.0;
/// The strip's own line under the page heading, mm.
pub const STRIP_HEAD_MM: f64 = 6.0;

/// Text size of stations, crossing ids and piece ids, pt.
const LABEL_PT: f64 = 7.0;

/// The scale denominator for lamellas `height_mm` high.
pub fn scale_for(height_mm: f64) -> u32 {
    [20u32, 10, 5, 2, 1]
        .into_iter()
        .find(|&d| height_mm / f64::from(d) >= MIN_HEIGHT_ON_PAPER_MM)
        .unwrap_or(1)
}

/// Rows, row length along the lamella (mm) and rows per page.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripLayout {
    /// Scale denominator.
    pub scale: u32,
    /// Length of lamella per row, mm (full size).
    pub row_length_mm: f64,
    /// Height of a row on paper, mm.
    pub row_height_mm: f64,
    /// Rows on one page.
    pub rows_per_page: usize,
}

impl StripLayout {
    /// The layout for lamellas `height_mm` high on `frame`.
    pub fn new(frame: &Frame, height_mm: f64) -> StripLayout {
        let scale = scale_for(height_mm);
        let d = f64::from(scale);
        let row_height_mm = ROW_ABOVE_MM + height_mm / d + ROW_BELOW_MM;
        StripLayout {
            scale,
            row_length_mm: (frame.width_mm() - LABEL_COLUMN_MM) * d,
            row_height_mm,
            rows_per_page: (((frame.height_mm() - STRIP_HEAD_MM) / row_height_mm).floor() as usize)
                .max(1),
        }
    }
}

/// One lamella: its pieces in order along its line.
struct Lamella<'a> {
    number: u32,
    pieces: Vec<&'a PlanPart>,
    start_mm: f64,
    end_mm: f64,
    rows: usize,
}

/// Every strip's pages, in strip order.
pub fn pages(plan: &Plan, frame: &Frame) -> Vec<SealedPage> {
    match &plan.parts {
        Some(parts) => pages_of(plan, parts, frame),
        None => Vec::new(),
    }
}

/// [`pages`] with the plan's parts given apart (`lamella build` draws the
/// strip sheets while the kit is being nested, before the parts join the
/// plan).
pub fn pages_of(plan: &Plan, parts: &[PlanPart], frame: &Frame) -> Vec<SealedPage> {
    let height = plan
        .profile
        .as_ref()
        .map(|p| p.height_mm)
        .or_else(|| {
            parts
                .iter()
                .find(|p| p.kind == "lamella")
                .map(|p| p.height_mm)
        })
        .unwrap_or(50.0);
    let layout = StripLayout::new(frame, height);
    let block = parts
        .iter()
        .find(|p| p.kind == "shear_block")
        .map(|p| (p.length_mm, p.height_mm));
    let mut by_strip: HashMap<&str, Vec<&PlanPart>> = HashMap::new();
    for p in parts.iter().filter(|p| p.kind == "lamella") {
        if let Some(s) = &p.strip {
            by_strip.entry(s.as_str()).or_default().push(p);
        }
    }
    let strips: Vec<StripRows> = plan
        .strips
        .par_iter()
        .filter_map(|s| by_strip.get(s.id.as_str()).map(|ps| (s, ps)))
        .map(|(s, ps)| {
            let mut numbers: Vec<u32> = ps.iter().filter_map(|p| p.lamella).collect();
            numbers.sort_unstable();
            numbers.dedup();
            let lamellas: Vec<Lamella> = numbers
                .iter()
                .map(|&n| {
                    let mut pieces: Vec<&PlanPart> = ps
                        .iter()
                        .copied()
                        .filter(|p| p.lamella == Some(n))
                        .collect();
                    pieces.sort_by(|a, b| {
                        a.station_start_mm
                            .unwrap_or(0.0)
                            .total_cmp(&b.station_start_mm.unwrap_or(0.0))
                    });
                    let start_mm = pieces
                        .iter()
                        .map(|p| p.station_start_mm.unwrap_or(0.0))
                        .fold(f64::INFINITY, f64::min);
                    let end_mm = pieces
                        .iter()
                        .map(|p| p.station_start_mm.unwrap_or(0.0) + p.length_mm)
                        .fold(f64::NEG_INFINITY, f64::max);
                    let rows =
                        (((end_mm - start_mm) / layout.row_length_mm).ceil() as usize).max(1);
                    Lamella {
                        number: n,
                        pieces,
                        start_mm,
                        end_mm,
                        rows,
                    }
                })
                .collect();
            StripRows { strip: s, lamellas }
        })
        .collect();
    strip_pages(&strips, &layout, frame, block)
}

/// One strip ready to lay out: its lamellas and their rows.
struct StripRows<'a> {
    strip: &'a crate::plan::PlanStrip,
    lamellas: Vec<Lamella<'a>>,
}

/// Lay strips out on pages: a strip goes on the current page when its
/// line and all its rows fit there, else it starts a new page; a strip
/// longer than a page fills pages of [`StripLayout::rows_per_page`] rows
/// and its last rows stay open to the next strip.
fn paginate(
    strips: &[StripRows],
    layout: &StripLayout,
    frame: &Frame,
) -> Vec<Vec<(usize, usize, usize)>> {
    let full = frame.height_mm();
    let mut pages: Vec<Vec<(usize, usize, usize)>> = Vec::new();
    let mut left = 0.0_f64;
    for (si, s) in strips.iter().enumerate() {
        let rows: Vec<(usize, usize)> = s
            .lamellas
            .iter()
            .enumerate()
            .flat_map(|(i, l)| (0..l.rows).map(move |r| (i, r)))
            .collect();
        let need = STRIP_HEAD_MM + rows.len() as f64 * layout.row_height_mm;
        let used = |pages: &Vec<Vec<_>>| pages.last().is_some_and(|p: &Vec<_>| !p.is_empty());
        if need > left + 1e-9 && used(&pages) || pages.is_empty() {
            pages.push(Vec::new());
            left = full;
        }
        for chunk in rows.chunks(layout.rows_per_page) {
            let need = STRIP_HEAD_MM + chunk.len() as f64 * layout.row_height_mm;
            if need > left + 1e-9 && used(&pages) {
                pages.push(Vec::new());
                left = full;
            }
            if let Some(page) = pages.last_mut() {
                page.extend(chunk.iter().map(|&(i, r)| (si, i, r)));
            }
            left -= need;
        }
    }
    pages
}

/// The pages of all strips.
fn strip_pages(
    strips: &[StripRows],
    layout: &StripLayout,
    frame: &Frame,
    block: Option<(f64, f64)>,
) -> Vec<SealedPage> {
    let pages = paginate(strips, layout, frame);
    pages
        .par_iter()
        .map(|rows| {
            let mut ids: Vec<&str> = rows.iter().map(|&(si, _, _)| strips[si].strip.id.as_str()).collect();
            ids.dedup();
            let heading = match ids.as_slice() {
                [one] => format!("Strip {one}"),
                [first, .., last] => format!("Strips {first} to {last}"),
                [] => "Strips".to_string(),
            };
            let mut page = Page::new("Strip sheets", heading, Some(layout.scale));
            let c = &mut page.canvas;
            let mut top = frame.y1_mm;
            let mut current = usize::MAX;
            for &(si, i, r) in rows {
                let st = &strips[si];
                if si != current {
                    current = si;
                    let s = st.strip;
                    c.fill(BLACK);
                    c.text([frame.x0_mm, top - 4.0], 9.0, true, Align::Left, 0.0, &format!("Strip {} (family {})", s.id, s.family));
                    let cont = if r > 0 || i > 0 { ", continued" } else { "" };
                    c.text(
                        [frame.x0_mm + LABEL_COLUMN_MM + 8.0, top - 4.0],
                        8.0,
                        false,
                        Align::Left,
                        0.0,
                        &format!(
                            "{} mm along its curve, {} nodes, {} lamella{}{cont}; stations in mm from each piece's cut start end (0: where its engraved arrow starts); crossing strip ids at the nodes",
                            mm0(s.length_mm),
                            s.nodes.len(),
                            st.lamellas.len(),
                            if st.lamellas.len() == 1 { "" } else { "s" }
                        ),
                    );
                    c.stroke(GREY);
                    c.width(0.15);
                    c.line([frame.x0_mm, top - 5.5], [frame.x1_mm, top - 5.5]);
                    top -= STRIP_HEAD_MM;
                }
                draw_row(c, &st.strip.id, &st.lamellas[i], r, top, layout, frame, block);
                top -= layout.row_height_mm;
            }
            page.seal()
        })
        .collect()
}

/// Open runs of the closed polygon `pts` inside x ∈ [xa, xb].
fn clip_x(pts: &[[f64; 2]], xa: f64, xb: f64) -> Vec<Vec<[f64; 2]>> {
    let n = pts.len();
    let mut runs: Vec<Vec<[f64; 2]>> = Vec::new();
    let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9;
    for i in 0..n {
        let (p, q) = (pts[i], pts[(i + 1) % n]);
        let (lo, hi) = (p[0].min(q[0]), p[0].max(q[0]));
        if hi < xa || lo > xb {
            continue;
        }
        let at = |x: f64| {
            let t = if (q[0] - p[0]).abs() < 1e-12 {
                0.0
            } else {
                (x - p[0]) / (q[0] - p[0])
            };
            [x, p[1] + t * (q[1] - p[1])]
        };
        let a = if p[0] < xa {
            at(xa)
        } else if p[0] > xb {
            at(xb)
        } else {
            p
        };
        let b = if q[0] < xa {
            at(xa)
        } else if q[0] > xb {
            at(xb)
        } else {
            q
        };
        match runs.last_mut() {
            Some(run) if run.last().is_some_and(|&l| close(l, a)) => run.push(b),
            _ => runs.push(vec![a, b]),
        }
    }
    // The last run may continue into the first across the polygon's start.
    if runs.len() > 1 {
        let last_end = runs[runs.len() - 1][runs[runs.len() - 1].len() - 1];
        if close(last_end, runs[0][0]) {
            let first = runs.remove(0);
            if let Some(last) = runs.last_mut() {
                last.extend_from_slice(&first[1..]);
            }
        }
    }
    runs
}

/// One row of a lamella: row `r` of `l`, its top at `top`.
#[allow(clippy::too_many_arguments)]
fn draw_row(
    c: &mut Canvas,
    strip: &str,
    l: &Lamella,
    r: usize,
    top: f64,
    layout: &StripLayout,
    frame: &Frame,
    block: Option<(f64, f64)>,
) {
    let d = f64::from(layout.scale);
    let (xa, xb) = (
        r as f64 * layout.row_length_mm,
        ((r + 1) as f64 * layout.row_length_mm).min(l.end_mm - l.start_mm),
    );
    let left = frame.x0_mm + LABEL_COLUMN_MM;
    let height = l.pieces.first().map_or(0.0, |p| p.height_mm);
    let y_bot = top - ROW_ABOVE_MM - height / d;
    let y_top = y_bot + height / d;
    // Lamella-relative x (from its start end, mm) and part y to paper.
    let px = |x: f64| left + (x - xa) / d;
    let py = |y: f64| y_bot + y / d;
    // Name column.
    c.fill(BLACK);
    c.text(
        [frame.x0_mm, y_top + 2.0],
        10.0,
        true,
        Align::Left,
        0.0,
        &format!("{strip}-{}", l.number),
    );
    c.text(
        [frame.x0_mm, y_top - 2.5],
        7.0,
        false,
        Align::Left,
        0.0,
        &format!("lamella {}, row {} of {}", l.number, r + 1, l.rows),
    );
    // The pieces this row shows (stations count from each one's start end).
    let shown: Vec<&str> = l
        .pieces
        .iter()
        .filter(|p| {
            let off = p.station_start_mm.unwrap_or(0.0) - l.start_mm;
            off < xb && off + p.length_mm > xa
        })
        .map(|p| p.id.as_str())
        .collect();
    c.fill(GREY);
    c.text(
        [frame.x0_mm, y_top - 6.0],
        7.0,
        false,
        Align::Left,
        0.0,
        &match shown.as_slice() {
            [one] => format!("piece {one}"),
            [first, .., last] => format!("{first} to {last}"),
            [] => String::new(),
        },
    );
    // Shear blocks first (under the outline), then outlines, holes. Every
    // station printed is from its own piece's start end (x = 0 there).
    let mut nodes: Vec<(f64, f64, String)> = Vec::new();
    let mut starts: Vec<f64> = Vec::new();
    for p in &l.pieces {
        let off = p.station_start_mm.unwrap_or(0.0) - l.start_mm;
        if off > xb || off + p.length_mm < xa {
            continue;
        }
        if let Some((bl, bh)) = block {
            c.fill([0.8, 0.86, 0.95]);
            for f in p
                .features
                .iter()
                .filter(|f| f.hole_use == Some(PlanHoleUse::ShearBlock))
            {
                let x = f.center_mm[0] + off;
                if x - 0.5 * bl >= xa && x + 0.5 * bl <= xb {
                    let (x0, y0) = (px(x - 0.5 * bl), py(f.center_mm[1] - 0.5 * bh));
                    c.rect(x0, y0, bl / d, bh / d, true, false);
                }
            }
        }
        let pts: Vec<[f64; 2]> = p
            .outline
            .iter()
            .map(|q| [px(q[0] + off), py(q[1])])
            .collect();
        c.stroke(BLACK);
        c.width(0.25);
        if off >= xa && off + p.length_mm <= xb {
            c.polyline(&pts, true);
        } else {
            for run in clip_x(&pts, px(xa), px(xb)) {
                c.polyline(&run, false);
            }
        }
        c.width(0.15);
        for f in p
            .features
            .iter()
            .filter(|f| f.kind == PlanFeatureKind::Hole)
        {
            let x = f.center_mm[0] + off;
            if (xa..=xb).contains(&x) {
                c.circle(
                    [px(x), py(f.center_mm[1])],
                    (0.5 * f.width_mm / d).max(0.2),
                    false,
                );
            }
        }
        if (xa..xb).contains(&off) {
            starts.push(off);
        }
        for f in &p.features {
            if let (Some(_), Some(cross)) = (f.node, &f.crossing) {
                let x = f.center_mm[0] + off;
                if (xa..=xb).contains(&x)
                    && !nodes
                        .iter()
                        .any(|(nx, _, id)| id == cross && (nx - x).abs() < 1.0)
                {
                    nodes.push((x, f.station_mm.unwrap_or(f.center_mm[0]), cross.clone()));
                }
            }
        }
        // Piece id under the visible part of the piece.
        let (va, vb) = (off.max(xa), (off + p.length_mm).min(xb));
        c.fill(BLACK);
        c.text(
            [0.5 * (px(va) + px(vb)), y_bot - 3.5],
            LABEL_PT,
            false,
            Align::Center,
            0.0,
            &p.id,
        );
        // Piece joints (splices): a mark under the lamella.
        c.stroke(GREY);
        c.width(0.15);
        for x in [off, off + p.length_mm] {
            if x > 1e-6 && x < l.end_mm - l.start_mm - 1e-6 && (xa..=xb).contains(&x) {
                c.line([px(x), y_bot - 0.8], [px(x), y_bot - 5.5]);
            }
        }
    }
    // Break marks where the lamella goes on in the next or came from the last row.
    c.stroke(GREY);
    c.width(0.2);
    let zig = |c: &mut Canvas, x: f64| {
        let h = y_top - y_bot;
        c.polyline(
            &[
                [x, y_bot - 1.0],
                [x, y_bot + 0.3 * h],
                [x + 1.0, y_bot + 0.45 * h],
                [x - 1.0, y_bot + 0.55 * h],
                [x, y_bot + 0.7 * h],
                [x, y_top + 1.0],
            ],
            false,
        );
    };
    if r + 1 < l.rows {
        zig(c, px(xb) + 1.5);
    }
    if r > 0 {
        zig(c, px(xa) - 1.5);
    }
    // Stations: each piece's start end (0), each node (from its piece's
    // start end), the last piece's far end (its length).
    let mut marks: Vec<(f64, f64, Option<String>)> =
        starts.into_iter().map(|x| (x, 0.0, None)).collect();
    marks.extend(nodes.into_iter().map(|(x, st, id)| (x, st, Some(id))));
    if r + 1 == l.rows {
        if let Some(last) = l.pieces.last() {
            marks.push((l.end_mm - l.start_mm, last.length_mm, None));
        }
    }
    marks.sort_by(|a, b| a.0.total_cmp(&b.0));
    let cap = 0.718 * LABEL_PT * 25.4 / 72.0;
    let pitch = cap + 0.9;
    // Where each label goes (moved right along a leader when crowded).
    let mut last_label = f64::NEG_INFINITY;
    let placed: Vec<(f64, f64, String, Option<String>)> = marks
        .into_iter()
        .map(|(x, st, id)| {
            let tick = px(x);
            let lx = tick.max(last_label + pitch);
            last_label = lx;
            (tick, lx, mm0(st), id)
        })
        .collect();
    // Ticks and leaders, then the stations, then the ids: one colour and
    // font change each per row.
    c.stroke(BLUE);
    c.width(0.15);
    for (tick, lx, _, _) in &placed {
        if (lx - tick).abs() > 0.05 {
            c.polyline(
                &[
                    [*tick, y_top + 0.3],
                    [*tick, y_top + 1.5],
                    [*lx, y_top + 2.5],
                ],
                false,
            );
        } else {
            c.line([*tick, y_top + 0.3], [*tick, y_top + 1.5]);
        }
    }
    // Upright text reads upward; its glyphs lie left of the baseline.
    c.fill(BLUE);
    for (_, lx, station, _) in &placed {
        c.text(
            [lx + 0.5 * cap, y_top + 3.0],
            LABEL_PT,
            false,
            Align::Left,
            90.0,
            station,
        );
    }
    c.fill(BLACK);
    for (_, lx, station, id) in &placed {
        if let Some(id) = id {
            let above = y_top + 4.5 + super::canvas::text_width_mm(station, LABEL_PT, false);
            c.text(
                [lx + 0.5 * cap, above],
                LABEL_PT,
                true,
                Align::Left,
                90.0,
                id,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_keeps_lamellas_readable() {
        assert_eq!(scale_for(50.0), 10);
        assert_eq!(scale_for(60.0), 10);
        assert_eq!(scale_for(12.0), 2);
        assert_eq!(scale_for(100.0), 20);
        assert_eq!(scale_for(3.0), 1);
    }

    #[test]
    fn clipping_a_rectangle() {
        let r = [[0.0, 0.0], [10.0, 0.0], [10.0, 2.0], [0.0, 2.0]];
        let runs = clip_x(&r, 2.0, 5.0);
        // The bottom edge, then the top edge (its own run).
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0], vec![[2.0, 0.0], [5.0, 0.0]]);
        assert_eq!(runs[1], vec![[5.0, 2.0], [2.0, 2.0]]);
    }
}
