//! Stations on lamella lines offset from the curve (docs/geometry.md "Where each
//! lamella really is") against a numerical integration of the exact offset
//! line c(s) + dy·y(s) + dz·z(s) built from the closed-form surface.

use crate::support::synth::{self, Enneper, Helicoid, ParamLine, ParamSurface, Sampling};
use crate::support::*;
use glam::{DVec2, DVec3};
use lamella::analysis::lines::LamellaLine;
use lamella::profile::LamellaOffset;

/// Length of t ↦ X(t) + dy·y(t) + dz·z(t) over the whole line (fine polygon with
/// Richardson extrapolation), z the analytic unit normal times `zsign`.
fn exact_offset_length(
    surface: &dyn ParamSurface,
    line: &ParamLine,
    scale: f64,
    dy: f64,
    dz: f64,
    zsign: f64,
) -> f64 {
    let (t0, t1) = (line.t0, line.t1);
    let p = |t: f64| {
        let uv = line.uv(t);
        let (xu, xv) = surface.partials(uv);
        let x = (xu * line.dir.x + xv * line.dir.y).normalize();
        let z = surface.normal(uv) * zsign;
        let y = z.cross(x);
        surface.point(uv) * scale + y * dy + z * dz
    };
    let poly = |n: usize| {
        let mut len = 0.0;
        let mut prev = p(t0);
        for i in 1..=n {
            let q = p(t0 + (t1 - t0) * i as f64 / n as f64);
            len += q.distance(prev);
            prev = q;
        }
        len
    };
    let (a, b) = (poly(20_000), poly(40_000));
    b + (b - a) / 3.0
}

/// Arc lengths of the same exact offset line from its start to each of the
/// parameters `ts` (ascending, in [t0, t1]): a fine polygon on every
/// interval between them, Richardson-extrapolated (each interval's count
/// doubles, so the h² error term cancels interval by interval).
fn exact_offset_stations(
    surface: &dyn ParamSurface,
    line: &ParamLine,
    scale: f64,
    (dy, dz, zsign): (f64, f64, f64),
    ts: &[f64],
) -> Vec<f64> {
    let p = |t: f64| {
        let uv = line.uv(t);
        let (xu, xv) = surface.partials(uv);
        let x = (xu * line.dir.x + xv * line.dir.y).normalize();
        let z = surface.normal(uv) * zsign;
        let y = z.cross(x);
        surface.point(uv) * scale + y * dy + z * dz
    };
    let span = line.t1 - line.t0;
    let run = |per_span: f64| {
        let mut out = Vec::with_capacity(ts.len());
        let (mut acc, mut prev_t) = (0.0, line.t0);
        let mut prev = p(prev_t);
        for &t in ts {
            let n = ((t - prev_t) / span * per_span).ceil() as usize;
            for i in 1..=n {
                let q = p(prev_t + (t - prev_t) * i as f64 / n as f64);
                acc += q.distance(prev);
                prev = q;
            }
            prev_t = t;
            prev = p(t);
            out.push(acc);
        }
        out
    };
    let (a, b) = (run(10_000.0), run(20_000.0));
    a.iter().zip(&b).map(|(a, b)| b + (b - a) / 3.0).collect()
}

/// Parameter on `line` where it crosses `other` (straight lines in (u, v)).
fn crossing_t(line: &ParamLine, other: &ParamLine) -> f64 {
    // start + dir·t = o.start + o.dir·s  →  solve the 2×2 system for t.
    let (d, e, r) = (line.dir, other.dir, other.start - line.start);
    let det = d.x * (-e.y) - (-e.x) * d.y;
    (r.x * (-e.y) - (-e.x) * r.y) / det
}

fn check(
    surface: &dyn ParamSurface,
    lines: &[ParamLine],
    scale: f64,
    step_mm: f64,
    normals: bool,
    tol_mm: f64,
) {
    let raw = synth::network("o", surface, lines, scale, Sampling { step_mm, normals });
    let (_net, an) = run(raw);
    let mut nodes_checked = 0;
    for (strip, line) in an.strips.iter().zip(lines) {
        let smooth = &an.curves[strip.curve];
        // Orientation of lamella's z against the analytic normal.
        let mid = strip.frame_at(smooth, 0.5 * strip.length_mm);
        let zsign = if mid.z.dot(surface.normal(line.uv(nearest_t(
            surface,
            line,
            scale,
            mid.point_world_mm,
        )))) < 0.0
        {
            -1.0
        } else {
            1.0
        };
        for (dy, dz) in [(10.75, 0.0), (-10.75, 0.0), (0.0, 30.0), (8.0, -25.0)] {
            let stations = [0.0, strip.length_mm];
            let got = strip.offset_stations(smooth, dy, dz, &stations, 25.0);
            let want = exact_offset_length(surface, line, scale, dy, dz, zsign);
            let centre = strip.length_mm;
            assert!(
                (got[1] - got[0] - want).abs() < tol_mm,
                "{} dy {dy} dz {dz}: offset length {} vs exact {want} (centre {centre})",
                strip.id,
                got[1] - got[0]
            );
            // Every node's station on the lamella's own line.
            let lamella = LamellaLine::new(
                strip,
                smooth,
                LamellaOffset {
                    number: 1,
                    dy_mm: dy,
                    dz_mm: dz,
                },
            );
            // The same integral (other breakpoints: the nodes).
            assert!(
                (lamella.length_mm - got[1]).abs() < 1e-3,
                "{}: {} vs {}",
                strip.id,
                lamella.length_mm,
                got[1]
            );
            assert_eq!(lamella.nodes.len(), strip.nodes.len(), "{}", strip.id);
            assert!(!lamella.nodes.is_empty());
            let ts: Vec<f64> = strip
                .nodes
                .iter()
                .map(|cn| crossing_t(line, &lines[cn.crossing]))
                .collect();
            let exact = exact_offset_stations(surface, line, scale, (dy, dz, zsign), &ts);
            for ((ln, cn), want) in lamella.nodes.iter().zip(&strip.nodes).zip(&exact) {
                assert_eq!(ln.node, cn.node);
                assert!(
                    (ln.station_mm - want).abs() < 0.01,
                    "{} dy {dy} dz {dz}: node {} at {} on the lamella line, exactly {want}",
                    strip.id,
                    ln.node,
                    ln.station_mm
                );
            }
            nodes_checked += lamella.nodes.len();
        }
    }
    assert!(nodes_checked > 100, "{nodes_checked} node stations checked");
}

/// The parameter of the line point closest to `p` (coarse search is enough
/// to read off the normal's orientation).
fn nearest_t(surface: &dyn ParamSurface, line: &ParamLine, scale: f64, p: DVec3) -> f64 {
    (0..=1000)
        .map(|i| line.t0 + (line.t1 - line.t0) * i as f64 / 1000.0)
        .min_by(|a, b| {
            let da = (surface.point(line.uv(*a)) * scale).distance(p);
            let db = (surface.point(line.uv(*b)) * scale).distance(p);
            da.total_cmp(&db)
        })
        .unwrap()
}

#[test]
fn enneper_lamella_lines_match_exact_offsets() {
    let lines = synth::diagonal_lines(0.5, 7, DVec2::ZERO);
    check(&Enneper, &lines, 4400.0, 20.0, true, 0.01);
    check(&Enneper, &lines, 4400.0, 20.0, false, 0.02);
}

#[test]
fn helicoid_lamella_lines_match_exact_offsets() {
    let c = 1000.0;
    let us: Vec<f64> = synth::spread(0.75, 5).iter().map(|u| u + 0.75).collect();
    let vs: Vec<f64> = synth::spread(600.0, 5).iter().map(|v| v + 900.0).collect();
    let lines = synth::coordinate_lines(&us, &vs);
    check(&Helicoid { c }, &lines, 1.0, 20.0, true, 0.01);
    check(&Helicoid { c }, &lines, 1.0, 20.0, false, 0.02);
}

#[test]
fn offset_changes_length_to_first_order_in_kg() {
    // A 5 mm tangential offset on a helix of the helicoid: the length changes by
    // about −dy·∫kg ds (docs/geometry.md: first order in kg).
    let c = 1000.0;
    let lines = synth::coordinate_lines(&[0.0, 1.5], &[800.0, 1200.0]);
    let raw = synth::network(
        "h",
        &Helicoid { c },
        &lines,
        1.0,
        Sampling {
            step_mm: 20.0,
            normals: true,
        },
    );
    let (_net, an) = run(raw);
    let strip = &an.strips[2]; // helix v = 800
    assert!(
        (kg_expected(800.0, c) - strip.frame_at(&an.curves[2], 100.0).kg_per_mm.abs()).abs() < 1e-8
    );
    let smooth = &an.curves[strip.curve];
    let kg = strip.frame_at(smooth, 100.0).kg_per_mm;
    let tg = c / (800.0 * 800.0 + c * c);
    let got = strip.offset_stations(smooth, 5.0, 0.0, &[strip.length_mm], 25.0)[0];
    let expected = strip.length_mm * ((1.0 - 5.0 * kg).powi(2) + (5.0 * tg).powi(2)).sqrt();
    assert!((got - expected).abs() < 0.01, "{got} vs {expected}");
    // kg = 800/(800² + c²) ≈ 1/3.3 m over 1.92 m: about 4.7 mm shorter or longer (the side of y).
    assert!(
        ((strip.length_mm - got).abs() - 4.7).abs() < 0.1,
        "{}",
        strip.length_mm - got
    );
}

fn kg_expected(v: f64, c: f64) -> f64 {
    v / (v * v + c * c)
}
