//! Engraving the parts: every part its id; every lamella the crossing
//! strip's id beside each slot or node hole and an orientation mark (an
//! arrow from the start end toward the end, its tick toward the top edge).
//! Every engraving lies inside its part and keeps at least `clearance_mm`
//! (kerf plus part spacing) from every cut.
//!
//! Lamellas are rectangles notched from one edge, so their labels go into
//! the band the slots leave whole (y from the clearance to the slots' roots
//! less the clearance) and are placed along x as intervals: linear in the
//! number of features however long the lamella. Other parts use the general
//! [`label::Placer`](super::label::Placer).

use super::font;
use super::label::{LabelSize, Placer};
use super::part::{Engraved, Engraving, FeatureKind, Part, PartKind, SlotEdge};
use kurbo::Point;
use rayon::prelude::*;

/// The largest cap height of a lamella's id, mm.
const ID_HEIGHT_MM: f64 = 8.0;
/// The largest cap height of a crossing strip's id beside a slot, mm.
const CROSSING_HEIGHT_MM: f64 = 5.0;
/// The smallest cap height engraved, mm (below it a laser's line blurs).
pub const MIN_HEIGHT_MM: f64 = 1.0;
/// How far a crossing label may move from its slot, in text widths.
const CROSSING_SEARCH_WIDTHS: f64 = 3.0;

/// Engrave every part (each on its own, in parallel); returns what could
/// not be engraved (one line each, in part order).
pub fn engrave_all(parts: &mut [Part], clearance_mm: f64) -> Vec<String> {
    parts
        .par_iter_mut()
        .map(|p| {
            if p.kind == PartKind::Lamella {
                engrave_lamella(p, clearance_mm)
            } else {
                engrave_other(p, clearance_mm).into_iter().collect()
            }
        })
        .collect::<Vec<Vec<String>>>()
        .into_iter()
        .flatten()
        .collect()
}

/// Free x-intervals search: the position nearest `want` (a box centre) for a
/// box `width` wide that overlaps none of `blocked` (sorted or not), within
/// `reach` of `want`.
fn nearest_free(want: f64, width: f64, blocked: &[(f64, f64)], reach: f64) -> Option<f64> {
    let half = 0.5 * width;
    // Touching is fine; rounding must not make it a collision.
    let eps = 1e-9;
    let fits = |c: f64| {
        blocked
            .iter()
            .all(|&(a, b)| c + half <= a + eps || c - half >= b - eps)
    };
    if fits(want) {
        return Some(want);
    }
    // Candidates: just beside each blocked interval.
    let mut best: Option<f64> = None;
    for &(a, b) in blocked {
        for c in [a - half, b + half] {
            if (c - want).abs() <= reach
                && fits(c)
                && best.is_none_or(|x: f64| (c - want).abs() < (x - want).abs())
            {
                best = Some(c);
            }
        }
    }
    best
}

/// Lamella labels in the band the slots leave whole.
fn engrave_lamella(p: &mut Part, c: f64) -> Vec<String> {
    let (len, h) = (p.length_mm, p.height_mm);
    let slots: Vec<_> = p
        .features
        .iter()
        .filter(|f| f.kind == FeatureKind::Slot && f.edge != Some(SlotEdge::End))
        .collect();
    let depth = slots.iter().map(|f| f.depth_mm).fold(0.0, f64::max);
    let (band_lo, band_hi) = match slots.first().and_then(|f| f.edge) {
        Some(SlotEdge::Top) => (c, h - depth - c),
        Some(SlotEdge::Bottom) => (depth + c, h - c),
        Some(SlotEdge::End) | None => (c, h - c),
    };
    let band = band_hi - band_lo;
    let mut missing = Vec::new();
    if band < MIN_HEIGHT_MM {
        missing.push(format!(
            "{}: no room to engrave (the slots leave {band:.2} mm)",
            p.id
        ));
        return missing;
    }
    // What blocks a box of this height in the band: the ends, the holes
    // whose clearance zone reaches the box's rows, and placed labels.
    let mut holes: Vec<(f64, f64, f64)> = p
        .features
        .iter()
        .filter(|f| f.kind == FeatureKind::Hole)
        .map(|f| (f.center_part_mm.x, f.center_part_mm.y, 0.5 * f.width_mm))
        .collect();
    holes.sort_by(|a, b| a.0.total_cmp(&b.0));
    // End slots (an edge strip runs through them): x from, x to, y from, y to.
    let end_slots: Vec<(f64, f64, f64, f64)> = p
        .features
        .iter()
        .filter(|f| f.kind == FeatureKind::Slot && f.edge == Some(SlotEdge::End))
        .map(|f| {
            let (y0, y1) = (
                f.center_part_mm.y - 0.5 * f.width_mm,
                f.center_part_mm.y + 0.5 * f.width_mm,
            );
            if f.center_part_mm.x < 0.5 * len {
                (0.0, f.depth_mm, y0, y1)
            } else {
                (len - f.depth_mm, len, y0, y1)
            }
        })
        .collect();
    let widest_hole = holes.iter().map(|h| 2.0 * (h.2 + c)).fold(0.0, f64::max);
    // Placed labels (with their clearance), kept sorted by start; the ends
    // of the part as two more blocked intervals.
    let mut taken: Vec<(f64, f64)> = Vec::new();
    let mut widest_taken: f64 = 0.0;
    // Only what lies within [lo, hi] can block a box there: found by
    // binary search, so placing n labels costs O(n log n).
    let blocked_for = |y0: f64, th: f64, lo: f64, hi: f64, taken: &[(f64, f64)], widest: f64| {
        let mut b: Vec<(f64, f64)> = Vec::new();
        let first = taken.partition_point(|t| t.0 < lo - widest);
        for &t in &taken[first..] {
            if t.0 > hi {
                break;
            }
            b.push(t);
        }
        b.push((f64::NEG_INFINITY, c));
        b.push((len - c, f64::INFINITY));
        for &(xa, xb, ya, yb) in &end_slots {
            if yb + c > y0 && ya - c < y0 + th {
                b.push((xa - c, xb + c));
            }
        }
        let first = holes.partition_point(|h| h.0 < lo - widest_hole);
        for &(hx, hy, r) in &holes[first..] {
            if hx - r - c > hi {
                break;
            }
            if hy + r + c > y0 && hy - r - c < y0 + th {
                b.push((hx - r - c, hx + r + c));
            }
        }
        b
    };
    let mut engraving: Vec<Engraving> = Vec::new();
    let put = |what: Engraved, height_mm: f64, x0: f64, y0: f64, out: &mut Vec<Engraving>| {
        out.push(Engraving {
            what,
            at_part_mm: Point::new(x0, y0),
            height_mm,
        });
    };
    // Place a box of `width(th)` at heights from `max_h` down; returns
    // (centre x, cap height, bottom y).
    let place = |width: &dyn Fn(f64) -> f64,
                 want: f64,
                 reach: &dyn Fn(f64) -> f64,
                 max_h: f64,
                 taken: &[(f64, f64)],
                 widest: f64|
     -> Option<(f64, f64, f64)> {
        let mut th = max_h.min(band);
        while th >= MIN_HEIGHT_MM - 1e-12 {
            let y0 = band_lo + 0.5 * (band - th);
            let w = width(th);
            let r = reach(w);
            let blocked = blocked_for(y0, th, want - r - w, want + r + w, taken, widest);
            if let Some(x) = nearest_free(want, w + 2.0 * c, &blocked, r) {
                return Some((x, th, y0));
            }
            th *= 0.85;
        }
        None
    };
    let mut take = |t: (f64, f64), taken: &mut Vec<(f64, f64)>| {
        let at = taken.partition_point(|x| x.0 < t.0);
        taken.insert(at, t);
        widest_taken = widest_taken.max(t.1 - t.0);
        widest_taken
    };
    // Place a text where `place` finds room, engrave it and take its span;
    // returns (centre x, cap height, width).
    let mut widest = 0.0;
    let mut place_text = |text: &str,
                          want: f64,
                          reach: &dyn Fn(f64) -> f64,
                          max_h: f64,
                          engraving: &mut Vec<Engraving>|
     -> Option<(f64, f64, f64)> {
        let width = |th: f64| font::text_width_mm(text, th);
        let (cx, th, y0) = place(&width, want, reach, max_h, &taken, widest)?;
        let w = width(th);
        put(
            Engraved::Text(text.to_string()),
            th,
            cx - 0.5 * w,
            y0,
            engraving,
        );
        widest = take((cx - 0.5 * w - c, cx + 0.5 * w + c), &mut taken);
        Some((cx, th, w))
    };
    // Crossing ids beside slots and node holes, in x order.
    let mut marks: Vec<(f64, &str, Option<usize>)> = p
        .features
        .iter()
        .filter(|f| f.kind == FeatureKind::Slot || f.hole_use == Some(super::part::HoleUse::Node))
        .filter_map(|f| {
            f.crossing
                .as_deref()
                .map(|id| (f.center_part_mm.x, id, f.node))
        })
        .collect();
    marks.sort_by(|a, b| a.0.total_cmp(&b.0));
    marks.dedup_by(|a, b| a.1 == b.1 && a.2 == b.2);
    // One per mark, the id and the orientation mark.
    engraving.reserve_exact(marks.len() + 2);
    for (x, id, node) in marks {
        let reach = |w: f64| CROSSING_SEARCH_WIDTHS * w + 10.0;
        if place_text(id, x, &reach, CROSSING_HEIGHT_MM, &mut engraving).is_none() {
            missing.push(format!(
                "{}: no room to engrave the crossing strip {id} beside node {}",
                p.id,
                node.map_or_else(|| "?".into(), |n| n.to_string())
            ));
        }
    }
    // The part id near the start, then the orientation mark after it.
    let id = p.id.clone();
    let far = |_: f64| len;
    let want = c + 0.5 * font::text_width_mm(&id, ID_HEIGHT_MM.min(band)) + c;
    match place_text(&id, want, &far, ID_HEIGHT_MM, &mut engraving) {
        Some((cx, th, w)) => {
            let mark_w = |mh: f64| font::ORIENTATION_MARK_LENGTH * mh;
            let at = cx + 0.5 * w + c + mark_w(th);
            match place(&mark_w, at, &far, th, &taken, widest) {
                Some((mx, mh, my)) => {
                    put(
                        Engraved::OrientationMark,
                        mh,
                        mx - 0.5 * mark_w(mh),
                        my,
                        &mut engraving,
                    );
                }
                None => missing.push(format!("{}: no room for the orientation mark", p.id)),
            }
        }
        None => missing.push(format!("{}: no room to engrave its id", p.id)),
    }
    p.engraving = engraving;
    missing
}

/// Any other part: its id where it fits, tried at anchors over its extent.
fn engrave_other(p: &mut Part, c: f64) -> Option<String> {
    let (x0, x1, y0, y1) = p.outline_part_mm.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, cc, d), q| (a.min(q.x), b.max(q.x), cc.min(q.y), d.max(q.y)),
    );
    let size = LabelSize {
        max_height_mm: ID_HEIGHT_MM.min(0.5 * (y1 - y0)),
        min_height_mm: MIN_HEIGHT_MM,
        search_mm: 0.5 * (x1 - x0),
    };
    let outline = p.outline_part_mm.clone();
    let holes = p.hole_polygons();
    let mut placer = Placer::new(&outline, &holes, c);
    // Anchors: the centre line of the extent first, then a grid.
    let mut anchors = Vec::new();
    for fy in [0.5, 0.25, 0.75, 0.1, 0.9] {
        for fx in [0.5, 0.25, 0.75, 0.1, 0.9] {
            anchors.push(Point::new(x0 + fx * (x1 - x0), y0 + fy * (y1 - y0)));
        }
    }
    // Then, for narrow parts (a small plate's strip between its holes and
    // its edge), every twentieth of the height.
    for k in 1..20 {
        let fy = f64::from(k) / 20.0;
        if [0.5, 0.25, 0.75, 0.1, 0.9].contains(&fy) {
            continue;
        }
        for fx in [0.5, 0.25, 0.75, 0.1, 0.9] {
            anchors.push(Point::new(x0 + fx * (x1 - x0), y0 + fy * (y1 - y0)));
        }
    }
    for a in anchors {
        if let Some(l) = placer.text(&p.id, a, &size) {
            p.engraving = vec![l.engraving];
            return None;
        }
    }
    Some(format!("{}: no room to engrave its id", p.id))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_free_steps_beside_what_is_taken() {
        let blocked = [(10.0, 20.0), (30.0, 40.0)];
        assert_eq!(nearest_free(5.0, 4.0, &blocked, 50.0), Some(5.0));
        assert_eq!(nearest_free(15.0, 4.0, &blocked, 50.0), Some(8.0));
        assert_eq!(nearest_free(19.0, 4.0, &blocked, 50.0), Some(22.0));
        // A gap too narrow for the box is skipped.
        assert_eq!(nearest_free(25.0, 12.0, &blocked, 50.0), Some(4.0));
        assert_eq!(nearest_free(25.0, 12.0, &blocked, 5.0), None);
    }
}
