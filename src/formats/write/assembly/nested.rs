//! Sheets as nested: one stock sheet per page, drawn by
//! [`crate::formats::write::drawing::Drawer`] (the cutting files' own geometry,
//! nominal) at the largest standard scale at which the sheet fits, every
//! placed part outlined and labelled with its id where the label
//! overprints no other (else beside it; parts left without room are
//! counted under the sheet). Engraving is left out
//! (too fine at these scales); outlines are thinned to 0.1 mm on paper.

use super::canvas::{self, Align, BLACK, GREY};
use super::nodeplan::Labels;
use super::{fixed, standard_scale, Frame, Page, SealedPage};
use crate::error::Result;
use crate::formats::write::arcs::flatten;
use crate::formats::write::drawing::{within, Drawer, Layer, Shape, SheetDrawing};
use crate::plan::{Plan, PlanSheet};
use rayon::prelude::*;
use std::path::Path;

/// Room above the sheet for its line of figures, mm.
const SUB_MM: f64 = 8.0;

/// One page per sheet, in nest order.
pub fn pages(plan: &Plan, frame: &Frame, plan_path: &Path) -> Result<Vec<SealedPage>> {
    let drawer = Drawer::new(plan, None, plan_path)?;
    let sheets = plan.sheets.as_deref().unwrap_or_default();
    (0..drawer.len())
        .into_par_iter()
        .map(|i| {
            Ok(page(
                &drawer.sheet_cuts(i)?,
                &sheets[i],
                drawer.len(),
                frame,
            ))
        })
        .collect()
}

/// The page of one stock sheet, `sheet` drawn from the plan's sheet `meta`
/// (nominal: without kerf compensation) of `count` sheets. Engraving in
/// the drawing, if any, is left out.
pub fn page(sheet: &SheetDrawing, meta: &PlanSheet, count: usize, frame: &Frame) -> SealedPage {
    let den =
        (sheet.length_mm / frame.width_mm()).max(sheet.width_mm / (frame.height_mm() - SUB_MM));
    let scale = standard_scale(den);
    let s = 1.0 / f64::from(scale);
    let mut page = Page::new(
        "Sheets as nested",
        if meta.group.is_empty() {
            format!("Sheet {} of {}: {}", sheet.number, count, sheet.id)
        } else {
            format!(
                "Sheet {} of {}: {}, {} {} mm ({})",
                sheet.number, count, sheet.id, meta.material, meta.thickness_mm, meta.group
            )
        },
        Some(scale),
    );
    let c = &mut page.canvas;
    c.fill(BLACK);
    c.text(
        [frame.x0_mm, frame.y1_mm - 4.0],
        8.0,
        false,
        Align::Left,
        0.0,
        &format!(
            "stock {} {} mm, {} parts, utilisation {} %; file sheets/{}.dxf",
            if meta.form.is_empty() {
                "sheet"
            } else {
                &meta.form
            },
            meta.stock,
            sheet.parts.len(),
            fixed(100.0 * meta.utilization, 1),
            sheet.file_stem()
        ),
    );
    let ox = frame.x0_mm;
    let oy = frame.y1_mm - SUB_MM - sheet.width_mm * s;
    let map = |x: f64, y: f64| [ox + x * s, oy + y * s];
    c.stroke(GREY);
    c.width(0.3);
    c.rect(ox, oy, sheet.length_mm * s, sheet.width_mm * s, false, true);
    for part in &sheet.parts {
        for sh in &part.shapes {
            match sh {
                Shape::Polyline {
                    layer,
                    closed,
                    vertices,
                } if *layer != Layer::Engrave => {
                    c.stroke(if *layer == Layer::CutOuter {
                        BLACK
                    } else {
                        GREY
                    });
                    c.width(if *layer == Layer::CutOuter { 0.15 } else { 0.1 });
                    let mut pts: Vec<[f64; 2]> = Vec::with_capacity(vertices.len());
                    // Arcs as chords within 0.05 mm on paper.
                    for q in flatten(vertices, *closed, 0.05 / s) {
                        let p = map(q[0], q[1]);
                        if pts
                            .last()
                            .is_none_or(|q: &[f64; 2]| !within(p[0] - q[0], p[1] - q[1], 0.1))
                        {
                            pts.push(p);
                        }
                    }
                    c.polyline(&pts, *closed);
                }
                Shape::Circle {
                    center_mm,
                    radius_mm,
                    ..
                } => {
                    c.stroke(GREY);
                    c.width(0.1);
                    c.circle(
                        map(center_mm[0], center_mm[1]),
                        (radius_mm * s).max(0.15),
                        false,
                    );
                }
                _ => {}
            }
        }
    }
    // Labels: as large as fits the part's box, 4 to 8 pt, where they
    // overprint no other label (else beside, else counted in the list).
    c.fill([0.1, 0.1, 0.5]);
    let mut labels = Labels::new(None);
    let mut unlabelled: std::collections::BTreeMap<&str, usize> = Default::default();
    for part in &sheet.parts {
        let [x0, y0, x1, y1] = part.bbox_mm;
        let (bw, bh) = ((x1 - x0) * s, (y1 - y0) * s);
        let text = canvas::winansi(&part.part);
        let w1 = canvas::text_width_mm(&text, 1.0, false);
        let at = map(0.5 * (x0 + x1), 0.5 * (y0 + y1));
        // A part much taller than wide is labelled upright.
        let upright = bh > 2.0 * bw && bw < w1 * 4.0;
        let size = if upright {
            (0.85 * bh / w1).min(0.6 * bw / canvas::cap_mm(1.0))
        } else {
            (0.85 * bw / w1).min(0.6 * bh / canvas::cap_mm(1.0))
        }
        .clamp(4.0, 8.0);
        // The box from the descender to the cap height.
        let desc = 0.3 * canvas::cap_mm(size);
        let (w, h) = (w1 * size, canvas::cap_mm(size) + desc);
        let (bw_l, bh_l) = if upright { (h, w) } else { (w, h) };
        let centred = [
            at[0] - 0.5 * bw_l,
            at[1] - 0.5 * bh_l,
            at[0] + 0.5 * bw_l,
            at[1] + 0.5 * bh_l,
        ];
        let lower_left = if labels.free(&centred) {
            labels.hold(centred);
            Some([centred[0], centred[1]])
        } else {
            labels.place(at, bw_l, bh_l, 0.3).map(|(ll, _)| ll)
        };
        let Some(ll) = lower_left else {
            *unlabelled.entry(part.part.as_str()).or_default() += 1;
            continue;
        };
        if upright {
            c.text(
                [ll[0] + h - desc, ll[1] + 0.5 * w],
                size,
                false,
                Align::Center,
                90.0,
                &text,
            );
        } else {
            c.text(
                [ll[0] + 0.5 * w, ll[1] + desc],
                size,
                false,
                Align::Center,
                0.0,
                &text,
            );
        }
    }
    if !unlabelled.is_empty() {
        let list: Vec<String> = unlabelled
            .iter()
            .map(|(id, n)| format!("{id} × {n}"))
            .collect();
        c.fill(BLACK);
        c.text(
            [frame.x1_mm, frame.y1_mm - 4.0],
            7.0,
            false,
            Align::Right,
            0.0,
            &format!("not labelled above (no room): {}", list.join(", ")),
        );
    }
    page.seal()
}
