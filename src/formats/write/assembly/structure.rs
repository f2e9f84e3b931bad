//! The structure pages (with `--loads`): what an engineer signs off.
//!
//! * **supports, loads and verdict**: the grid in an axonometric view with
//!   every support marked by its kind, the verdict, the model's size, the
//!   load cases' sums and every combination's α_cr, largest utilisation
//!   and largest displacement;
//! * **deformed shape** of the SLS combination with the largest deflection:
//!   the grid thin and grey, the deformed grid over it with its
//!   displacements scaled by a stated factor, the node that moves most
//!   marked, the limit stated;
//! * **utilisation**: every lamella element coloured by its largest ULS
//!   utilisation (load plus erection; the colour bar of the overview), the
//!   governing item named;
//! * **first buckling mode** of the ULS combination with the smallest
//!   α_cr, scaled and drawn over the grey grid;
//! * **reactions**: every support's reactions, per support the governing
//!   ULS combination's and the envelope over every combination (every
//!   combination's are in plan.json `structure.reactions`).
//!
//! The views are axonometric (x to the right and down, y to the right and
//! up, z up; 30° each way) and not to scale: the grid is fitted to the
//! view. Drawn from plan.json's `structure` and its drawing data, which
//! only a build in the same process has (a plan read back from plan.json
//! draws no structure pages).

use super::canvas::{Align, Canvas, Rgb3, BLACK, BLUE, GREY, LIGHT, RED};
use super::tables::{draw_block, table_pages, Column, Row, HEADER_MM, ROW_MM};
use super::{fixed, utilisation_colour, Frame, Page};
use crate::plan::structure::{PlanStructure, StructureDrawing};
use crate::plan::Plan;
use glam::DVec3;

/// The section's name.
pub const SECTION: &str = "Structure";

/// The largest drawn displacement or mode amplitude, as a fraction of the
/// view's larger side.
const SHOWN_FRACTION: f64 = 0.08;

/// The structure pages, none without a frame analysis.
pub fn pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let Some(st) = &plan.structure else {
        return Vec::new();
    };
    let Some(d) = &st.drawing else {
        return Vec::new();
    };
    let mut pages = vec![summary_page(st, d, frame)];
    pages.extend(deformed_page(st, d, frame));
    pages.push(utilisation_page(st, d, frame));
    pages.extend(mode_page(d, frame));
    pages.extend(bracing_pages(st, d, frame));
    pages.extend(reaction_pages(st, frame));
    pages
}

/// The axonometric projection of a point, mm (not to scale).
fn axo(p: DVec3) -> [f64; 2] {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    [(p.x + p.y) * c, (p.y - p.x) * s + p.z]
}

/// A view: the grid's nodes (and their moved positions) fitted into a box.
struct View {
    origin: [f64; 2],
    lo: [f64; 2],
    scale: f64,
}

impl View {
    /// The view of `points` fitted into (x, y, w, h), with a margin.
    fn fit(points: &[DVec3], (x, y, w, h): (f64, f64, f64, f64)) -> View {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in points {
            let q = axo(*p);
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let (ew, eh) = ((hi[0] - lo[0]).max(1.0), (hi[1] - lo[1]).max(1.0));
        let margin = 8.0;
        let scale = ((w - 2.0 * margin) / ew).min((h - 2.0 * margin) / eh);
        View {
            origin: [x + 0.5 * (w - ew * scale), y + 0.5 * (h - eh * scale)],
            lo,
            scale,
        }
    }

    fn map(&self, p: DVec3) -> [f64; 2] {
        let q = axo(p);
        [
            self.origin[0] + (q[0] - self.lo[0]) * self.scale,
            self.origin[1] + (q[1] - self.lo[1]) * self.scale,
        ]
    }
}

/// The grid's elements, each a line, in one colour and width.
fn draw_grid(c: &mut Canvas, d: &StructureDrawing, view: &View, at: impl Fn(usize) -> DVec3) {
    for ([a, b], _) in &d.elements {
        c.line(view.map(at(*a)), view.map(at(*b)));
    }
}

/// The factor that draws `moves` (per node) at most `SHOWN_FRACTION` of
/// the grid's size, rounded down to 1, 2 or 5 × 10ⁿ.
fn display_factor(d: &StructureDrawing, moves: &[DVec3]) -> f64 {
    let largest = moves.iter().map(|v| v.length()).fold(0.0, f64::max);
    let (lo, hi) = d.nodes_mm.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let size = (hi - lo).max_element();
    if largest <= 0.0 || !size.is_finite() {
        return 1.0;
    }
    let raw = SHOWN_FRACTION * size / largest;
    let decade = 10f64.powf(raw.log10().floor());
    let step = [5.0, 2.0, 1.0]
        .into_iter()
        .find(|m| m * decade <= raw)
        .unwrap_or(1.0);
    step * decade
}

/// The drawing's box on a page: the content less a band at the foot for
/// notes, mm.
fn drawing_box(frame: &Frame, right_mm: f64) -> (f64, f64, f64, f64) {
    (
        frame.x0_mm,
        frame.y0_mm + 14.0,
        frame.width_mm() - right_mm,
        frame.height_mm() - 14.0,
    )
}

/// Notes at the foot of a drawing, one line each.
fn notes(c: &mut Canvas, frame: &Frame, lines: &[String]) {
    c.fill(BLACK);
    for (i, l) in lines.iter().enumerate() {
        c.text(
            [frame.x0_mm, frame.y0_mm + 8.0 - 4.5 * i as f64],
            8.0,
            i == 0,
            Align::Left,
            0.0,
            l,
        );
    }
}

/// A support's symbol: a triangle (pinned), a filled square (fixed), a
/// circle (roller), a diamond (anything else).
fn support_symbol(c: &mut Canvas, at: [f64; 2], kind: &str) {
    let r = 1.6;
    c.stroke(BLACK);
    c.fill(BLACK);
    c.width(0.25);
    match kind {
        "pinned" => c.polyline(
            &[
                at,
                [at[0] - r, at[1] - 1.7 * r],
                [at[0] + r, at[1] - 1.7 * r],
            ],
            true,
        ),
        "fixed" => c.rect(at[0] - r, at[1] - r, 2.0 * r, 2.0 * r, true, false),
        "roller" => c.circle([at[0], at[1] - r], r, false),
        _ => c.polyline(
            &[
                [at[0], at[1] + r],
                [at[0] + r, at[1]],
                [at[0], at[1] - r],
                [at[0] - r, at[1]],
            ],
            true,
        ),
    }
}

fn kn(n: f64) -> String {
    fixed(n / 1000.0, 2)
}

const CASE_COLUMNS: [Column; 5] = [
    ("load case (sums)", 26.0, Align::Left),
    ("action", 18.0, Align::Left),
    ("Fx kN", 16.0, Align::Right),
    ("Fy kN", 16.0, Align::Right),
    ("Fz kN", 16.0, Align::Right),
];

const COMBINATION_COLUMNS: [Column; 6] = [
    ("combination", 38.0, Align::Left),
    ("alpha_cr", 13.0, Align::Right),
    ("util.", 13.0, Align::Right),
    ("strip", 13.0, Align::Left),
    ("max. mm", 14.0, Align::Right),
    ("load Fz kN", 15.0, Align::Right),
];

/// Supports, load cases, combinations and the verdict.
fn summary_page(st: &PlanStructure, d: &StructureDrawing, frame: &Frame) -> Page {
    let table_w: f64 = COMBINATION_COLUMNS.iter().map(|c| c.1).sum();
    let mut page = Page::new(SECTION, "Structure: supports, loads and verdict", None);
    let c = &mut page.canvas;
    let area = drawing_box(frame, table_w + 8.0);
    let view = View::fit(&d.nodes_mm, area);
    c.stroke(GREY);
    c.width(0.2);
    draw_grid(c, d, &view, |n| d.nodes_mm[n]);
    for (node, kind) in &d.supports {
        support_symbol(c, view.map(d.nodes_mm[*node]), kind);
    }
    let kinds: std::collections::BTreeSet<&str> =
        d.supports.iter().map(|(_, k)| k.as_str()).collect();
    notes(
        c,
        frame,
        &[
            st.verdict.clone(),
            format!(
                "{} supports ({}: triangle pinned, square fixed, circle roller); loads {}; span {} mm, deflection limit {} mm; axonometric, not to scale",
                d.supports.len(),
                kinds.into_iter().collect::<Vec<_>>().join(", "),
                st.loads,
                fixed(st.span_mm, 0),
                fixed(st.deflection_limit_mm, 1)
            ),
        ],
    );
    let x = frame.x1_mm - table_w;
    let mut top = frame.y1_mm;
    let text = |c: &mut Canvas, top: &mut f64, s: &str, bold: bool| {
        c.fill(BLACK);
        c.text([x, *top - 3.5], 8.0, bold, Align::Left, 0.0, s);
        *top -= 5.0;
    };
    let m = &st.model;
    text(c, &mut top, "Model", true);
    text(
        c,
        &mut top,
        &format!(
            "{} nodes, {} beam elements ({} per node-to-node span), {} links",
            m.nodes, m.beams, m.elements_per_span, m.links
        ),
        false,
    );
    text(
        c,
        &mut top,
        &format!(
            "imperfection for second order: first mode, {} mm",
            fixed(st.imperfection_mm, 1)
        ),
        false,
    );
    top -= 2.0;
    let cases: Vec<Row> = st
        .load_cases
        .iter()
        .map(|l| {
            (
                vec![
                    l.name.clone(),
                    l.action.clone(),
                    kn(l.load_sum_n[0]),
                    kn(l.load_sum_n[1]),
                    kn(l.load_sum_n[2]),
                ],
                None,
            )
        })
        .collect();
    draw_block(c, &CASE_COLUMNS, x, top, &cases);
    top -= HEADER_MM + cases.len() as f64 * ROW_MM + 6.0;
    let rows: Vec<Row> = st
        .combinations
        .iter()
        .map(|k| {
            let over = k.max_utilisation.is_some_and(|u| u > 1.0)
                || k.alpha_cr.first().is_some_and(|a| *a <= 1.0);
            (
                vec![
                    k.name.clone(),
                    k.alpha_cr.first().map_or("-".into(), |a| fixed(*a, 2)),
                    k.max_utilisation.map_or("-".into(), |u| fixed(u, 2)),
                    k.governing_strip.clone().unwrap_or_else(|| "-".into()),
                    fixed(k.max_translation_mm, 1),
                    kn(k.load_sum_n[2]),
                ],
                over.then_some(RED),
            )
        })
        .collect();
    draw_down_to_frame(
        c,
        &COMBINATION_COLUMNS,
        x,
        top,
        frame,
        &rows,
        "in plan.json",
    );
    page
}

/// The rows of a table from `top` down to the frame's bottom, and a line
/// saying how many more plan.json has where they do not all fit.
fn draw_down_to_frame(
    c: &mut Canvas,
    columns: &[Column],
    x: f64,
    top: f64,
    frame: &Frame,
    rows: &[Row],
    rest: &str,
) -> usize {
    // The last line under the table says where the rest are.
    let room = ((top - frame.y0_mm - HEADER_MM - 5.0) / ROW_MM)
        .floor()
        .max(0.0) as usize;
    let shown = rows.len().min(room);
    draw_block(c, columns, x, top, &rows[..shown]);
    if shown < rows.len() {
        c.fill(BLACK);
        c.text(
            [x, top - HEADER_MM - shown as f64 * ROW_MM - 4.0],
            7.0,
            false,
            Align::Left,
            0.0,
            &format!("… {} more {rest}", rows.len() - shown),
        );
    }
    shown
}

/// The SLS deformed shape.
fn deformed_page(st: &PlanStructure, d: &StructureDrawing, frame: &Frame) -> Option<Page> {
    let (name, moves) = d.deflection.as_ref()?;
    let factor = display_factor(d, moves);
    let mut page = Page::new(
        SECTION,
        format!("Structure: deformed shape under {name}, displacements × {factor}"),
        None,
    );
    let c = &mut page.canvas;
    let (view, moved) = draw_displaced(c, d, frame, moves, factor, BLUE);
    let (most, largest) = moves
        .iter()
        .enumerate()
        .map(|(i, u)| (i, u.length()))
        .fold((0, 0.0), |b, x| if x.1 > b.1 { x } else { b });
    let at = view.map(moved[most]);
    c.stroke(RED);
    c.fill(RED);
    c.circle(at, 1.2, true);
    let node = st
        .deflection
        .as_ref()
        .map(|x| x.node.clone())
        .unwrap_or_default();
    c.text(
        [at[0] + 2.5, at[1] + 1.5],
        8.0,
        true,
        Align::Left,
        0.0,
        &format!("{} mm (node {node})", fixed(largest, 1)),
    );
    let verdict = if largest <= st.deflection_limit_mm {
        "within"
    } else {
        "OVER"
    };
    notes(
        c,
        frame,
        &[
            format!(
                "largest displacement {} mm at node {node}, {verdict} the limit of {} mm (span {} mm / {})",
                fixed(largest, 1),
                fixed(st.deflection_limit_mm, 1),
                fixed(st.span_mm, 0),
                fixed(st.span_mm / st.deflection_limit_mm, 0)
            ),
            format!(
                "grey: the erected grid; blue: deformed under {name}, displacements drawn {factor} times; axonometric, not to scale"
            ),
        ],
    );
    Some(page)
}

/// Every lamella element by its largest ULS utilisation.
fn utilisation_page(st: &PlanStructure, d: &StructureDrawing, frame: &Frame) -> Page {
    let mut page = Page::new(
        SECTION,
        "Structure: utilisation of every lamella (ULS, load plus erection)",
        None,
    );
    let c = &mut page.canvas;
    let bar_w = 40.0;
    let view = View::fit(&d.nodes_mm, drawing_box(frame, bar_w + 6.0));
    // The least used first, so the governing elements are on top.
    let mut order: Vec<usize> = (0..d.elements.len()).collect();
    order.sort_by(|a, b| d.elements[*a].1.total_cmp(&d.elements[*b].1));
    c.width(0.5);
    for i in order {
        let ([a, b], u) = d.elements[i];
        c.stroke(utilisation_colour(u));
        c.line(view.map(d.nodes_mm[a]), view.map(d.nodes_mm[b]));
    }
    for (node, kind) in &d.supports {
        support_symbol(c, view.map(d.nodes_mm[*node]), kind);
    }
    // The colour bar.
    let x = frame.x1_mm - bar_w;
    let mut y = frame.y1_mm - 6.0;
    c.fill(BLACK);
    c.text([x, y], 8.0, true, Align::Left, 0.0, "utilisation");
    for (label, u) in [
        ("0", 0.0),
        ("0.25", 0.25),
        ("0.5", 0.5),
        ("0.75", 0.75),
        ("0.9", 0.9),
        ("1.0", 1.0),
        ("over 1", 1.5),
    ] {
        y -= 6.0;
        c.fill(utilisation_colour(u));
        c.rect(x, y, 8.0, 4.0, true, false);
        c.fill(BLACK);
        c.text([x + 10.0, y + 1.0], 7.0, false, Align::Left, 0.0, label);
    }
    let mut lines = Vec::new();
    if let Some(g) = &st.governing {
        lines.push(format!(
            "governing: strip {} lamella {} at {} mm, {} check, utilisation {} under {}",
            g.strip,
            g.lamella,
            fixed(g.station_mm, 0),
            g.check,
            fixed(g.utilisation, 2),
            g.combination
        ));
    }
    lines.push(
        "each element coloured by its largest utilisation over every ULS combination (EN 1993-1-1 §6.2/6.3 or EN 1995-1-1 §6); axonometric, not to scale"
            .into(),
    );
    notes(c, frame, &lines);
    page
}

/// The erected grid in grey, the grid moved by `moves` × `factor` in
/// `colour` over it and the supports, fitted into the drawing box; the
/// view and the moved nodes.
fn draw_displaced(
    c: &mut Canvas,
    d: &StructureDrawing,
    frame: &Frame,
    moves: &[DVec3],
    factor: f64,
    colour: Rgb3,
) -> (View, Vec<DVec3>) {
    let moved: Vec<DVec3> = d
        .nodes_mm
        .iter()
        .zip(moves)
        .map(|(p, u)| *p + *u * factor)
        .collect();
    let all: Vec<DVec3> = d.nodes_mm.iter().chain(&moved).copied().collect();
    let view = View::fit(&all, drawing_box(frame, 0.0));
    c.stroke(LIGHT);
    c.width(0.2);
    draw_grid(c, d, &view, |n| d.nodes_mm[n]);
    c.stroke(colour);
    c.width(0.3);
    draw_grid(c, d, &view, |n| moved[n]);
    for (node, kind) in &d.supports {
        support_symbol(c, view.map(d.nodes_mm[*node]), kind);
    }
    (view, moved)
}

/// The first buckling mode.
fn mode_page(d: &StructureDrawing, frame: &Frame) -> Option<Page> {
    let (name, alpha, shape) = d.mode.as_ref()?;
    let factor = display_factor(d, shape);
    let mut page = Page::new(
        SECTION,
        format!(
            "Structure: first buckling mode under {name}, α_cr = {}",
            fixed(*alpha, 2)
        ),
        None,
    );
    draw_displaced(&mut page.canvas, d, frame, shape, factor, RED);
    let c = &mut page.canvas;
    let stands = if *alpha > 1.0 {
        "above 1: the grid does not buckle under this combination"
    } else {
        "at most 1: the grid buckles under this combination"
    };
    notes(
        c,
        frame,
        &[
            format!(
                "critical load factor α_cr = {} under {name}, {stands}; second order runs where α_cr < 10 (EN 1993-1-1 §5.2.1)",
                fixed(*alpha, 2)
            ),
            format!(
                "grey: the erected grid; red: the first mode, its largest translation drawn {} mm (the mode's scale is arbitrary); axonometric, not to scale",
                fixed(factor, 0)
            ),
        ],
    );
    Some(page)
}

const REACTION_COLUMNS: [Column; 12] = [
    ("support", 16.0, Align::Left),
    ("kind", 14.0, Align::Left),
    ("x mm", 15.0, Align::Right),
    ("y mm", 15.0, Align::Right),
    ("z mm", 15.0, Align::Right),
    ("Rx kN", 13.0, Align::Right),
    ("Ry kN", 13.0, Align::Right),
    ("Rz kN", 13.0, Align::Right),
    ("min Rz", 13.0, Align::Right),
    ("max Rz", 13.0, Align::Right),
    ("max Rxy", 13.0, Align::Right),
    ("max |M| kNm", 19.0, Align::Right),
];

/// Every support's reactions: under the governing ULS combination, and
/// the envelope over every combination.
fn reaction_pages(st: &PlanStructure, frame: &Frame) -> Vec<Page> {
    let governing = st
        .governing
        .as_ref()
        .map(|g| g.combination.as_str())
        .or(st.alpha_cr.as_ref().map(|a| a.combination.as_str()));
    let k = governing
        .and_then(|name| st.combinations.iter().position(|c| c.name == name))
        .unwrap_or(0);
    let name = st
        .combinations
        .get(k)
        .map(|c| c.name.clone())
        .unwrap_or_default();
    let rows: Vec<Row> = st
        .reactions
        .iter()
        .map(|r| {
            let f = r.forces_n.get(k).copied().unwrap_or_default();
            let rz = r.forces_n.iter().map(|f| f[2]);
            let min_rz = rz.clone().fold(f64::INFINITY, f64::min);
            let max_rz = rz.fold(f64::NEG_INFINITY, f64::max);
            let rxy = r
                .forces_n
                .iter()
                .map(|f| f[0].hypot(f[1]))
                .fold(0.0, f64::max);
            let moment = r
                .moments_nmm
                .iter()
                .map(|m| (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt())
                .fold(0.0, f64::max);
            (
                vec![
                    r.node.clone(),
                    r.kind.clone(),
                    fixed(r.position_mm[0], 0),
                    fixed(r.position_mm[1], 0),
                    fixed(r.position_mm[2], 0),
                    kn(f[0]),
                    kn(f[1]),
                    kn(f[2]),
                    kn(min_rz),
                    kn(max_rz),
                    kn(rxy),
                    fixed(moment / 1e6, 3),
                ],
                None,
            )
        })
        .collect();
    table_pages(
        frame,
        SECTION,
        &format!(
            "Structure: reactions on the supports (R on the grid); Rx Ry Rz under {name}, the envelope over all {} combinations",
            st.combinations.len()
        ),
        &REACTION_COLUMNS,
        &rows,
    )
}

const CABLE_COLUMNS: [Column; 7] = [
    ("cable", 12.0, Align::Left),
    ("nodes", 20.0, Align::Left),
    ("dia mm", 11.0, Align::Right),
    ("pin-pin mm", 18.0, Align::Right),
    ("wire cut mm", 19.0, Align::Right),
    ("T0 kN", 13.0, Align::Right),
    ("max kN", 13.0, Align::Right),
];

/// The eye plate drawn full size (on the A3 sheet) at (`x`, `top`): its
/// outline, the bolt's and the pin's holes, their centre line, with its
/// measures beside it; returns the y below it.
fn eye_plate_detail(
    c: &mut Canvas,
    f: &crate::plan::structure::PlanFittings,
    d: &StructureDrawing,
    x: f64,
    top: f64,
) -> f64 {
    let (w, s) = (f.eye_plate_width_mm, f.eye_plate_hole_spacing_mm);
    let (x0, y0) = (x + 2.0, top - 2.0 - w);
    c.stroke(BLACK);
    c.width(0.3);
    let outline: Vec<[f64; 2]> = d
        .eye_plate_mm
        .iter()
        .map(|p| [x0 + p[0], y0 + p[1]])
        .collect();
    c.polyline(&outline, true);
    let mid = 0.5 * w;
    c.circle([x0 + mid, y0 + mid], 0.5 * f.bolt_hole_mm, false);
    c.circle([x0 + mid + s, y0 + mid], 0.5 * f.pin_hole_mm, false);
    c.stroke(GREY);
    c.width(0.15);
    c.dash(true);
    c.line([x0 - 1.0, y0 + mid], [x0 + s + w + 1.0, y0 + mid]);
    c.dash(false);
    c.fill(BLACK);
    let tx = x0 + s + w + 4.0;
    let lines = [
        format!(
            "{} at 1:1 (A3): {} × {} mm",
            f.eye_plate_part,
            fixed(s + w, 0),
            fixed(w, 0)
        ),
        format!(
            "holes {} and {} mm",
            fixed(f.bolt_hole_mm, 1),
            fixed(f.pin_hole_mm, 1)
        ),
        format!("{} mm apart; nested as a part", fixed(s, 0)),
    ];
    for (i, l) in lines.iter().enumerate() {
        c.text(
            [tx, top - 6.0 - 4.0 * i as f64],
            7.0,
            false,
            Align::Left,
            0.0,
            l,
        );
    }
    top - 4.0 - w
}

/// The bracing plan: the grid with every cable and its id, the cable
/// schedule (continued on pages of its own where it does not fit), the
/// strand, its fittings and how the figures moved.
fn bracing_pages(st: &PlanStructure, d: &StructureDrawing, frame: &Frame) -> Vec<Page> {
    let Some(b) = st.bracing.as_ref() else {
        return Vec::new();
    };
    let table_w: f64 = CABLE_COLUMNS.iter().map(|c| c.1).sum();
    let mut page = Page::new(SECTION, "Structure: bracing plan and cable schedule", None);
    let c = &mut page.canvas;
    let view = View::fit(&d.nodes_mm, drawing_box(frame, table_w + 8.0));
    c.stroke(GREY);
    c.width(0.2);
    draw_grid(c, d, &view, |n| d.nodes_mm[n]);
    for (node, kind) in &d.supports {
        support_symbol(c, view.map(d.nodes_mm[*node]), kind);
    }
    c.stroke(RED);
    c.width(0.6);
    for ([p, q], cable) in d.cables.iter().zip(&b.cables) {
        let (a, z) = (view.map(*p), view.map(*q));
        c.line(a, z);
        c.fill(RED);
        // A third of the way from its fixed end: a crossed pair's ids
        // do not meet at the crossing.
        let mid = [
            a[0] + (z[0] - a[0]) / 3.0 + 1.0,
            a[1] + (z[1] - a[1]) / 3.0 + 1.0,
        ];
        c.text(mid, 6.0, true, Align::Left, 0.0, &cable.id);
    }
    let figures = |f: &crate::plan::structure::PlanFigures| {
        format!(
            "α_cr {}, deflection {} mm, utilisation {}",
            f.alpha_cr.map_or("-".into(), |a| fixed(a, 2)),
            f.deflection_mm.map_or("-".into(), |x| fixed(x, 1)),
            f.utilisation.map_or("-".into(), |u| fixed(u, 2)),
        )
    };
    notes(
        c,
        frame,
        &[
            format!(
                "{} layout, {} diagonals: {} cables of {} candidates; unbraced {}; braced {}",
                b.layout,
                b.diagonals,
                b.cables.len(),
                b.candidates,
                figures(&b.before),
                figures(&b.after)
            ),
            "cables in red with their ids, on eye plates under the node bolts; axonometric, not to scale".into(),
        ],
    );
    let x = frame.x1_mm - table_w;
    let mut top = frame.y1_mm;
    let text = |c: &mut Canvas, top: &mut f64, s: &str, bold: bool| {
        c.fill(BLACK);
        c.text([x, *top - 3.5], 8.0, bold, Align::Left, 0.0, s);
        *top -= 5.0;
    };
    text(c, &mut top, "Cables", true);
    text(
        c,
        &mut top,
        &format!("{} dia. {} mm", b.designation, fixed(b.diameter_mm, 0)),
        false,
    );
    text(
        c,
        &mut top,
        &format!(
            "F_Rd {} kN, largest force {} kN, pretension {} kN",
            fixed(b.design_resistance_kn, 2),
            fixed(b.max_force_kn, 2),
            fixed(b.pretension_kn, 2)
        ),
        false,
    );
    text(
        c,
        &mut top,
        &format!(
            "{} m pin to pin, {} m of wire",
            fixed(b.total_length_m, 2),
            fixed(b.total_wire_m, 2)
        ),
        false,
    );
    text(
        c,
        &mut top,
        "wire cut: pin to pin less terminal and turnbuckle at mid take-up, unstressed",
        false,
    );
    let f = &b.fittings;
    text(c, &mut top, "Fittings", true);
    text(
        c,
        &mut top,
        &format!(
            "{} eye plates ({}), {} mm thick, under the node bolts;",
            f.eye_plates,
            f.eye_plate_part,
            fixed(f.eye_plate_thickness_mm, 1),
        ),
        false,
    );
    text(
        c,
        &mut top,
        &format!(
            "pin hole F_Rd {} kN (EN 1993-1-8 Table 3.9);",
            fixed(f.eye_plate_resistance_kn, 2),
        ),
        false,
    );
    text(
        c,
        &mut top,
        &format!("cable axis {} mm above the node", fixed(f.offset_mm, 1)),
        false,
    );
    text(
        c,
        &mut top,
        &format!(
            "fork terminal {} mm, turnbuckle {} mm at mid take-up (take-up {} mm)",
            fixed(f.terminal_mm, 0),
            fixed(f.turnbuckle_mid_mm, 0),
            fixed(f.take_up_mm, 0)
        ),
        false,
    );
    top = eye_plate_detail(c, f, d, x, top);
    top -= 2.0;
    let rows: Vec<Row> = b
        .cables
        .iter()
        .map(|k| {
            (
                vec![
                    k.id.clone(),
                    format!("{}-{}", k.nodes[0], k.nodes[1]),
                    fixed(b.diameter_mm, 0),
                    fixed(k.length_mm, 1),
                    fixed(k.wire_cut_mm, 1),
                    fixed(k.pretension_kn, 2),
                    fixed(k.max_force_kn, 2),
                ],
                (k.max_force_kn > b.design_resistance_kn).then_some(RED),
            )
        })
        .collect();
    let shown = draw_down_to_frame(c, &CABLE_COLUMNS, x, top, frame, &rows, "on the next pages");
    // The rest of the schedule, whole, on pages of its own.
    let mut pages = vec![page];
    if shown < rows.len() {
        pages.extend(table_pages(
            frame,
            SECTION,
            "Structure: cable schedule, continued",
            &CABLE_COLUMNS,
            &rows[shown..],
        ));
    }
    pages
}
