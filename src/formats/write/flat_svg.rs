//! flat.svg: the flat grid to scale (one SVG unit = 1 mm, y up), for
//! marking out the assembly floor: every strip as a polyline through its
//! nodes, labelled at both ends; every node a circle with its id and the
//! rotation it turns through on erection (degrees, counter-clockwise
//! positive, A → B). Deterministic: fixed decimals.

use crate::plan::FlatDrawing;
use std::fmt::Write;

/// Margin round the grid, mm.
const MARGIN_MM: f64 = 200.0;

/// The SVG text of a flat state; `title` names the project.
pub fn to_svg(flat: &FlatDrawing, title: &str) -> String {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for n in &flat.nodes {
        for k in 0..2 {
            lo[k] = lo[k].min(n.position_mm[k]);
            hi[k] = hi[k].max(n.position_mm[k]);
        }
    }
    if flat.nodes.is_empty() {
        lo = [0.0; 2];
        hi = [0.0; 2];
    }
    let (x0, y0) = (lo[0] - MARGIN_MM, lo[1] - MARGIN_MM);
    let (w, h) = (
        hi[0] - lo[0] + 2.0 * MARGIN_MM,
        hi[1] - lo[1] + 2.0 * MARGIN_MM,
    );
    // Sheet coordinates: x from the left margin, y down from the top.
    let at = |p: [f64; 2]| (p[0] - x0, h - (p[1] - y0));
    let text_mm = (0.06
        * (flat
            .strips
            .iter()
            .flat_map(|s| s.lengths_mm.iter())
            .sum::<f64>()
            / flat
                .strips
                .iter()
                .map(|s| s.lengths_mm.len())
                .sum::<usize>()
                .max(1) as f64))
        .clamp(5.0, 60.0);
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.1}mm" height="{h:.1}mm" viewBox="0 0 {w:.1} {h:.1}">"#
    );
    let _ = writeln!(s, "<title>{}</title>", escape(title));
    let _ = writeln!(
        s,
        r##"<g id="STRIPS" fill="none" stroke-width="{:.2}" stroke-linecap="round" stroke-linejoin="round">"##,
        0.15 * text_mm
    );
    for strip in &flat.strips {
        if strip.nodes.len() < 2 {
            continue;
        }
        let colour = if strip.family_a { "#c00000" } else { "#0040c0" };
        let _ = write!(s, r#"<polyline stroke="{colour}" points=""#);
        for (k, &i) in strip.nodes.iter().enumerate() {
            let (x, y) = at(flat.nodes[i].position_mm);
            let _ = write!(s, "{}{x:.2},{y:.2}", if k > 0 { " " } else { "" });
        }
        let _ = writeln!(s, r#""/>"#);
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r##"<g id="STRIP-LABELS" font-family="sans-serif" font-size="{:.1}" text-anchor="middle">"##,
        1.4 * text_mm
    );
    for strip in &flat.strips {
        if strip.nodes.len() < 2 {
            continue;
        }
        let n = strip.nodes.len();
        for (end, next) in [(0, 1), (n - 1, n - 2)] {
            let p = flat.nodes[strip.nodes[end]].position_mm;
            let q = flat.nodes[strip.nodes[next]].position_mm;
            let d = [p[0] - q[0], p[1] - q[1]];
            let len = d[0].hypot(d[1]).max(1e-9);
            // Beyond the end node, along the strip.
            let lbl = [
                p[0] + d[0] / len * 3.0 * text_mm,
                p[1] + d[1] / len * 3.0 * text_mm,
            ];
            let (x, y) = at(lbl);
            let _ = writeln!(
                s,
                r#"<text x="{x:.2}" y="{:.2}">{}</text>"#,
                y + 0.5 * text_mm,
                escape(&strip.id)
            );
        }
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r##"<g id="NODES" font-family="sans-serif" font-size="{:.1}" fill="#000000">"##,
        text_mm
    );
    for n in &flat.nodes {
        let (x, y) = at(n.position_mm);
        let _ = writeln!(
            s,
            r##"<circle cx="{x:.2}" cy="{y:.2}" r="{:.2}" fill="none" stroke="#000000" stroke-width="{:.2}"/><text x="{:.2}" y="{:.2}">{} {:+.1}°</text>"##,
            0.4 * text_mm,
            0.1 * text_mm,
            x + 0.6 * text_mm,
            y - 0.6 * text_mm,
            n.node,
            n.rotation_deg
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(s, "</svg>");
    s
}

fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
