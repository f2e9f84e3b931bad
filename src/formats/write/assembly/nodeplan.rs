//! The node plan: every node of the grid in plan (x right, y up, the
//! network's frame) with its id, and every strip's id at its ends, so a
//! crew can find a node on the ground; and [`Labels`], the label placer
//! the overview and the nested sheets share (a label never overprints
//! another, nor a node: it moves aside, hangs on a leader, or goes to a
//! list).
//!
//! Layout rule (the tests recompute the page count from it): the view is
//! the content area less [`KEY_MM`] at the top, inset [`PAD_MM`]; the
//! scale is the smallest standard one at which the nodes' plan extent
//! fits one view, unless then the nodes' spacing ([`spacing_mm`]: the
//! 10th percentile of the node-to-node distances along the strips) is
//! under [`MIN_SPACING_MM`] on paper: then the largest standard scale at
//! which it is not, coarsened along the standard series until the tiles
//! (columns × rows of views, centred on the extent) number at most
//! [`MAX_TILES`].
//! Tiles holding no node are left out; the rest are pages, top row first,
//! left to right.

use super::canvas::{self, Align, BLACK, BLUE, GREY};
use super::{standard_scale, Frame, Page};
use crate::plan::Plan;
use std::collections::HashMap;

/// The nodes' spacing ([`spacing_mm`]) wanted on paper at least, mm.
pub const MIN_SPACING_MM: f64 = 8.0;
/// At most this many tiles.
pub const MAX_TILES: usize = 12;
/// The key line above the view, mm.
pub const KEY_MM: f64 = 8.0;
/// Inset of the view inside its box, mm.
pub const PAD_MM: f64 = 6.0;
/// Node ids, pt.
const NODE_PT: f64 = 6.0;
/// Strip ids, pt.
const STRIP_PT: f64 = 6.5;

/// An axis-aligned box on paper: x0, y0, x1, y1, mm.
pub type Box2 = [f64; 4];

/// Labels placed on a page so far, and what they must stay clear of.
#[derive(Debug, Default)]
pub struct Labels {
    boxes: Vec<Box2>,
    grid: HashMap<(i64, i64), Vec<usize>>,
    bounds: Option<Box2>,
}

/// Grid cell of the placer's index, mm.
const CELL_MM: f64 = 6.0;

fn overlaps(a: &Box2, b: &Box2) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

impl Labels {
    /// A placer keeping labels inside `bounds` (if given).
    pub fn new(bounds: Option<Box2>) -> Labels {
        Labels {
            bounds,
            ..Labels::default()
        }
    }

    fn cells(b: &Box2) -> impl Iterator<Item = (i64, i64)> {
        let (i0, i1) = (
            (b[0] / CELL_MM).floor() as i64,
            (b[2] / CELL_MM).floor() as i64,
        );
        let (j0, j1) = (
            (b[1] / CELL_MM).floor() as i64,
            (b[3] / CELL_MM).floor() as i64,
        );
        (i0..=i1).flat_map(move |i| (j0..=j1).map(move |j| (i, j)))
    }

    /// Whether `b` is free: inside the bounds, clear of every box held.
    pub fn free(&self, b: &Box2) -> bool {
        if let Some(k) = self.bounds {
            if b[0] < k[0] || b[1] < k[1] || b[2] > k[2] || b[3] > k[3] {
                return false;
            }
        }
        Labels::cells(b).all(|c| {
            self.grid
                .get(&c)
                .is_none_or(|v| v.iter().all(|&i| !overlaps(&self.boxes[i], b)))
        })
    }

    /// Hold `b` (a label or something labels must avoid).
    pub fn hold(&mut self, b: Box2) {
        let i = self.boxes.len();
        self.boxes.push(b);
        for c in Labels::cells(&b) {
            self.grid.entry(c).or_default().push(i);
        }
    }

    /// Place a text `w` × `h` mm near `at`: beside it at `gap` mm in eight
    /// directions, then further out on a leader (3 and 6 mm). Returns the
    /// text box's lower left and whether it hangs on a leader; `None` when
    /// nothing is free (the caller lists it instead).
    pub fn place(&mut self, at: [f64; 2], w: f64, h: f64, gap: f64) -> Option<([f64; 2], bool)> {
        let dirs: [[f64; 2]; 8] = [
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [-1.0, 1.0],
            [-1.0, 0.0],
            [-1.0, -1.0],
            [0.0, -1.0],
            [1.0, -1.0],
        ];
        for (k, dist) in [gap, gap + 3.0, gap + 6.0].into_iter().enumerate() {
            for d in dirs {
                // The box's anchor corner faces the point.
                let cx = at[0] + d[0] * dist;
                let cy = at[1] + d[1] * dist;
                let x0 = match d[0] {
                    x if x > 0.0 => cx,
                    x if x < 0.0 => cx - w,
                    _ => cx - 0.5 * w,
                };
                let y0 = match d[1] {
                    y if y > 0.0 => cy,
                    y if y < 0.0 => cy - h,
                    _ => cy - 0.5 * h,
                };
                let b = [x0, y0, x0 + w, y0 + h];
                if self.free(&b) {
                    self.hold(b);
                    return Some(([x0, y0], k > 0));
                }
            }
        }
        None
    }
}

/// The node plan's scale, tiles (columns, rows) and the extent's lower
/// left and size, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodePlanLayout {
    /// Scale denominator.
    pub scale: u32,
    /// Tiles across.
    pub cols: usize,
    /// Tiles up.
    pub rows: usize,
    /// Lower left of the nodes' extent, mm.
    pub lo_mm: [f64; 2],
    /// One view's size at full scale, mm.
    pub tile_mm: [f64; 2],
}

/// The next standard scale above `d`.
fn coarser(d: u32) -> u32 {
    standard_scale(f64::from(d) + 0.5)
}

/// The largest standard scale at or below `den` (1 at least).
fn standard_at_most(den: f64) -> u32 {
    let mut s = 1;
    loop {
        let next = coarser(s);
        if f64::from(next) > den || next == u32::MAX {
            return s;
        }
        s = next;
    }
}

/// The layout of the node plan (see the module doc); `None` without nodes.
pub fn layout(plan: &Plan, frame: &Frame) -> Option<NodePlanLayout> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for n in &plan.nodes {
        for k in 0..2 {
            lo[k] = lo[k].min(n.position_mm[k]);
            hi[k] = hi[k].max(n.position_mm[k]);
        }
    }
    if plan.nodes.is_empty() {
        return None;
    }
    let ext = [(hi[0] - lo[0]).max(1.0), (hi[1] - lo[1]).max(1.0)];
    let view = [
        frame.width_mm() - 2.0 * PAD_MM,
        frame.height_mm() - KEY_MM - 2.0 * PAD_MM,
    ];
    let fit = standard_scale((ext[0] / view[0]).max(ext[1] / view[1]));
    let read = spacing_mm(plan).map_or(fit, |d| standard_at_most(d / MIN_SPACING_MM));
    let mut scale = read.min(fit);
    let tiles = |s: u32| {
        let d = f64::from(s);
        (
            ((ext[0] / (view[0] * d)) - 1e-9).ceil().max(1.0) as usize,
            ((ext[1] / (view[1] * d)) - 1e-9).ceil().max(1.0) as usize,
        )
    };
    while tiles(scale).0 * tiles(scale).1 > MAX_TILES && scale < fit {
        scale = coarser(scale);
    }
    let (cols, rows) = tiles(scale);
    let d = f64::from(scale);
    let tile_mm = [view[0] * d, view[1] * d];
    // The tiles centred on the extent.
    let lo_mm = [
        lo[0] - 0.5 * (cols as f64 * tile_mm[0] - ext[0]),
        lo[1] - 0.5 * (rows as f64 * tile_mm[1] - ext[1]),
    ];
    Some(NodePlanLayout {
        scale,
        cols,
        rows,
        lo_mm,
        tile_mm,
    })
}

/// The spacing the node plan keeps legible: the 10th percentile of the
/// node-to-node distances along every strip, mm (`None` without any).
pub fn spacing_mm(plan: &Plan) -> Option<f64> {
    let mut d: Vec<f64> = plan
        .strips
        .iter()
        .flat_map(|s| s.node_to_node_mm.iter().copied())
        .filter(|x| *x > 0.0)
        .collect();
    if d.is_empty() {
        return None;
    }
    d.sort_by(f64::total_cmp);
    Some(d[(d.len() - 1) / 10])
}

/// The node plan's pages.
pub fn pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let Some(l) = layout(plan, frame) else {
        return Vec::new();
    };
    let s = 1.0 / f64::from(l.scale);
    let mut tiles: Vec<(usize, usize)> = Vec::new();
    for r in (0..l.rows).rev() {
        for c in 0..l.cols {
            let (x0, y0) = (
                l.lo_mm[0] + c as f64 * l.tile_mm[0],
                l.lo_mm[1] + r as f64 * l.tile_mm[1],
            );
            let inside = |p: &[f64; 3]| {
                p[0] >= x0 - 1e-9
                    && p[0] < x0 + l.tile_mm[0] + if c + 1 == l.cols { 1e-6 } else { 0.0 }
                    && p[1] >= y0 - 1e-9
                    && p[1] < y0 + l.tile_mm[1] + if r + 1 == l.rows { 1e-6 } else { 0.0 }
            };
            if plan.nodes.iter().any(|n| inside(&n.position_mm)) {
                tiles.push((c, r));
            }
        }
    }
    let total = tiles.len();
    let family: HashMap<&str, &str> = plan
        .strips
        .iter()
        .map(|st| (st.id.as_str(), st.family.as_str()))
        .collect();
    tiles
        .iter()
        .enumerate()
        .map(|(t, &(c, r))| {
            let heading = if total == 1 {
                "Node plan: every node's id, in plan (x right, y up)".to_string()
            } else {
                format!(
                    "Node plan, tile {} of {total} (column {} of {}, row {} of {} from the top): node ids in plan",
                    t + 1,
                    c + 1,
                    l.cols,
                    l.rows - r,
                    l.rows
                )
            };
            let mut page = Page::new("Overview", heading, Some(l.scale));
            let cv = &mut page.canvas;
            let (bx, by, bw, bh) = (
                frame.x0_mm,
                frame.y0_mm,
                frame.width_mm(),
                frame.height_mm() - KEY_MM,
            );
            let x0 = l.lo_mm[0] + c as f64 * l.tile_mm[0];
            let y0 = l.lo_mm[1] + r as f64 * l.tile_mm[1];
            let map = |p: &[f64; 3]| {
                [
                    bx + PAD_MM + (p[0] - x0) * s,
                    by + PAD_MM + (p[1] - y0) * s,
                ]
            };
            let view = [bx, by, bx + bw, by + bh];
            let in_view = |q: [f64; 2]| q[0] >= view[0] && q[0] <= view[2] && q[1] >= view[1] && q[1] <= view[3];
            cv.stroke(GREY);
            cv.width(0.15);
            cv.rect(bx, by, bw, bh, false, true);
            // Curves, clipped to the view.
            cv.clip_begin(bx, by, bw, bh);
            for edges in [false, true] {
                for curve in &plan.curves {
                    let edge = family.get(curve.id.as_str()).is_none_or(|f| *f == "edge");
                    if edge != edges {
                        continue;
                    }
                    cv.stroke(match family.get(curve.id.as_str()) {
                        Some(&"A") => [0.75, 0.35, 0.35],
                        Some(&"B") => [0.35, 0.45, 0.8],
                        _ => BLACK,
                    });
                    cv.width(if edge { 0.4 } else { 0.25 });
                    // Only the curves that reach into this tile.
                    let reaches = curve.points_mm.iter().any(|p| {
                        let q = map(p);
                        q[0] >= view[0] - 5.0
                            && q[0] <= view[2] + 5.0
                            && q[1] >= view[1] - 5.0
                            && q[1] <= view[3] + 5.0
                    });
                    if !reaches {
                        continue;
                    }
                    let pts: Vec<[f64; 2]> = curve.points_mm.iter().map(map).collect();
                    cv.polyline(&pts, false);
                }
            }
            cv.clip_end();
            // Nodes: dots, held clear of every label.
            let mut labels = Labels::new(Some(view));
            let here: Vec<(&crate::plan::PlanNode, [f64; 2])> = plan
                .nodes
                .iter()
                .map(|n| (n, map(&n.position_mm)))
                .filter(|(_, q)| in_view(*q))
                .collect();
            let r_dot = 0.45;
            for (_, q) in &here {
                labels.hold([q[0] - r_dot, q[1] - r_dot, q[0] + r_dot, q[1] + r_dot]);
            }
            cv.fill(BLACK);
            for (_, q) in &here {
                cv.circle(*q, r_dot, true);
            }
            let cap = canvas::cap_mm(NODE_PT);
            let mut listed: Vec<usize> = Vec::new();
            let mut leaders: Vec<([f64; 2], [f64; 2])> = Vec::new();
            let mut texts: Vec<([f64; 2], String)> = Vec::new();
            for (n, q) in &here {
                let id = n.id.to_string();
                let w = canvas::text_width_mm(&id, NODE_PT, false);
                match labels.place(*q, w + 0.4, cap + 0.8, 0.7) {
                    Some((at, leader)) => {
                        if leader {
                            let mid = [at[0] + 0.5 * (w + 0.4), at[1] + 0.5 * (cap + 0.8)];
                            leaders.push((*q, mid));
                        }
                        texts.push(([at[0] + 0.2, at[1] + 0.5], id));
                    }
                    None => listed.push(n.id),
                }
            }
            // Strip ids beyond their ends (where the end is in this tile).
            let mut strip_texts: Vec<([f64; 2], String)> = Vec::new();
            for curve in &plan.curves {
                let pts: Vec<[f64; 2]> = curve.points_mm.iter().map(map).collect();
                if pts.len() < 2 {
                    continue;
                }
                let n = pts.len();
                let ends: Vec<[f64; 2]> = if family.get(curve.id.as_str()).is_none_or(|f| *f == "edge") {
                    vec![pts[n / 2]]
                } else {
                    vec![pts[0], pts[n - 1]]
                };
                for e in ends.into_iter().filter(|e| in_view(*e)) {
                    let w = canvas::text_width_mm(&curve.id, STRIP_PT, true);
                    let h = canvas::cap_mm(STRIP_PT);
                    if let Some((at, _)) = labels.place(e, w + 0.4, h + 0.8, 1.2) {
                        strip_texts.push(([at[0] + 0.2, at[1] + 0.5], curve.id.clone()));
                    }
                }
            }
            // White behind every label, so strips running under stay clear of it.
            cv.fill([1.0, 1.0, 1.0]);
            for (at, t) in &texts {
                let w = canvas::text_width_mm(t, NODE_PT, false);
                cv.rect(at[0] - 0.2, at[1] - 0.5, w + 0.4, cap + 0.8, true, false);
            }
            for (at, t) in &strip_texts {
                let w = canvas::text_width_mm(t, STRIP_PT, true);
                cv.rect(
                    at[0] - 0.2,
                    at[1] - 0.5,
                    w + 0.4,
                    canvas::cap_mm(STRIP_PT) + 0.8,
                    true,
                    false,
                );
            }
            cv.stroke(GREY);
            cv.width(0.12);
            for (a, b) in &leaders {
                cv.line(*a, *b);
            }
            cv.fill(BLACK);
            for (at, t) in &texts {
                cv.text(*at, NODE_PT, false, Align::Left, 0.0, t);
            }
            cv.fill(BLUE);
            for (at, t) in &strip_texts {
                cv.text(*at, STRIP_PT, true, Align::Left, 0.0, t);
            }
            // The key: what is drawn, where this tile lies, what is listed.
            let key_y = frame.y1_mm - KEY_MM + 2.5;
            cv.fill(BLACK);
            let mut key = format!(
                "x {} to {}, y {} to {} mm (network frame); node ids black, strip ids blue; positions in the setting-out table",
                super::mm0(x0),
                super::mm0(x0 + l.tile_mm[0]),
                super::mm0(y0),
                super::mm0(y0 + l.tile_mm[1])
            );
            if !listed.is_empty() {
                listed.sort_unstable();
                let shown: Vec<String> = listed.iter().take(40).map(|i| i.to_string()).collect();
                key = format!(
                    "{key}; too close to label here: {}{}",
                    shown.join(" "),
                    if listed.len() > 40 {
                        format!(" and {} more", listed.len() - 40)
                    } else {
                        String::new()
                    }
                );
            }
            cv.text([frame.x0_mm, key_y], 7.0, false, Align::Left, 0.0, &key);
            // The tiles in miniature, this one filled.
            if total > 1 {
                let kw = 4.0;
                let kx = frame.x1_mm - l.cols as f64 * kw;
                let cell_h = (KEY_MM - 2.0) / l.rows as f64;
                for rr in 0..l.rows {
                    for cc in 0..l.cols {
                        let x = kx + cc as f64 * kw;
                        let y = frame.y1_mm - KEY_MM + 1.0 + rr as f64 * cell_h;
                        let mine = rr == r && cc == c;
                        cv.fill(if mine { GREY } else { [1.0, 1.0, 1.0] });
                        cv.stroke(GREY);
                        cv.width(0.1);
                        cv.rect(x, y, kw, cell_h, true, true);
                    }
                }
            }
            page
        })
        .collect()
}
