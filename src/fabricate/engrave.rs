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
/// The step of the last, fine search across a small part's height, mm.
const FINE_STEP_MM: f64 = 0.05;
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
    // Last, for the narrowest (a short splice plate cut from a strongly
    // bowed band, its holes on the centre line: the strip beside them may
    // be only a few tenths wider than the smallest text and its
    // clearances), the centre line of the length at every
    // [`FINE_STEP_MM`] across the height, the text sliding along the
    // whole length.
    // (At most 400 steps: a tall part's grid has found room long before.)
    let step = FINE_STEP_MM.max((y1 - y0) / 400.0);
    let steps = ((y1 - y0) / step).floor() as u32;
    anchors.extend((1..steps).map(|k| Point::new(0.5 * (x0 + x1), y0 + f64::from(k) * step)));
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

    /// A 41 × 13 mm splice plate cut from a strongly bowed veneer band
    /// (the 1:5 pavilion's SP-edge03.1 at a 200 mm band bow): four 2.6 mm
    /// holes on its centre line, 1.65 mm clearance; the strip above the
    /// holes is 0.3 mm wider than a 1 mm id and its clearances, and no
    /// anchor of the grid lies in it. The fine search finds it: the id is
    /// engraved, inside and clear of every cut.
    #[test]
    fn a_short_bowed_plate_gets_its_id() {
        use super::super::invariants::check_part;
        use super::super::part::{Feature, HoleUse};
        let outline: Vec<Point> = [
            (0.0, 1.3549),
            (0.1539, 1.3352),
            (1.3322, 1.1891),
            (2.5119, 1.051),
            (3.6929, 0.9211),
            (4.8751, 0.7994),
            (5.1492, 0.7724),
            (6.1956, 0.6735),
            (7.2429, 0.5812),
            (8.4283, 0.4848),
            (9.6147, 0.3969),
            (10.802, 0.3176),
            (11.9901, 0.247),
            (13.1789, 0.1852),
            (14.3684, 0.1321),
            (15.5065, 0.0896),
            (16.7489, 0.0524),
            (17.9398, 0.026),
            (19.1311, 0.0085),
            (20.3226, 0.0),
            (21.5143, 0.0005),
            (22.706, 0.0101),
            (23.8977, 0.0287),
            (24.8993, 0.0514),
            (25.9008, 0.0805),
            (26.2806, 0.0932),
            (27.4717, 0.1391),
            (28.6624, 0.1941),
            (29.8527, 0.2582),
            (31.0423, 0.3313),
            (32.2314, 0.4135),
            (33.4197, 0.5048),
            (34.6071, 0.6051),
            (35.7937, 0.7143),
            (36.2751, 0.7612),
            (38.1638, 0.9597),
            (39.3471, 1.0957),
            (40.5292, 1.2405),
            (41.4365, 1.3577),
            (39.8649, 13.2544),
            (39.0256, 13.1459),
            (37.9324, 13.012),
            (36.8384, 12.8862),
            (35.0929, 12.7029),
            (34.6482, 12.6595),
            (33.5521, 12.5586),
            (32.4553, 12.466),
            (31.358, 12.3817),
            (30.2602, 12.3058),
            (29.1619, 12.2383),
            (28.0631, 12.1791),
            (26.9639, 12.1284),
            (25.8644, 12.086),
            (25.5138, 12.0743),
            (24.5892, 12.0474),
            (23.6644, 12.0264),
            (22.5641, 12.0092),
            (21.4635, 12.0004),
            (20.3628, 11.9999),
            (19.2621, 12.0078),
            (18.1613, 12.024),
            (17.0604, 12.0484),
            (15.9117, 12.0827),
            (14.8589, 12.122),
            (13.7583, 12.1712),
            (12.6579, 12.2284),
            (11.5577, 12.2938),
            (10.4578, 12.3673),
            (9.3581, 12.4487),
            (8.2588, 12.5381),
            (7.2871, 12.6238),
            (6.3158, 12.7156),
            (6.0613, 12.7407),
            (4.9632, 12.8537),
            (3.8656, 12.9744),
            (2.7685, 13.1028),
            (1.6719, 13.2388),
            (1.5287, 13.2571),
        ]
        .iter()
        .map(|&(x, y)| Point::new(x, y))
        .collect();
        let features = [
            (5.7325, 6.744),
            (15.7091, 6.0861),
            (25.7073, 6.0774),
            (35.684, 6.732),
        ]
        .iter()
        .map(|&(x, y)| Feature {
            kind: FeatureKind::Hole,
            hole_use: Some(HoleUse::Splice),
            node: None,
            crossing: None,
            center_part_mm: Point::new(x, y),
            width_mm: 2.6,
            depth_mm: 0.0,
            edge: None,
            angle_range_deg: None,
            station_mm: None,
        })
        .collect();
        let mut p = Part {
            id: "SP-edge03.1".into(),
            kind: PartKind::SplicePlate,
            strip: Some("edge03".into()),
            lamella: None,
            count: 1,
            length_mm: 41.4365,
            height_mm: 13.2571,
            station_start_mm: None,
            outline_part_mm: outline,
            holes_part_mm: Vec::new(),
            engraving: Vec::new(),
            features,
        };
        let clearance = 0.15 + 1.5;
        assert_eq!(engrave_other(&mut p, clearance), None);
        assert_eq!(p.engraving.len(), 1);
        assert!(p.engraving[0].height_mm >= MIN_HEIGHT_MM);
        assert_eq!(check_part(&p, clearance), Ok(()));
    }
}
