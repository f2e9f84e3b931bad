//! Curve ends and boundary strips of an asymptotic web cut to a square in
//! (u, v) on Enneper: the A and B lines u ± v = const run diagonally across
//! it, so the strips near the corners are short, carry two or three nodes
//! and run past their last node to the boundary. Read without normals
//! (coordinates rounded to 0.001 mm), every strip's largest twist must stay
//! within 25 % of the same web read with its exact surface normals, their
//! median within 3 %, and the check must find as many overstressed strips
//! (±1).

use crate::support::synth::{self, Enneper, ParamLine, ParamSurface, Sampling};
use crate::support::{export, profile, validate};
use glam::DVec2;
use lamella::check::check;
use lamella::network::{Family, Network, RawNetwork};
use lamella::{analyze, AnalysisOptions};

/// mm per surface unit (cells of about 300 mm, like a pavilion's).
const SCALE_MM: f64 = 4400.0;

/// The grid values of p = u + v and q = u − v, `spacing` apart, offset by
/// half a spacing from 0, over (−1, 1).
fn grid_values(spacing: f64) -> Vec<f64> {
    let n = (2.0 / spacing).round() as usize;
    (0..n).map(|i| -1.0 + spacing * (i as f64 + 0.5)).collect()
}

/// The lines p = p_i (A, along q) and q = q_j (B, along p), p_i, q_j on a
/// grid offset by half a spacing from 0, each cut to the square: its ends
/// lie beyond its first and last node.
fn web_lines(spacing: f64) -> Vec<ParamLine> {
    let values = grid_values(spacing);
    let mut lines = Vec::new();
    for (family, prefix) in [(Family::A, "A"), (Family::B, "B")] {
        for (i, &c) in values.iter().enumerate() {
            let reach = 1.0 + 0.3 * spacing - c.abs();
            // A: u = (c + t)/2, v = (c − t)/2; B: u = (t + c)/2, v = (t − c)/2.
            let (start, dir) = match family {
                Family::A => (DVec2::new(c / 2.0, c / 2.0), DVec2::new(0.5, -0.5)),
                _ => (DVec2::new(c / 2.0, -c / 2.0), DVec2::new(0.5, 0.5)),
            };
            lines.push(ParamLine {
                id: format!("{prefix}{i:02}"),
                family,
                start,
                dir,
                t0: -reach,
                t1: reach,
            });
        }
    }
    lines
}

/// The web sampled every `step_mm`, or at its nodes only when `step_mm` is
/// 0 (a quad grid's polylines), with exact normals or as exported.
fn web(spacing: f64, step_mm: f64, normals: bool) -> RawNetwork {
    let lines = web_lines(spacing);
    let mut raw = synth::network(
        "enneper-web",
        &Enneper,
        &lines,
        SCALE_MM,
        Sampling {
            step_mm: step_mm.max(1.0),
            normals: true,
        },
    );
    if step_mm == 0.0 {
        for (curve, line) in raw.curves.iter_mut().zip(&lines) {
            let ts: Vec<f64> = grid_values(spacing)
                .into_iter()
                .filter(|t| *t >= line.t0 - 1e-9 && *t <= line.t1 + 1e-9)
                .collect();
            curve.points = ts
                .iter()
                .map(|&t| Enneper.point(line.uv(t)) * SCALE_MM)
                .collect();
            curve.normals = Some(ts.iter().map(|&t| Enneper.normal(line.uv(t))).collect());
        }
    }
    export(raw, !normals)
}

/// Largest closed-form |tg| along a line, rad/mm: tg = 2/λ² (surface
/// units), λ = 1 + (p² + q²)/2, largest where |q| is least (q = 0 inside).
fn closed_form_max_tg(line: &ParamLine) -> f64 {
    let c = line.start.x + line.start.y * if line.family == Family::A { 1.0 } else { -1.0 };
    let lambda = 1.0 + c * c / 2.0;
    2.0 / (lambda * lambda) / SCALE_MM
}

/// Per A/B strip: id, largest |tg| (rad/mm), smallest bending radius (mm);
/// and the number of overstressed strips.
fn measure(net: &Network) -> (Vec<(String, f64, f64)>, usize) {
    let an = analyze(net, AnalysisOptions::for_network(net)).expect("analysis");
    let report = check(&an, &profile("steel-1.5"), false).0;
    let strips = an
        .lamella_strips()
        .map(|s| {
            (
                s.id.clone(),
                s.max_abs_tg_per_mm,
                s.min_bending_radius_mm().unwrap_or(f64::INFINITY),
            )
        })
        .collect();
    (strips, report.overstressed())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

#[test]
fn boundary_strips_twist_like_with_file_normals() {
    let mut failures = Vec::new();
    for (spacing, step_mm) in [(0.1, 0.0), (0.2, 0.0), (0.1, 10.0), (0.2, 50.0)] {
        let lines = web_lines(spacing);
        let (want, want_over) = measure(&validate(web(spacing, step_mm, true)));
        let (got, got_over) = measure(&validate(web(spacing, step_mm, false)));
        assert_eq!(want.len(), got.len());
        let mut errors = Vec::new();
        let mut report = String::new();
        for ((w, g), line) in want.iter().zip(&got).zip(&lines) {
            assert_eq!(w.0, g.0);
            let e = (g.1 - w.1) / w.1;
            errors.push(e);
            let deg_m = |x: f64| x.to_degrees() * 1000.0;
            report.push_str(&format!(
                "{spacing} {step_mm} mm {}: max tg {:.1} vs {:.1} (closed form {:.1}) °/m, {:+.1} %; min R {:.0} vs {:.0} mm\n",
                w.0,
                deg_m(g.1),
                deg_m(w.1),
                deg_m(closed_form_max_tg(line)),
                100.0 * e,
                g.2,
                w.2
            ));
        }
        let worst = errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let med = median(errors.clone());
        let med_tg = (median(got.iter().map(|g| g.1).collect())
            - median(want.iter().map(|w| w.1).collect()))
            / median(want.iter().map(|w| w.1).collect());
        eprintln!(
            "{report}{spacing} {step_mm} mm: worst {:.1} %, median error {:+.2} %, median twist {:+.2} %, overstressed {got_over} vs {want_over}",
            100.0 * worst,
            100.0 * med,
            100.0 * med_tg
        );
        if worst >= 0.25 || med_tg.abs() >= 0.03 || got_over.abs_diff(want_over) > 1 {
            failures.push(format!(
                "spacing {spacing}, {step_mm} mm: worst strip {:.1} %, median {:+.2} %, overstressed {got_over} vs {want_over}",
                100.0 * worst,
                100.0 * med_tg
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
