//! Joint sections: every kind of joint of the kit in section on one page
//! (panels side by side), its bolt along the page's vertical, head up: the
//! parts it clamps with their thicknesses (from the profile), the plain
//! washers and the nut (ISO 7089, ISO 4032), the bolt as ordered (its
//! length from the ISO 4017 series for the grip), its torque, and which
//! lamella of a doubled strip goes on which side. Each panel is drawn at
//! the largest of 10:1, 5:1, 2:1, 1:1 at which it fits, and says so.

use super::canvas::{Align, Canvas, BLACK, BLUE, GREY, LIGHT};
use super::{fixed, Frame, Page};
use crate::plan::joints::{EdgeSection, JointBolt, PlanJoint};
use crate::plan::Plan;

/// Text size of the notes and dimensions, pt.
const TEXT_PT: f64 = 7.0;
/// Room below each drawing for its notes, mm.
const NOTES_MM: f64 = 62.0;

/// The joint sections' page (none when the kit has no joints), then the
/// edge joint's page when lamellas end on edge bands.
pub fn pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let (edge, joints): (Vec<&PlanJoint>, Vec<&PlanJoint>) =
        plan.joints.iter().partition(|j| j.edge.is_some());
    let mut out = Vec::new();
    if !joints.is_empty() {
        let names: Vec<&str> = joints.iter().map(|j| j.title.as_str()).collect();
        let mut page = Page::new(
            "Joint sections",
            format!("Joint sections: {}", names.join(", ").to_lowercase()),
            None,
        );
        let n = joints.len() as f64;
        let w = frame.width_mm() / n;
        for (i, j) in joints.iter().enumerate() {
            let x0 = frame.x0_mm + i as f64 * w;
            panel(
                &mut page.canvas,
                j,
                [x0 + 3.0, frame.y0_mm, x0 + w - 3.0, frame.y1_mm],
            );
        }
        out.push(page);
    }
    for j in edge {
        if let Some(e) = &j.edge {
            out.push(edge_page(j, e, frame));
        }
    }
    out
}

/// Lamella and band fills.
const LAMELLA_FILL: [f32; 3] = [0.75, 0.8, 0.9];
const BAND_FILL: [f32; 3] = [0.85, 0.85, 0.75];

/// A dimension line from `a` to `b` (horizontal or vertical) with end ticks
/// and its text beside it (left of a vertical one, above a horizontal one).
fn dimension(c: &mut Canvas, a: [f64; 2], b: [f64; 2], text: &str) {
    c.stroke(BLUE);
    c.width(0.15);
    c.line(a, b);
    let vertical = (a[0] - b[0]).abs() < 1e-9;
    for p in [a, b] {
        if vertical {
            c.line([p[0] - 1.0, p[1]], [p[0] + 1.0, p[1]]);
        } else {
            c.line([p[0], p[1] - 1.0], [p[0], p[1] + 1.0]);
        }
    }
    c.fill(BLUE);
    if vertical {
        c.text(
            [a[0] - 1.2, 0.5 * (a[1] + b[1])],
            TEXT_PT,
            false,
            Align::Center,
            90.0,
            text,
        );
    } else {
        c.text(
            [0.5 * (a[0] + b[0]), a[1] + 1.0],
            TEXT_PT,
            false,
            Align::Center,
            0.0,
            text,
        );
    }
}

/// The edge joint's page: left, the section across the strip at an edge
/// node (looking along the strip toward its end), the band through the
/// lamellas' end slots and, bolted, the bolt through the gap and the
/// band's hole with its washers and nut; right, the elevation of the
/// lamella's end with its end slot, the band in section, the allowance and
/// the slot's depth. Both at the largest of 10:1, 5:1, 2:1, 1:1 that fits.
fn edge_page(j: &PlanJoint, e: &EdgeSection, frame: &Frame) -> Page {
    let mut page = Page::new(
        "Joint sections",
        format!("Joint sections: {}", j.title.to_lowercase()),
        None,
    );
    let c = &mut page.canvas;
    let (t, h, gap) = (e.thickness_mm, e.height_mm, e.gap_mm);
    let doubled = e.per_strip >= 2;
    let pair = if doubled { gap + 2.0 * t } else { t };
    let band_w = pair + 0.5 * h + 8.0;
    // Above and below the lamella: head and washer, washer and nut and the
    // bolt's end; the band where it lies beyond the lamella.
    let band_lo = e.slot_centre_mm - 0.5 * t;
    let band_hi = e.slot_centre_mm + 0.5 * t;
    let (above, below) = match &j.bolt {
        Some(b) => {
            let tail = (b.length_mm - h - 2.0 * b.washer_mm[0]).max(b.nut_mm);
            (0.7 * b.diameter_mm + b.washer_mm[0], b.washer_mm[0] + tail)
        }
        None => (0.0, 0.0),
    };
    let above = above.max(band_hi - h);
    let below = below.max(-band_lo);
    let tall = above + h + below;
    let elevation_w = e.slot_depth_mm + 0.6 * h;
    let half = 0.5 * frame.width_mm();
    let avail_h = frame.y1_mm - frame.y0_mm - NOTES_MM - 40.0;
    let k = [10.0, 5.0, 2.0, 1.0]
        .into_iter()
        .find(|k| {
            tall * k <= avail_h && band_w * k <= half - 80.0 && elevation_w * k <= half - 30.0
        })
        .unwrap_or(1.0);
    let (x0, y1) = (frame.x0_mm + 3.0, frame.y1_mm);
    c.fill(BLACK);
    c.text([x0, y1 - 5.0], 10.0, true, Align::Left, 0.0, &j.title);
    c.text(
        [x0, y1 - 9.5],
        TEXT_PT,
        false,
        Align::Left,
        0.0,
        &format!(
            "drawn {}:1; mm; the band and the lamellas cut short; figures from the profile",
            k as u32
        ),
    );
    // Both views share the heights: the lamella's bottom edge at y0.
    let top = y1 - 26.0;
    let y0 = top - (above + h) * k;
    let yy = |y: f64| y0 + y * k;
    let (slot_lo, slot_hi) = (
        (e.slot_centre_mm - 0.5 * e.slot_mm).max(0.0),
        (e.slot_centre_mm + 0.5 * e.slot_mm).min(h),
    );
    // Section across the strip.
    let ax = x0 + 30.0 + 0.5 * band_w * k;
    let label_x = ax + 0.5 * band_w * k + 12.0;
    c.fill(BLACK);
    c.text(
        [x0, top + 8.0],
        8.0,
        true,
        Align::Left,
        0.0,
        "Section across the strip at the node, looking toward its end",
    );
    let mut labels: Vec<(f64, String)> = Vec::new();
    c.stroke(BLACK);
    c.width(0.3);
    let lamella_xs: Vec<f64> = if doubled {
        vec![ax - 0.5 * gap * k - t * k, ax + 0.5 * gap * k]
    } else {
        vec![ax - 0.5 * t * k]
    };
    c.fill(LAMELLA_FILL);
    for &lx in &lamella_xs {
        if slot_lo > 0.0 {
            c.rect(lx, yy(0.0), t * k, slot_lo * k, true, true);
        }
        if slot_hi < h {
            c.rect(lx, yy(slot_hi), t * k, (h - slot_hi) * k, true, true);
        }
    }
    if doubled {
        c.fill(BLUE);
        c.text(
            [lamella_xs[0] - 1.0, yy(0.75 * h)],
            TEXT_PT,
            true,
            Align::Right,
            0.0,
            "2",
        );
        c.text(
            [lamella_xs[1] + t * k + 1.0, yy(0.75 * h)],
            TEXT_PT,
            true,
            Align::Left,
            0.0,
            "1",
        );
    }
    labels.push((
        yy(0.85 * h),
        if doubled {
            format!(
                "lamellas 2 | 1, t = {}, gap {}, h = {}",
                fixed(t, 1),
                fixed(gap, 1),
                fixed(h, 1)
            )
        } else {
            format!("lamella, t = {}, h = {}", fixed(t, 1), fixed(h, 1))
        },
    ));
    // The band through the slots (and the hole for the bolt).
    c.fill(BAND_FILL);
    c.stroke(BLACK);
    let bx0 = ax - 0.5 * band_w * k;
    let bx1 = ax + 0.5 * band_w * k;
    match e.hole_mm {
        Some(d) => {
            let hx = 0.5 * d * k;
            c.rect(bx0, yy(band_lo), ax - hx - bx0, t * k, true, true);
            c.rect(ax + hx, yy(band_lo), bx1 - ax - hx, t * k, true, true);
        }
        None => c.rect(bx0, yy(band_lo), bx1 - bx0, t * k, true, true),
    }
    labels.push((
        yy(e.slot_centre_mm),
        format!(
            "band, t = {}, in the end slots {} (t + 2 × {} clearance)",
            fixed(t, 1),
            fixed(e.slot_mm, 1),
            fixed(0.5 * (e.slot_mm - t), 1)
        ),
    ));
    if let Some(d) = e.hole_mm {
        labels.push((
            yy(e.slot_centre_mm) - 0.01,
            format!(
                "band hole Ø {} at the node, on its centre line",
                fixed(d, 1)
            ),
        ));
    }
    if let Some(b) = &j.bolt {
        let d = b.diameter_mm * k;
        let w = b.washer_mm[0] * k;
        let ow = b.washer_mm[1] * k;
        let head = 0.7 * b.diameter_mm * k;
        c.stroke(BLACK);
        c.width(0.3);
        c.fill(LIGHT);
        c.rect(ax - 0.8 * d, yy(h) + w, 1.6 * d, head, true, true);
        labels.push((yy(h) + w + 0.5 * head, format!("head of {}", b.designation)));
        c.fill([0.9, 0.9, 0.9]);
        c.rect(ax - 0.5 * ow, yy(h), ow, w, true, true);
        labels.push((
            yy(h) + 0.5 * w,
            format!("plain washer ISO 7089, {}", fixed(b.washer_mm[0], 1)),
        ));
        c.rect(ax - 0.5 * ow, yy(0.0) - w, ow, w, true, true);
        labels.push((
            yy(0.0) - 0.5 * w,
            format!("plain washer ISO 7089, {}", fixed(b.washer_mm[0], 1)),
        ));
        let nut = b.nut_mm * k;
        c.fill(LIGHT);
        c.rect(ax - 0.8 * d, yy(0.0) - w - nut, 1.6 * d, nut, true, true);
        labels.push((
            yy(0.0) - w - 0.5 * nut,
            format!("nut ISO 4032, m = {}", fixed(b.nut_mm, 1)),
        ));
        let grip_top = yy(h) + w;
        let end = grip_top - b.length_mm * k;
        c.stroke(BLACK);
        c.width(0.25);
        c.dash(true);
        c.rect(ax - 0.5 * d, end, d, grip_top - end, false, true);
        c.dash(false);
        let left = bx0 - 5.0;
        dimension(
            c,
            [left, yy(0.0)],
            [left, yy(h)],
            &format!("grip {}", fixed(b.grip_mm, 1)),
        );
        dimension(
            c,
            [left - 7.0, end],
            [left - 7.0, grip_top],
            &format!("L = {}", fixed(b.length_mm, 0)),
        );
    } else {
        dimension(
            c,
            [bx0 - 5.0, yy(0.0)],
            [bx0 - 5.0, yy(h)],
            &format!("h = {}", fixed(h, 1)),
        );
    }
    // Labels at the right, spread so none overprints.
    labels.sort_by(|a, b| b.0.total_cmp(&a.0));
    let pitch = 3.4;
    let mut last = f64::INFINITY;
    let mut placed = Vec::new();
    c.stroke(GREY);
    c.width(0.1);
    for (yl, text) in &labels {
        let at = yl.min(last - pitch);
        last = at;
        c.line(
            [ax + 0.5 * band_w * k - 2.0, *yl],
            [label_x - 1.0, at + 0.8],
        );
        placed.push((at, text.clone()));
    }
    c.fill(BLACK);
    for (at, text) in placed {
        c.text([label_x, at], TEXT_PT, false, Align::Left, 0.0, &text);
    }
    // Elevation of the lamella's end.
    let ex1 = frame.x0_mm + 2.0 * half - 20.0;
    let ex0 = ex1 - elevation_w * k;
    let xr = ex1 - e.slot_depth_mm * k;
    let xn = ex1 - e.allowance_mm * k;
    c.fill(BLACK);
    c.text(
        [ex0, top + 8.0],
        8.0,
        true,
        Align::Left,
        0.0,
        "Elevation of the lamella's end on the band (at a right angle)",
    );
    let mut outline = vec![[ex0, yy(0.0)]];
    if slot_lo > 0.0 {
        outline.extend([[ex1, yy(0.0)], [ex1, yy(slot_lo)], [xr, yy(slot_lo)]]);
    } else {
        outline.push([xr, yy(0.0)]);
    }
    if slot_hi < h {
        outline.extend([[xr, yy(slot_hi)], [ex1, yy(slot_hi)], [ex1, yy(h)]]);
    } else {
        outline.push([xr, yy(h)]);
    }
    outline.push([ex0, yy(h)]);
    c.fill(LAMELLA_FILL);
    c.fill_polygon(&outline);
    c.stroke(BLACK);
    c.width(0.3);
    c.polyline(&outline, true);
    c.fill(BAND_FILL);
    c.rect(xn - 0.5 * h * k, yy(band_lo), h * k, t * k, true, true);
    if let Some(b) = &j.bolt {
        let d = b.diameter_mm * k;
        let w = b.washer_mm[0] * k;
        let ow = b.washer_mm[1] * k;
        c.fill(LIGHT);
        c.rect(
            xn - 0.8 * d,
            yy(h) + w,
            1.6 * d,
            0.7 * b.diameter_mm * k,
            true,
            true,
        );
        c.fill([0.9, 0.9, 0.9]);
        c.rect(xn - 0.5 * ow, yy(h), ow, w, true, true);
        c.rect(xn - 0.5 * ow, yy(0.0) - w, ow, w, true, true);
        c.fill(LIGHT);
        c.rect(
            xn - 0.8 * d,
            yy(0.0) - w - b.nut_mm * k,
            1.6 * d,
            b.nut_mm * k,
            true,
            true,
        );
        c.stroke(BLACK);
        c.width(0.25);
        c.dash(true);
        c.rect(
            xn - 0.5 * d,
            yy(0.0) - w - b.nut_mm * k,
            d,
            (h * k) + 2.0 * w + b.nut_mm * k,
            false,
            true,
        );
        c.dash(false);
    }
    // Dimensions: the allowance and the band's width above, the slot's
    // depth below, the height and the slot at the right.
    let up = top + 2.0;
    dimension(
        c,
        [xn, up],
        [ex1, up],
        &format!("allowance {}", fixed(e.allowance_mm, 1)),
    );
    let band_y = yy(0.0) - below * k - 6.0;
    dimension(
        c,
        [xn - 0.5 * h * k, band_y],
        [xn + 0.5 * h * k, band_y],
        &format!("band {} wide", fixed(h, 1)),
    );
    dimension(
        c,
        [xr, band_y - 9.0],
        [ex1, band_y - 9.0],
        &format!("end slot {} deep", fixed(e.slot_depth_mm, 1)),
    );
    dimension(
        c,
        [ex0 - 6.0, yy(0.0)],
        [ex0 - 6.0, yy(h)],
        &format!("h = {}", fixed(h, 1)),
    );
    c.fill(BLACK);
    c.text(
        [ex1 + 2.0, yy(slot_hi) + 1.0],
        TEXT_PT,
        false,
        Align::Left,
        0.0,
        &format!("slot {}", fixed(e.slot_mm, 1)),
    );
    let notes_box = [x0, frame.y0_mm, frame.x1_mm - 3.0, frame.y1_mm];
    if let Some(b) = &j.bolt {
        bolt_lines(c, b, notes_box);
    }
    notes(c, j, notes_box);
    page
}

/// How wide a layer is drawn, mm: its width, cut short (the drawing says
/// how long it goes on) a little past the washers and the gap.
fn drawn_width(j: &PlanJoint, l: &crate::plan::joints::JointLayer) -> f64 {
    let limit = match (&j.bolt, j.beside) {
        (_, Some([t, gap, _])) => gap + 2.0 * t + 16.0,
        (Some(b), None) => (b.washer_mm[1] + 8.0).max(3.0 * b.diameter_mm),
        (None, None) => l.width_mm,
    };
    l.width_mm.min(limit)
}

/// The height of a joint's drawing at full size, mm (head to bolt end),
/// and its width.
fn extent_mm(j: &PlanJoint) -> (f64, f64) {
    let grip: f64 = j.stack.iter().map(|l| l.thickness_mm).sum();
    let wide = j
        .stack
        .iter()
        .map(|l| drawn_width(j, l))
        .fold(0.0, f64::max)
        .max(j.beside.map_or(0.0, |b| 2.0 * (b[0] + b[1])));
    match &j.bolt {
        Some(b) => {
            let washers = if b.plain_washers {
                2.0 * b.washer_mm[0]
            } else {
                0.0
            };
            let tail = (b.length_mm - grip - washers).max(b.nut_mm);
            (
                0.7 * b.diameter_mm + washers + grip + tail,
                wide.max(b.washer_mm[1]),
            )
        }
        None => (j.beside.map_or(10.0, |b| b[2]), wide),
    }
}

/// One joint's panel inside `bx` (x0, y0, x1, y1, mm).
fn panel(c: &mut Canvas, j: &PlanJoint, bx: [f64; 4]) {
    let (h_mm, w_mm) = extent_mm(j);
    let avail_h = bx[3] - bx[1] - NOTES_MM - 14.0;
    let avail_w = 0.5 * (bx[2] - bx[0]) - 4.0;
    let k = [10.0, 5.0, 2.0, 1.0]
        .into_iter()
        .find(|k| h_mm * k <= avail_h && w_mm * k <= avail_w)
        .unwrap_or(1.0);
    c.fill(BLACK);
    c.text([bx[0], bx[3] - 5.0], 10.0, true, Align::Left, 0.0, &j.title);
    c.text(
        [bx[0], bx[3] - 9.5],
        TEXT_PT,
        false,
        Align::Left,
        0.0,
        &format!("drawn {}:1; mm; plates and lamellas cut short", k as u32),
    );
    // The bolt axis at a quarter of the panel, head at the top.
    let ax = bx[0] + 14.0 + 0.25 * (bx[2] - bx[0]);
    let top = bx[3] - 16.0;
    let mut y = top;
    let label_x = bx[0] + 18.0 + 0.5 * (bx[2] - bx[0]);
    let mut labels: Vec<(f64, String)> = Vec::new();
    let Some(b) = &j.bolt else {
        slots(c, j, bx, k, top);
        notes(c, j, bx);
        return;
    };
    let d = b.diameter_mm * k;
    // Head (ISO 4017 head height about 0.7 d; across flats about 1.6 d).
    let head = 0.7 * b.diameter_mm * k;
    c.stroke(BLACK);
    c.width(0.3);
    c.fill(LIGHT);
    c.rect(ax - 0.8 * d, y - head, 1.6 * d, head, true, true);
    labels.push((y - 0.5 * head, format!("head of {}", b.designation)));
    y -= head;
    let grip_top = y;
    let washer = |c: &mut Canvas, y: &mut f64, labels: &mut Vec<(f64, String)>| {
        let t = b.washer_mm[0] * k;
        c.fill([0.9, 0.9, 0.9]);
        c.rect(
            ax - 0.5 * b.washer_mm[1] * k,
            *y - t,
            b.washer_mm[1] * k,
            t,
            true,
            true,
        );
        labels.push((
            *y - 0.5 * t,
            format!("plain washer ISO 7089, {}", fixed(b.washer_mm[0], 1)),
        ));
        *y -= t;
    };
    if b.plain_washers {
        washer(c, &mut y, &mut labels);
    }
    let clamp_top = y;
    for l in &j.stack {
        let t = l.thickness_mm * k;
        let w = drawn_width(j, l) * k;
        match (j.beside, l.lamella) {
            (Some([lt, gap, _]), true) => {
                // The doubled strip beside the bolt: lamella 2 left, 1 right.
                c.fill([0.75, 0.8, 0.9]);
                let (lt, gap) = (lt * k, gap * k);
                c.rect(ax - 0.5 * gap - lt, y - t, lt, t, true, true);
                c.rect(ax + 0.5 * gap, y - t, lt, t, true, true);
                // The crossing strip, behind, across the washers' arms.
                c.stroke(GREY);
                c.dash(true);
                c.rect(ax - 0.5 * w, y - t, w, t, false, true);
                c.dash(false);
                c.stroke(BLACK);
                c.fill(BLUE);
                c.text(
                    [ax - 0.5 * gap - lt - 1.0, y - 0.5 * t],
                    TEXT_PT,
                    true,
                    Align::Right,
                    0.0,
                    "2",
                );
                c.text(
                    [ax + 0.5 * gap + lt + 1.0, y - 0.5 * t],
                    TEXT_PT,
                    true,
                    Align::Left,
                    0.0,
                    "1",
                );
                labels.push((
                    y - 0.5 * t,
                    format!(
                        "{} (lamellas 2 | 1, t = {}, gap {})",
                        l.what,
                        fixed(lt / k, 1),
                        fixed(gap / k, 1)
                    ),
                ));
            }
            _ => {
                c.fill(if l.lamella {
                    [0.75, 0.8, 0.9]
                } else {
                    [0.85, 0.85, 0.75]
                });
                c.rect(ax - 0.5 * w, y - t, w, t, true, true);
                labels.push((y - 0.5 * t, l.what.clone()));
            }
        }
        y -= t;
    }
    let clamp_bottom = y;
    if b.plain_washers {
        washer(c, &mut y, &mut labels);
    }
    // Nut.
    let nut = b.nut_mm * k;
    c.fill(LIGHT);
    c.rect(ax - 0.8 * d, y - nut, 1.6 * d, nut, true, true);
    labels.push((
        y - 0.5 * nut,
        format!("nut ISO 4032, m = {}", fixed(b.nut_mm, 1)),
    ));
    // The bolt's shank from under the head to its end (length L).
    let end = grip_top - b.length_mm * k;
    c.stroke(BLACK);
    c.width(0.25);
    c.dash(true);
    c.rect(ax - 0.5 * d, end, d, grip_top - end, false, true);
    c.dash(false);
    // Dimensions: the grip and the length, left of the stack.
    let dim = |c: &mut Canvas, x: f64, y0: f64, y1: f64, text: &str| {
        c.stroke(BLUE);
        c.width(0.15);
        c.line([x, y0], [x, y1]);
        c.line([x - 1.0, y0], [x + 1.0, y0]);
        c.line([x - 1.0, y1], [x + 1.0, y1]);
        c.fill(BLUE);
        c.text(
            [x - 1.2, 0.5 * (y0 + y1)],
            TEXT_PT,
            false,
            Align::Center,
            90.0,
            text,
        );
    };
    let left = ax - 0.5 * w_mm * k - 5.0;
    dim(
        c,
        left,
        clamp_bottom,
        clamp_top,
        &format!("grip {}", fixed(b.grip_mm, 1)),
    );
    dim(
        c,
        left - 7.0,
        end,
        grip_top,
        &format!("L = {}", fixed(b.length_mm, 0)),
    );
    // Labels at the right, each on a leader, spread so none overprints.
    let pitch = 3.4;
    let mut last = f64::INFINITY;
    c.stroke(GREY);
    c.width(0.1);
    let mut placed = Vec::new();
    for (yl, t) in &labels {
        let at = yl.min(last - pitch);
        last = at;
        c.line([ax + 0.6 * d, *yl], [label_x - 1.0, at + 0.8]);
        placed.push((at, t.clone()));
    }
    c.fill(BLACK);
    for (at, t) in placed {
        c.text([label_x, at], TEXT_PT, false, Align::Left, 0.0, &t);
    }
    bolt_lines(c, b, bx);
    notes(c, j, bx);
}

/// The bolt's order line, count and torque under the drawing.
fn bolt_lines(c: &mut Canvas, b: &JointBolt, bx: [f64; 4]) {
    let y = bx[1] + NOTES_MM - 4.0;
    c.fill(BLACK);
    c.text(
        [bx[0], y],
        8.0,
        true,
        Align::Left,
        0.0,
        &format!("{} bolts {}", b.count, b.designation),
    );
    let nut_washers = if b.plain_washers {
        "a nut and two plain washers each"
    } else {
        "a nut each; the star washers under head and nut"
    };
    let torque = b
        .torque_nm
        .map(|t| format!("; tighten to {} N·m", fixed(t, 1)))
        .unwrap_or_else(|| "; no property class: no torque given".into());
    c.text(
        [bx[0], y - 4.0],
        TEXT_PT,
        false,
        Align::Left,
        0.0,
        &format!("{nut_washers}{torque}"),
    );
}

/// The notes under a panel, wrapped to its width.
fn notes(c: &mut Canvas, j: &PlanJoint, bx: [f64; 4]) {
    let mut y = bx[1] + NOTES_MM - 13.0;
    let width = bx[2] - bx[0];
    c.fill(BLACK);
    for n in &j.notes {
        let mut line = String::new();
        for word in n.split(' ') {
            let next = if line.is_empty() {
                word.to_string()
            } else {
                format!("{line} {word}")
            };
            if super::canvas::text_width_mm(&next, TEXT_PT, false) > width && !line.is_empty() {
                c.text([bx[0], y], TEXT_PT, false, Align::Left, 0.0, &line);
                y -= 3.3;
                line = format!("  {word}");
            } else {
                line = next;
            }
        }
        c.text([bx[0], y], TEXT_PT, false, Align::Left, 0.0, &line);
        y -= 4.0;
    }
}

/// Halving slots without a bolt: the two lamellas in elevation, A slotted
/// from its top edge, B from its bottom edge.
fn slots(c: &mut Canvas, j: &PlanJoint, bx: [f64; 4], k: f64, top: f64) {
    let Some([t, _, h]) = j.beside else {
        return;
    };
    let (h, t) = (h * k, (t * k).max(0.6));
    let len = 4.0 * h;
    let x0 = bx[0] + 4.0;
    c.stroke(BLACK);
    c.width(0.3);
    for (i, (name, from_top)) in [
        ("family A: slot from the top edge", true),
        ("family B: slot from the bottom edge", false),
    ]
    .into_iter()
    .enumerate()
    {
        let y0 = top - 8.0 - i as f64 * (h + 14.0) - h;
        let sx = x0 + 0.5 * len;
        let (sy0, sy1) = if from_top {
            (y0 + 0.5 * h, y0 + h)
        } else {
            (y0, y0 + 0.5 * h)
        };
        let pts = if from_top {
            vec![
                [x0, y0],
                [x0 + len, y0],
                [x0 + len, y0 + h],
                [sx + t, sy1],
                [sx + t, sy0],
                [sx - t, sy0],
                [sx - t, sy1],
                [x0, y0 + h],
            ]
        } else {
            vec![
                [x0, y0],
                [sx - t, y0],
                [sx - t, sy1],
                [sx + t, sy1],
                [sx + t, y0],
                [x0 + len, y0],
                [x0 + len, y0 + h],
                [x0, y0 + h],
            ]
        };
        c.polyline(&pts, true);
        c.fill(BLACK);
        c.text([x0, y0 + h + 2.0], TEXT_PT, false, Align::Left, 0.0, name);
    }
}
