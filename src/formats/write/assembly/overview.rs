//! The overview: the erected grid in plan (x, y) and two elevations (x, z
//! from the front, y, z from the side), one scale for all three, chosen
//! from the standard series so they fit. A and B strips coloured by their
//! utilisation (a colour bar explains it), edge strips in black and
//! thicker, nodes as dots, every strip labelled at both ends in plan
//! where its id fits clear of the others (else on the node plan only).

use super::canvas::{self, Align, Canvas, BLACK, GREY};
use super::nodeplan::Labels;
use super::{standard_scale, utilisation_colour, AssemblyInput, Frame, Page};
use std::collections::HashMap;

/// A view's box on the page: x, y, width, height, mm.
type ViewBox = (f64, f64, f64, f64);

/// Room around each view for labels, mm.
const PAD_MM: f64 = 9.0;
/// Height of the colour bar band at the foot of the plan view, mm.
const BAR_MM: f64 = 16.0;
/// Strip labels, pt.
const LABEL_PT: f64 = 6.0;

/// The overview page (none when there are no curves).
pub fn pages(input: &AssemblyInput, frame: &Frame) -> Vec<Page> {
    let curves = &input.plan.curves;
    if curves.is_empty() {
        return Vec::new();
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in curves.iter().flat_map(|c| &c.points_mm) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext = [
        (hi[0] - lo[0]).max(1.0),
        (hi[1] - lo[1]).max(1.0),
        (hi[2] - lo[2]).max(1.0),
    ];
    // Plan on the left, the two elevations stacked on the right.
    let gap = 6.0;
    let w = frame.width_mm();
    let h = frame.height_mm();
    let plan_w = 0.6 * w;
    let right_w = w - plan_w - gap;
    let plan_h = h - BAR_MM;
    let elev_h = 0.5 * (h - gap);
    let den = [
        ext[0] / (plan_w - 2.0 * PAD_MM),
        ext[1] / (plan_h - 2.0 * PAD_MM),
        ext[0] / (right_w - 2.0 * PAD_MM),
        ext[1] / (right_w - 2.0 * PAD_MM),
        ext[2] / (elev_h - 2.0 * PAD_MM),
    ]
    .into_iter()
    .fold(0.0, f64::max);
    let scale = standard_scale(den.max(1e-6));
    let s = 1.0 / f64::from(scale);
    let mut page = Page::new(
        "Overview",
        "Overview: plan and elevations of the erected grid",
        Some(scale),
    );
    let c = &mut page.canvas;
    let util: HashMap<&str, (String, Option<f64>)> = input
        .plan
        .strips
        .iter()
        .map(|st| {
            (
                st.id.as_str(),
                (
                    st.family.clone(),
                    st.check.as_ref().map(|k| k.stress.utilization),
                ),
            )
        })
        .collect();
    // View origins: each view centred in its box.
    let plan_box = (frame.x0_mm, frame.y0_mm + BAR_MM, plan_w, plan_h);
    let front_box = (
        frame.x0_mm + plan_w + gap,
        frame.y0_mm + elev_h + gap,
        right_w,
        elev_h,
    );
    let side_box = (frame.x0_mm + plan_w + gap, frame.y0_mm, right_w, elev_h);
    let views: [(&str, ViewBox, usize, usize); 3] = [
        ("plan (x right, y up)", plan_box, 0, 1),
        ("front elevation (x right, z up)", front_box, 0, 2),
        ("side elevation (y right, z up)", side_box, 1, 2),
    ];
    for (vi, (name, (bx, by, bw, bh), i, j)) in views.into_iter().enumerate() {
        let ox = bx + 0.5 * bw - 0.5 * ext[i] * s;
        let oy = by + 0.5 * bh - 0.5 * ext[j] * s;
        let map = |p: &[f64; 3]| [ox + (p[i] - lo[i]) * s, oy + (p[j] - lo[j]) * s];
        c.stroke(GREY);
        c.width(0.15);
        c.rect(bx, by, bw, bh, false, true);
        c.fill(BLACK);
        c.text([bx + 2.0, by + bh - 4.0], 8.0, true, Align::Left, 0.0, name);
        // Lamella strips first, edges on top.
        for edges in [false, true] {
            for cv in curves {
                let (family, u) = util
                    .get(cv.id.as_str())
                    .cloned()
                    .unwrap_or(("edge".into(), None));
                if (family == "edge") != edges {
                    continue;
                }
                let colour = if edges {
                    BLACK
                } else {
                    u.map(utilisation_colour).unwrap_or(GREY)
                };
                c.stroke(colour);
                c.width(if edges { 0.5 } else { 0.3 });
                let pts: Vec<[f64; 2]> = thin(cv.points_mm.iter().map(map).collect(), 0.4);
                c.polyline(&pts, false);
            }
        }
        // Nodes.
        c.fill(BLACK);
        let r = if input.plan.nodes.len() > 2000 {
            0.2
        } else {
            0.35
        };
        // A big grid's nodes are dotted in plan only (elevations would be solid).
        let nodes: &[crate::plan::PlanNode] = if input.plan.nodes.len() > 2000 && vi > 0 {
            &[]
        } else {
            &input.plan.nodes
        };
        for n in nodes {
            if input.plan.nodes.len() > 2000 {
                c.dot(map(&n.position_mm), 2.0 * r);
            } else {
                c.circle(map(&n.position_mm), r, true);
            }
        }
        if vi == 0 {
            let centre = [ox + 0.5 * ext[i] * s, oy + 0.5 * ext[j] * s];
            // Labels never overprint: each goes where it fits, else is left
            // to the node plan (which labels every strip at its own scale).
            let mut labels = Labels::new(Some([bx, by, bx + bw, by + bh - 5.0]));
            for cv in curves {
                let pts: Vec<[f64; 2]> = cv.points_mm.iter().map(map).collect();
                let edge = util.get(cv.id.as_str()).is_none_or(|u| u.0 == "edge");
                if edge {
                    label_middle(c, &mut labels, &cv.id, &pts, centre);
                } else {
                    label_ends(c, &mut labels, &cv.id, &pts);
                }
            }
        }
    }
    colour_bar(c, frame.x0_mm + 4.0, frame.y0_mm + 3.0, 0.6 * plan_w);
    vec![page]
}

/// Drop points within `tol_mm` of the last kept (paper mm), keeping the ends.
fn thin(pts: Vec<[f64; 2]>, tol_mm: f64) -> Vec<[f64; 2]> {
    let n = pts.len();
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(n);
    for (k, p) in pts.into_iter().enumerate() {
        let keep = match out.last() {
            None => true,
            Some(q) => k + 1 == n || (p[0] - q[0]).hypot(p[1] - q[1]) >= tol_mm,
        };
        if keep {
            out.push(p);
        }
    }
    out
}

/// Draw `id` with its baseline start at `at` (`bold` or not) when its
/// box is free, else at the nearest free place around `near`; nothing
/// when there is none.
fn put(c: &mut Canvas, labels: &mut Labels, id: &str, at: [f64; 2], near: [f64; 2], bold: bool) {
    let w = canvas::text_width_mm(&canvas::winansi(id), LABEL_PT, bold);
    let h = canvas::cap_mm(LABEL_PT);
    let b = [at[0] - 0.2, at[1] - 0.5, at[0] + w + 0.2, at[1] + h + 0.3];
    let at = if labels.free(&b) {
        labels.hold(b);
        Some(at)
    } else {
        labels
            .place(near, w + 0.4, h + 0.8, 1.2)
            .map(|(ll, _)| [ll[0] + 0.2, ll[1] + 0.5])
    };
    if let Some(at) = at {
        c.text(at, LABEL_PT, bold, Align::Left, 0.0, id);
    }
}

/// The strip's id just beyond both ends, along its end direction.
fn label_ends(c: &mut Canvas, labels: &mut Labels, id: &str, pts: &[[f64; 2]]) {
    if pts.len() < 2 {
        return;
    }
    let n = pts.len();
    let ends = [(pts[0], pts[1.min(n - 1)]), (pts[n - 1], pts[n - 2])];
    let w = canvas::text_width_mm(&canvas::winansi(id), LABEL_PT, false);
    c.fill(BLACK);
    for (end, inner) in ends {
        let (dx, dy) = (end[0] - inner[0], end[1] - inner[1]);
        let len = dx.hypot(dy).max(1e-9);
        let (ux, uy) = (dx / len, dy / len);
        let at = [
            end[0] + 1.2 * ux,
            end[1] + 1.2 * uy - 0.35 * canvas::cap_mm(LABEL_PT),
        ];
        let at = if ux > 0.4 {
            at
        } else if ux < -0.4 {
            [at[0] - w, at[1]]
        } else {
            [at[0] - 0.5 * w, at[1] + if uy > 0.0 { 0.8 } else { -1.6 }]
        };
        put(c, labels, id, at, end, false);
    }
}

/// An edge strip's id beside its middle, on the side away from `centre`
/// (its ends meet the lamella strips' labels).
fn label_middle(c: &mut Canvas, labels: &mut Labels, id: &str, pts: &[[f64; 2]], centre: [f64; 2]) {
    if pts.is_empty() {
        return;
    }
    let m = pts[pts.len() / 2];
    let (dx, dy) = (m[0] - centre[0], m[1] - centre[1]);
    c.fill(BLACK);
    let cap = canvas::cap_mm(LABEL_PT);
    let w = canvas::text_width_mm(&canvas::winansi(id), LABEL_PT, true);
    let at = if dx.abs() >= dy.abs() {
        if dx > 0.0 {
            [m[0] + 6.0, m[1] + 1.5]
        } else {
            [m[0] - 6.0 - w, m[1] + 1.5]
        }
    } else {
        [m[0] + 6.0, m[1] + if dy > 0.0 { 5.5 } else { -5.5 - cap }]
    };
    put(c, labels, id, at, m, true);
}

/// A colour bar from utilisation 0 to 1 (and above), `w` mm long.
fn colour_bar(c: &mut Canvas, x: f64, y: f64, w: f64) {
    let w = w.min(150.0);
    let steps = 40;
    let bw = w / f64::from(steps);
    for k in 0..steps {
        let u = (f64::from(k) + 0.5) / f64::from(steps);
        c.fill(utilisation_colour(u));
        c.rect(x + f64::from(k) * bw, y + 4.0, bw + 0.05, 3.5, true, false);
    }
    c.fill(utilisation_colour(1.1));
    c.rect(x + w + 2.0, y + 4.0, 8.0, 3.5, true, false);
    c.fill(BLACK);
    for k in 0..=4 {
        let u = f64::from(k) / 4.0;
        c.text(
            [x + u * w, y + 0.5],
            7.0,
            false,
            Align::Center,
            0.0,
            &format!("{u:.2}"),
        );
    }
    c.text(
        [x + w + 6.0, y + 0.5],
        7.0,
        false,
        Align::Center,
        0.0,
        "> 1",
    );
    c.text(
        [x, y + 8.8],
        7.0,
        false,
        Align::Left,
        0.0,
        "utilisation of the strip's worst lamella; edge strips black; dots: nodes; ids that would overprint are on the node plan",
    );
}

/// Node labels on the flat layout, pt.
const NODE_PT: f64 = 5.0;

/// The flat assembly layout (plan.json's `flat`, when the flat state was
/// computed): every A/B strip through its nodes' floor positions at one
/// standard scale, A red, B blue, labelled at both ends; every node a
/// circle with its id and the rotation it turns through on erection.
pub fn flat_page(plan: &crate::plan::Plan, frame: &Frame) -> Option<Page> {
    let flat = plan.flat.as_ref()?;
    let pos: HashMap<usize, [f64; 2]> =
        flat.nodes.iter().map(|n| (n.node, n.position_mm)).collect();
    if pos.is_empty() {
        return None;
    }
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in pos.values() {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let pad = 2.0 * PAD_MM;
    let den = ((hi[0] - lo[0]).max(1.0) / (frame.width_mm() - 2.0 * pad))
        .max((hi[1] - lo[1]).max(1.0) / (frame.height_mm() - 2.0 * pad));
    let scale = standard_scale(den.max(1e-6));
    let s = 1.0 / f64::from(scale);
    let (cx, cy) = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
    let (px, py) = (
        0.5 * (frame.x0_mm + frame.x1_mm),
        0.5 * (frame.y0_mm + frame.y1_mm),
    );
    let at = |p: [f64; 2]| [px + (p[0] - cx) * s, py + (p[1] - cy) * s];
    let mut page = Page::new(
        "Assembly order",
        format!(
            "Flat assembly layout: footprint {} x {} mm, joints turn up to {:.1} deg on erection (node: id, rotation)",
            super::mm0(flat.footprint_mm[0]),
            super::mm0(flat.footprint_mm[1]),
            flat.max_rotation_deg
        ),
        Some(scale),
    );
    let c: &mut Canvas = &mut page.canvas;
    c.width(0.35);
    for st in &plan.strips {
        let colour = match st.family.as_str() {
            "A" => canvas::RED,
            "B" => canvas::BLUE,
            _ => continue,
        };
        let pts: Vec<[f64; 2]> = st
            .nodes
            .iter()
            .filter_map(|n| pos.get(&n.node).map(|p| at(*p)))
            .collect();
        if pts.len() < 2 {
            continue;
        }
        c.stroke(colour);
        c.polyline(&pts, false);
        c.fill(colour);
        for (end, next) in [(0, 1), (pts.len() - 1, pts.len() - 2)] {
            let (p, q) = (pts[end], pts[next]);
            let d = [p[0] - q[0], p[1] - q[1]];
            let len = d[0].hypot(d[1]).max(1e-9);
            let lbl = [p[0] + d[0] / len * 5.0, p[1] + d[1] / len * 5.0 - 1.0];
            c.text(lbl, LABEL_PT, true, Align::Center, 0.0, &st.id);
        }
    }
    c.stroke(BLACK);
    c.fill(BLACK);
    c.width(0.2);
    for n in &flat.nodes {
        let p = at(n.position_mm);
        c.circle(p, 0.8, false);
        c.text(
            [p[0] + 1.0, p[1] + 1.0],
            NODE_PT,
            false,
            Align::Left,
            0.0,
            &format!("{} {:+.1}", n.node, n.rotation_deg),
        );
    }
    c.fill(GREY);
    Some(page)
}
