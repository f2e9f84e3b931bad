//! Joint sections: every kind of joint of the kit in section on one page
//! (panels side by side), its bolt along the page's vertical, head up: the
//! parts it clamps with their thicknesses (from the profile), the plain
//! washers and the nut (ISO 7089, ISO 4032), the bolt as ordered (its
//! length from the ISO 4017 series for the grip), its torque, and which
//! lamella of a doubled strip goes on which side. Each panel is drawn at
//! the largest of 10:1, 5:1, 2:1, 1:1 at which it fits, and says so.

use super::canvas::{Align, Canvas, BLACK, BLUE, GREY, LIGHT};
use super::{fixed, Frame, Page};
use crate::plan::joints::{JointBolt, PlanJoint};
use crate::plan::Plan;

/// Text size of the notes and dimensions, pt.
const TEXT_PT: f64 = 7.0;
/// Room below each drawing for its notes, mm.
const NOTES_MM: f64 = 62.0;

/// The joint sections' page (none when the kit has no joints).
pub fn pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    if plan.joints.is_empty() {
        return Vec::new();
    }
    let names: Vec<&str> = plan.joints.iter().map(|j| j.title.as_str()).collect();
    let mut page = Page::new(
        "Joint sections",
        format!("Joint sections: {}", names.join(", ").to_lowercase()),
        None,
    );
    let n = plan.joints.len() as f64;
    let w = frame.width_mm() / n;
    for (i, j) in plan.joints.iter().enumerate() {
        let x0 = frame.x0_mm + i as f64 * w;
        panel(
            &mut page.canvas,
            j,
            [x0 + 3.0, frame.y0_mm, x0 + w - 3.0, frame.y1_mm],
        );
    }
    vec![page]
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
