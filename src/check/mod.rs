//! Elastic check: will every strip bend and twist into place?
//!
//! Input: the [`Analysis`] (kg, kn, tg at every sample of every strip) and a
//! [`Profile`]. Output: a [`CheckReport`]: per lamella of every strip, the
//! residual stresses of bending the flat strip into place (docs/geometry.md,
//! "Elastic check"), computed from geodesic curvature and torsion alone:
//!
//! ```text
//! bending about the weak axis   σb = E·|kg|·t/2
//! twisting (St. Venant)         τ  = G·|tg|·t
//! trapeze effect of twist       σw = E·tg²·h²/12
//! combined                      σv = sqrt((σb + σw)² + 3τ²)  ≤  f_d
//! ```
//!
//! Each lamella of a doubled strip lies on its own offset line (dy, dz); the
//! frame turns by the same angle on it over a longer or shorter length, so
//! its curvatures are the curve's divided by the stretch ds'/ds.
//!
//! A flat straight strip cannot take normal curvature kn (bending about its
//! strong axis): wherever the network is not exactly asymptotic, the
//! lamella's line unrolled into its own plane bows off its chord. That
//! sagitta ([`sagitta_mm`]) is compared with the profile's
//! `check.max_sagitta_mm`; a lamella over it fails the check too
//! (docs/geometry.md, "Sagitta").

use crate::analysis::lines::{LamellaLine, NetworkLines, StripLines};
use crate::analysis::strip::Curvatures;
use crate::analysis::Analysis;
use crate::profile::{LamellaOffset, Profile};
use rayon::prelude::*;

/// Which stress term is largest at the governing point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Governs {
    /// No stress at all (a straight, untwisted lamella).
    Nothing,
    /// Bending about the weak axis, σb = E·|kg|·t/2.
    Bending,
    /// St. Venant shear, √3·τ with τ = G·|tg|·t.
    Torsion,
    /// The trapeze effect of twist, σw = E·tg²·h²/12.
    Trapeze,
}

impl Governs {
    /// The name plan.json and the CLI use: `nothing`, `bending`, `torsion` or `trapeze`.
    pub fn as_str(self) -> &'static str {
        match self {
            Governs::Nothing => "nothing",
            Governs::Bending => "bending",
            Governs::Torsion => "torsion",
            Governs::Trapeze => "trapeze",
        }
    }
}

/// Stresses at one point of one lamella.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stresses {
    /// σb = E·|kg|·t/2, MPa.
    pub bending_stress_mpa: f64,
    /// τ = G·|tg|·t, MPa.
    pub torsion_shear_mpa: f64,
    /// σw = E·tg²·h²/12, MPa.
    pub trapeze_stress_mpa: f64,
    /// σv = √((σb + σw)² + 3τ²), MPa (von Mises).
    pub combined_stress_mpa: f64,
}

impl Stresses {
    /// The stresses of a lamella with curvature kg and twist tg (per mm).
    pub fn of(profile: &Profile, kg_per_mm: f64, tg_per_mm: f64) -> Stresses {
        let (e, g) = (profile.youngs_modulus_mpa(), profile.shear_modulus_mpa());
        let (t, h) = (profile.thickness_mm(), profile.height_mm());
        let sb = e * kg_per_mm.abs() * t / 2.0;
        let tau = g * tg_per_mm.abs() * t;
        let sw = e * tg_per_mm * tg_per_mm * h * h / 12.0;
        Stresses {
            bending_stress_mpa: sb,
            torsion_shear_mpa: tau,
            trapeze_stress_mpa: sw,
            combined_stress_mpa: ((sb + sw).powi(2) + 3.0 * tau * tau).sqrt(),
        }
    }

    /// The largest of σb, √3·τ and σw (ties: torsion, then bending); `Nothing`
    /// when σv is zero.
    pub fn governs(&self) -> Governs {
        let b = self.bending_stress_mpa;
        let t = 3f64.sqrt() * self.torsion_shear_mpa;
        let w = self.trapeze_stress_mpa;
        if self.combined_stress_mpa == 0.0 {
            Governs::Nothing
        } else if t >= b && t >= w {
            Governs::Torsion
        } else if b >= w {
            Governs::Bending
        } else {
            Governs::Trapeze
        }
    }
}

/// The check of one lamella.
#[derive(Debug, Clone, PartialEq)]
pub struct LamellaCheck {
    /// The lamella on its own line: number, offsets, length, node stations.
    pub line: LamellaLine,
    /// σv / f_d at the worst sample (≥ 0; infinite when the geometry gives no
    /// finite stress).
    pub utilization: f64,
    /// Where it governs, on the lamella's own line (what the workshop measures).
    pub governing_station_mm: f64,
    /// The same point as a station of the strip's curve.
    pub governing_curve_station_mm: f64,
    /// The stresses at the governing sample.
    pub stresses: Stresses,
    /// Which stress term is largest at the governing sample.
    pub governs: Governs,
    /// Smallest bending radius of this lamella; None when straight.
    pub min_bending_radius_mm: Option<f64>,
    /// Largest |tg| of this lamella on its own line, °/m.
    pub max_twist_deg_per_m: f64,
    /// How far the lamella's line, unrolled into its own plane, bows off
    /// its chord under the normal curvature kn, mm ([`sagitta_mm`]).
    pub sagitta_mm: f64,
}

/// The check of one strip: each lamella, and the worst.
#[derive(Debug, Clone, PartialEq)]
pub struct StripCheck {
    /// Index of the strip in `Analysis::strips` (and of its curve in the network).
    pub strip: usize,
    /// The curve's id.
    pub id: String,
    /// One per lamella of the profile (1 on −y, 2 on +y), in lamella order.
    pub lamellas: Vec<LamellaCheck>,
    /// Index into `lamellas` of the highest utilisation.
    pub worst: usize,
}

impl StripCheck {
    /// The lamella with the highest utilisation (the first of equals).
    pub fn worst(&self) -> &LamellaCheck {
        &self.lamellas[self.worst]
    }
    /// Every lamella's utilisation is at most 1.
    pub fn passes(&self) -> bool {
        self.worst().utilization <= 1.0
    }
    /// The lamella whose unrolled line bows most (the first of equals).
    pub fn most_bowed(&self) -> &LamellaCheck {
        let mut best = &self.lamellas[0];
        for l in &self.lamellas[1..] {
            if l.sagitta_mm.total_cmp(&best.sagitta_mm).is_gt() {
                best = l;
            }
        }
        best
    }
    /// The largest sagitta of its lamellas, mm.
    pub fn sagitta_mm(&self) -> f64 {
        self.most_bowed().sagitta_mm
    }
}

/// The whole network's check.
///
/// Guarantees: one [`StripCheck`] per A and B strip in strip order (edges
/// are never checked), one [`LamellaCheck`] per lamella of the profile;
/// utilisation = σv/f_d at the worst sample; the governing station is on
/// the lamella's own line.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    /// f_d, the design strength the stresses are compared with, MPa.
    pub design_strength_mpa: f64,
    /// The profile's limits in pure bending and in pure twist.
    pub limit_bending_radius_mm: f64,
    /// Largest twist in pure torsion, °/m (with `limit_bending_radius_mm`, mm).
    pub limit_twist_deg_per_m: f64,
    /// Largest sagitta of a lamella's unrolled line, mm (the profile's
    /// `check.max_sagitta_mm`).
    pub limit_sagitta_mm: f64,
    /// One per A and B strip, in strip order (edges are never checked).
    pub strips: Vec<StripCheck>,
}

impl CheckReport {
    /// Every strip passes: utilisation ≤ 1 and sagitta ≤ the limit on
    /// every lamella.
    pub fn passes(&self) -> bool {
        self.strips.iter().all(StripCheck::passes) && self.bowed() == 0
    }
    /// Number of strips with a lamella whose sagitta is above the limit.
    pub fn bowed(&self) -> usize {
        self.strips
            .iter()
            .filter(|s| !self.straight_enough(s))
            .count()
    }
    /// Every lamella of `strip` bows at most `limit_sagitta_mm` (a
    /// non-finite sagitta fails).
    pub fn straight_enough(&self, strip: &StripCheck) -> bool {
        strip.sagitta_mm() <= self.limit_sagitta_mm
    }
    /// The strip with the largest sagitta (the first of equals); None without strips.
    pub fn most_bowed(&self) -> Option<&StripCheck> {
        let mut best: Option<&StripCheck> = None;
        for s in &self.strips {
            if best.is_none_or(|b| s.sagitta_mm().total_cmp(&b.sagitta_mm()).is_gt()) {
                best = Some(s);
            }
        }
        best
    }
    /// Number of strips with a lamella above utilisation 1.
    pub fn overstressed(&self) -> usize {
        self.strips.iter().filter(|s| !s.passes()).count()
    }
    /// Strip indices by utilisation, highest first (ties by id).
    pub fn ranking(&self) -> Vec<usize> {
        let mut idx: Vec<usize> = (0..self.strips.len()).collect();
        idx.sort_by(|&a, &b| {
            let (sa, sb) = (&self.strips[a], &self.strips[b]);
            sb.worst()
                .utilization
                .total_cmp(&sa.worst().utilization)
                .then_with(|| sa.id.cmp(&sb.id))
        });
        idx
    }
    /// Highest utilisation over all strips (0 without strips).
    pub fn max_utilization(&self) -> f64 {
        self.strips
            .iter()
            .map(|s| s.worst().utilization)
            .fold(0.0, f64::max)
    }
}

/// Stretch ds'/ds of an offset line (docs/geometry.md).
fn stretch(dy: f64, dz: f64, kg: f64, kn: f64, tg: f64) -> f64 {
    let a = 1.0 - dy * kg - dz * kn;
    (a * a + (dz * tg).powi(2) + (dy * tg).powi(2)).sqrt()
}

/// How far a lamella's line, unrolled into its own plane, bows off its
/// chord, mm: the sagitta that the normal curvature kn leaves over the
/// strip (docs/geometry.md, "Sagitta").
///
/// The line's tangent turns in the lamella's plane by dθ = kn ds (on an
/// offset line kn/(ds'/ds) over ds', the same angle), so the unrolled line
/// is the plane curve of curvature kn over the lamella's own arc length.
/// Between consecutive samples kn is taken at its mean, so each step is an
/// arc. The sagitta is the largest distance of the line from the chord
/// from its first point to its last (from the first point when they
/// meet): at the steps' ends, and inside a step where its tangent runs
/// along the chord. Exact for a constant kn: on a circle of radius R over
/// the chord c, R − √(R² − c²/4). NaN when the curvatures are not finite.
pub fn sagitta_mm(samples: &[Curvatures], off: LamellaOffset) -> f64 {
    // Each step: its start (x, y), the tangent's angle there, the angle it
    // turns through and its length on the lamella's line.
    let mut steps: Vec<([f64; 2], f64, f64, f64)> = Vec::with_capacity(samples.len());
    let (mut at, mut angle) = ([0.0f64, 0.0f64], 0.0f64);
    let stretch_of =
        |c: &Curvatures| stretch(off.dy_mm, off.dz_mm, c.kg_per_mm, c.kn_per_mm, c.tg_per_mm);
    for w in samples.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let ds = b.station_mm - a.station_mm;
        let length = 0.5 * (stretch_of(a) + stretch_of(b)) * ds;
        let turn = 0.5 * (a.kn_per_mm + b.kn_per_mm) * ds;
        steps.push((at, angle, turn, length));
        at = arc_point(at, angle, turn, length);
        angle += turn;
    }
    let span = (at[0] * at[0] + at[1] * at[1]).sqrt();
    if !span.is_finite() {
        return f64::NAN;
    }
    // Distance from the chord (from the first point when the ends meet).
    let (ux, uy) = if span > 1e-9 {
        (at[0] / span, at[1] / span)
    } else {
        (1.0, 0.0)
    };
    let off_chord = |p: [f64; 2]| {
        if span > 1e-9 {
            (p[0] * uy - p[1] * ux).abs()
        } else {
            (p[0] * p[0] + p[1] * p[1]).sqrt()
        }
    };
    let chord_angle = uy.atan2(ux);
    let mut most = off_chord(at);
    for &(start, angle, turn, length) in &steps {
        most = most.max(off_chord(start));
        // Within the step, farthest where the tangent runs along the chord
        // (angle ≡ chord_angle mod π), if it does there.
        if turn.abs() > 0.0 && span > 1e-9 {
            let n = ((angle + 0.5 * turn - chord_angle) / std::f64::consts::PI).round();
            let t = (chord_angle + n * std::f64::consts::PI - angle) / turn;
            if (0.0..=1.0).contains(&t) {
                most = most.max(off_chord(arc_point(start, angle, t * turn, t * length)));
            }
        }
    }
    most
}

/// The end of an arc of `length` from `start`, leaving at `angle` and
/// turning through `turn`: its chord, of length·sin(turn/2)/(turn/2), runs
/// at the mean angle.
fn arc_point(start: [f64; 2], angle: f64, turn: f64, length: f64) -> [f64; 2] {
    let half = 0.5 * turn;
    let chord = if half.abs() < 1e-9 {
        length
    } else {
        length * half.sin() / half
    };
    let mid = angle + half;
    [start[0] + chord * mid.cos(), start[1] + chord * mid.sin()]
}

/// Worst point of one lamella over the strip's samples:
/// (utilisation, sample index, stresses, max |kg_l|, max |tg_l|).
fn scan(
    an: &Analysis,
    strip: usize,
    off: LamellaOffset,
    profile: &Profile,
) -> (f64, usize, Stresses, f64, f64) {
    let fd = profile.design_strength_mpa();
    let mut worst = (f64::NEG_INFINITY, 0, Stresses::of(profile, 0.0, 0.0));
    let (mut kmax, mut tmax) = (0.0f64, 0.0f64);
    for (i, c) in an.strips[strip].samples.iter().enumerate() {
        let k = stretch(off.dy_mm, off.dz_mm, c.kg_per_mm, c.kn_per_mm, c.tg_per_mm);
        let (kg, tg) = (c.kg_per_mm / k, c.tg_per_mm / k);
        kmax = kmax.max(kg.abs());
        tmax = tmax.max(tg.abs());
        let s = Stresses::of(profile, kg, tg);
        // A non-finite stress (broken geometry) counts as failing, never as 0.
        let u = if s.combined_stress_mpa.is_finite() {
            s.combined_stress_mpa / fd
        } else {
            f64::INFINITY
        };
        if u > worst.0 {
            worst = (u, i, s);
        }
    }
    (worst.0.max(0.0), worst.1, worst.2, kmax, tmax)
}

/// The largest utilisation of any lamella of an A or B strip (the strips
/// [`check`] checks; fast: no station bookkeeping).
pub fn max_utilization(an: &Analysis, profile: &Profile) -> f64 {
    an.lamella_strips()
        .flat_map(|s| {
            profile
                .lamella_offsets(s.family)
                .into_iter()
                .map(move |o| (s.curve, o))
        })
        .map(|(i, o)| scan(an, i, o, profile).0)
        .fold(0.0, f64::max)
}

/// Check every lamella of every A and B strip. Edge strips are not checked
/// here: they lie tangential to the surface and are cut as curved bands,
/// so kg does not bend them about their weak axis.
///
/// With `keep_lines`, every lamella line the check integrated is returned
/// too, for fabrication to carry its own stations onto
/// ([`crate::fabricate::fabricate`]) instead of integrating the lines
/// again; otherwise each strip's are dropped once it is checked and the
/// [`NetworkLines`] are empty. The report is the same either way.
pub fn check(an: &Analysis, profile: &Profile, keep_lines: bool) -> (CheckReport, NetworkLines) {
    let (report, lines) = check_strips(an, profile, keep_lines);
    (report, NetworkLines::new(lines.into_iter().flatten()))
}

/// [`check`]; with `keep_lines`, each strip's [`StripLines`] too.
fn check_strips(
    an: &Analysis,
    profile: &Profile,
    keep_lines: bool,
) -> (CheckReport, Vec<Option<StripLines>>) {
    let checked: Vec<&crate::analysis::strip::StripGeometry> = an.lamella_strips().collect();
    let (strips, lines): (Vec<StripCheck>, Vec<Option<StripLines>>) = checked
        .par_iter()
        .map(|s| {
            let smooth = &an.curves[s.curve];
            let offsets = profile.lamella_offsets(s.family);
            let scans: Vec<_> = offsets
                .iter()
                .map(|&off| scan(an, s.curve, off, profile))
                .collect();
            // Every lamella's line and governing station from one pass of
            // frames along the strip.
            let curve_stations: Vec<f64> =
                scans.iter().map(|sc| s.samples[sc.1].station_mm).collect();
            let mut strip_lines = StripLines::new(s, smooth, &offsets);
            let on_lines = strip_lines.stations(s, smooth, &curve_stations);
            let lines = if keep_lines {
                strip_lines.lines.clone()
            } else {
                std::mem::take(&mut strip_lines.lines)
            };
            let lamellas: Vec<LamellaCheck> = scans
                .into_iter()
                .zip(lines.into_iter().zip(on_lines))
                .enumerate()
                .map(
                    |(k, ((u, _, stresses, kmax, tmax), (line, on_line)))| LamellaCheck {
                        line,
                        utilization: u,
                        governing_station_mm: on_line[k],
                        governing_curve_station_mm: curve_stations[k],
                        governs: stresses.governs(),
                        stresses,
                        min_bending_radius_mm: (kmax > s.straight_curvature_per_mm())
                            .then(|| 1.0 / kmax),
                        max_twist_deg_per_m: tmax.to_degrees() * 1000.0,
                        sagitta_mm: sagitta_mm(&s.samples, offsets[k]),
                    },
                )
                .collect();
            let worst = (0..lamellas.len())
                .max_by(|&a, &b| {
                    lamellas[a]
                        .utilization
                        .total_cmp(&lamellas[b].utilization)
                        .then(b.cmp(&a))
                })
                .unwrap_or(0);
            (
                StripCheck {
                    strip: s.curve,
                    id: s.id.clone(),
                    lamellas,
                    worst,
                },
                keep_lines.then_some(strip_lines),
            )
        })
        .unzip();
    (
        CheckReport {
            design_strength_mpa: profile.design_strength_mpa(),
            limit_bending_radius_mm: profile.min_bending_radius_mm(),
            limit_twist_deg_per_m: profile.max_twist_per_mm().to_degrees() * 1000.0,
            limit_sagitta_mm: profile.max_sagitta_mm(),
            strips,
        },
        lines,
    )
}

/// What a designer can change so that every strip passes.
#[derive(Debug, Clone, PartialEq)]
pub struct Suggestion {
    /// Largest lamella thickness (at the profile's height) at which every strip
    /// passes; None when no thickness does (the trapeze term alone fails).
    pub max_thickness_mm: Option<f64>,
    /// Largest height (at the profile's thickness) at which every strip
    /// passes, when the height matters (trapeze term) and some height works.
    pub max_height_mm: Option<f64>,
    /// When no thickness works at the profile's height: the largest height at
    /// which some thickness works, and that thickness.
    pub height_and_thickness_mm: Option<(f64, f64)>,
}

/// Resolution of the searches, mm.
pub const SUGGEST_RESOLUTION_MM: f64 = 1e-4;

/// Largest x in [lo, hi] with passes(x), assuming passes is monotone
/// (true below some threshold); None if even lo fails.
fn largest_passing(lo: f64, hi: f64, passes: impl Fn(f64) -> bool) -> Option<f64> {
    let lo_probe = lo;
    if !passes(lo_probe) {
        return None;
    }
    if passes(hi) {
        return Some(hi);
    }
    let (mut lo, mut hi) = (lo_probe, hi);
    while hi - lo > SUGGEST_RESOLUTION_MM * 0.5 {
        let mid = 0.5 * (lo + hi);
        if passes(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    // Round down to the resolution so the suggested value itself passes.
    let rounded = (lo / SUGGEST_RESOLUTION_MM).floor() * SUGGEST_RESOLUTION_MM;
    Some(if passes(rounded) { rounded } else { lo })
}

/// Search the section for a passing network (utilisation ≤ 1 everywhere).
pub fn suggest(an: &Analysis, profile: &Profile) -> Suggestion {
    let (t0, h0) = (profile.thickness_mm(), profile.height_mm());
    let ok = |t: f64, h: f64| max_utilization(an, &profile.with_section(t, h)) <= 1.0;
    // Thickness: utilisation grows with t (σb, τ ∝ t); search up to 4 t0
    // so a passing design also shows its headroom.
    let max_thickness_mm = largest_passing(SUGGEST_RESOLUTION_MM, 4.0 * t0, |t| ok(t, h0));
    // Height matters through the trapeze term only; σw grows with h².
    // Only A and B strips, as `check`: edges are never checked as lamellas.
    let trapeze_matters = an.lamella_strips().any(|s| s.max_abs_tg_per_mm > 0.0);
    let max_height_mm = if trapeze_matters {
        largest_passing(2.0 * t0, 4.0 * h0, |h| ok(t0, h))
    } else {
        None
    };
    let height_and_thickness_mm = if max_thickness_mm.is_none() {
        // σw alone must stay below f_d: find the largest height where a thin
        // lamella passes, then the largest thickness there.
        largest_passing(2.0 * SUGGEST_RESOLUTION_MM, h0, |h| {
            ok(SUGGEST_RESOLUTION_MM, h)
        })
        .and_then(|h| {
            let h = 0.95 * h; // leave room for a real thickness
            largest_passing(SUGGEST_RESOLUTION_MM, (4.0 * t0).min(0.5 * h), |t| ok(t, h))
                .map(|t| (h, t))
        })
    } else {
        None
    };
    Suggestion {
        max_thickness_mm,
        max_height_mm,
        height_and_thickness_mm,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::{analyze, AnalysisOptions};
    use crate::network::{Family, Network, RawCurve, RawNetwork, Unit};
    use glam::DVec3;
    use std::path::Path;

    /// The shipped steel profile as one lamella per strip: E = 210 000 MPa,
    /// G = 81 000 MPa, t = 1.5 mm, h = 50 mm, f_d = 1.0 × 355 / 1.0 = 355 MPa.
    fn steel_single() -> Profile {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles/steel-1.5.yaml");
        let mut p = crate::formats::read::profile_file::load(&path).expect("steel profile");
        p.section.per_strip = 1;
        p.section.gap_mm = 0.0;
        p.shear_block = None;
        p
    }

    fn close(got: f64, want: f64, rel: f64, what: &str) {
        assert!(
            (got - want).abs() <= rel * want.abs(),
            "{what}: {got} against {want}"
        );
    }

    #[test]
    fn stresses_of_the_steel_section_by_hand() {
        let p = steel_single();
        assert_eq!(p.design_strength_mpa(), 355.0);
        // kg = 1/1000 mm (a 1 m radius), tg = 0.001 rad/mm (57.3°/m):
        // σb = E·kg·t/2    = 210 000 × 0.001 × 1.5 / 2  = 157.5 MPa
        // τ  = G·tg·t      = 81 000 × 0.001 × 1.5       = 121.5 MPa
        // σw = E·tg²·h²/12 = 210 000 × 1e-6 × 2500 / 12 = 43.75 MPa
        // σv = √((157.5 + 43.75)² + 3 × 121.5²) = √(40 501.5625 + 44 286.75)
        //    = √84 788.3125 = 291.18433 MPa
        let s = Stresses::of(&p, 1e-3, -1e-3);
        close(s.bending_stress_mpa, 157.5, 1e-12, "σb");
        close(s.torsion_shear_mpa, 121.5, 1e-12, "τ");
        close(s.trapeze_stress_mpa, 43.75, 1e-12, "σw");
        close(s.combined_stress_mpa, 291.18433, 1e-6, "σv");
        // √3 τ = 210.44 beats σb = 157.5 and σw = 43.75.
        assert_eq!(s.governs(), Governs::Torsion);
        // Bending alone: σv = σb; twist alone at 1e-4 rad/mm: τ = 12.15 MPa,
        // σw = 0.4375 MPa, √3 τ = 21.04 governs.
        assert_eq!(Stresses::of(&p, 1e-3, 0.0).governs(), Governs::Bending);
        assert_eq!(Stresses::of(&p, 0.0, 1e-4).governs(), Governs::Torsion);
        // A tall section twisted hard: h = 400 mm, tg = 0.01 rad/mm gives
        // σw = 210 000 × 1e-4 × 160 000 / 12 = 280 000 MPa against
        // √3 τ = √3 × 81 000 × 0.01 × 1.5 = 2104.4 MPa.
        let tall = p.with_section(1.5, 400.0);
        let s = Stresses::of(&tall, 0.0, 1e-2);
        close(s.trapeze_stress_mpa, 280_000.0, 1e-12, "σw");
        assert_eq!(s.governs(), Governs::Trapeze);
        assert_eq!(Stresses::of(&p, 0.0, 0.0).governs(), Governs::Nothing);
    }

    #[test]
    fn the_stretch_of_an_offset_line_by_hand() {
        // On an arc of radius 1000 mm (kg = 0.001) the line 5.75 mm towards
        // the centre (dy = +5.75 along y, which points to the centre) has
        // radius 994.25 mm: ds'/ds = 994.25 / 1000.
        close(stretch(5.75, 0.0, 1e-3, 0.0, 0.0), 0.99425, 1e-12, "inner");
        close(stretch(-5.75, 0.0, 1e-3, 0.0, 0.0), 1.00575, 1e-12, "outer");
        // On a straight twisted strip (tg = 0.001) a line 3 mm off the
        // centre is a helix of radius 3 mm and pitch 1/tg: ds'/ds =
        // √(1 + (3 × 0.001)²) = √1.000009.
        close(
            stretch(3.0, 0.0, 0.0, 0.0, 1e-3),
            1.000009f64.sqrt(),
            1e-12,
            "helix",
        );
    }

    fn raw(id: &str, family: Family, points: Vec<DVec3>, normals: Vec<DVec3>) -> RawCurve {
        RawCurve {
            id: id.into(),
            family,
            points,
            normals: Some(normals),
        }
    }

    /// A0: an arc of radius 1000 mm in z = 0 over 60°, normals +z (kg =
    /// 1/1000, kn = tg = 0). B0: a straight radial line at 30° from radius
    /// 900 to 1100 mm (crossing A0 at right angles), its normal turning
    /// about it at `twist` rad/mm (kg = kn = 0, |tg| = twist).
    fn arc_and_twisted_line(twist: f64) -> Network {
        let arc: Vec<DVec3> = (0..=60)
            .map(|k| {
                let a = f64::from(k).to_radians();
                DVec3::new(1000.0 * a.cos(), 1000.0 * a.sin(), 0.0)
            })
            .collect();
        let t = DVec3::new(30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0);
        let w = DVec3::Z.cross(t);
        let s: Vec<f64> = (0..=20).map(|k| 10.0 * f64::from(k)).collect();
        let line = s.iter().map(|&s| t * (900.0 + s)).collect();
        let turning = s
            .iter()
            .map(|&s| DVec3::Z * (twist * s).cos() + w * (twist * s).sin())
            .collect();
        let raw = RawNetwork {
            name: "arc-and-line".into(),
            unit: Unit::Mm,
            tolerance: None,
            precision: None,
            curves: vec![
                raw("A0", Family::A, arc, vec![DVec3::Z; 61]),
                raw("B0", Family::B, line, turning),
            ],
        };
        Network::new(raw, Path::new("test.yaml")).expect("valid network")
    }

    #[test]
    fn a_bent_strip_and_a_twisted_strip_by_hand() {
        let net = arc_and_twisted_line(1e-3);
        let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
        let report = check(&an, &steel_single(), false).0;
        assert_eq!(report.strips.len(), 2);
        // A0: σb = 210 000 × 1.5 / (2 × 1000) = 157.5 MPa, nothing else;
        // utilisation 157.5 / 355 = 0.443662.
        let a = report.strips[0].worst();
        close(a.stresses.bending_stress_mpa, 157.5, 1e-5, "A0 σb");
        assert!(a.stresses.torsion_shear_mpa < 1e-6, "A0 τ");
        close(a.utilization, 0.443662, 1e-5, "A0 utilisation");
        assert_eq!(a.governs, Governs::Bending);
        close(a.min_bending_radius_mm.expect("bent"), 1000.0, 1e-5, "A0 R");
        // B0: τ = 121.5 MPa, σw = 43.75 MPa (above), σv = √(43.75² +
        // 3 × 121.5²) = √46 200.8125 = 214.94374 MPa; utilisation 0.605475;
        // twist 0.001 rad/mm = 57.29578°/m.
        let b = report.strips[1].worst();
        assert!(b.stresses.bending_stress_mpa < 1e-6, "B0 σb");
        close(b.stresses.torsion_shear_mpa, 121.5, 1e-4, "B0 τ");
        close(b.stresses.trapeze_stress_mpa, 43.75, 2e-4, "B0 σw");
        close(b.stresses.combined_stress_mpa, 214.94374, 1e-4, "B0 σv");
        close(b.utilization, 0.605475, 1e-4, "B0 utilisation");
        close(b.max_twist_deg_per_m, 57.29578, 1e-4, "B0 twist");
        assert_eq!(b.governs, Governs::Torsion);
        assert_eq!(b.min_bending_radius_mm, None);
        assert!(report.passes());
        close(max_utilization(&an, &steel_single()), 0.605475, 1e-4, "max");
    }

    /// Samples every `step` mm over `length` mm at constant curvatures.
    fn constant(length: f64, step: f64, kg: f64, kn: f64, tg: f64) -> Vec<Curvatures> {
        let n = (length / step).ceil() as usize;
        (0..=n)
            .map(|i| Curvatures {
                station_mm: length * i as f64 / n as f64,
                kg_per_mm: kg,
                kn_per_mm: kn,
                tg_per_mm: tg,
            })
            .collect()
    }

    #[test]
    fn the_sagitta_of_a_circular_arc_by_hand() {
        // A line of length L = 2000 mm with kn = 1/R, R = 5000 mm, turns
        // through L/R = 0.4 rad: chord c = 2R·sin(0.2) = 1986.6933 mm,
        // sagitta R − √(R² − c²/4) = 5000 − 4900.3330 = 99.6670 mm
        // (≈ L²/(8R) = 100 mm).
        let (r, l) = (5000.0f64, 2000.0f64);
        let c = 2.0 * r * (l / (2.0 * r)).sin();
        let want = r - (r * r - c * c / 4.0).sqrt();
        assert!((want - 99.667).abs() < 1e-3, "{want}");
        let got = sagitta_mm(&constant(l, 50.0, 0.0, 1.0 / r, 0.0), LamellaOffset::CENTRE);
        assert!((got - want).abs() < 0.01, "{got} against {want}");
        // kn of either sign, coarse samples: the same.
        let got = sagitta_mm(
            &constant(l, 400.0, 0.0, -1.0 / r, 0.0),
            LamellaOffset::CENTRE,
        );
        assert!((got - want).abs() < 0.01, "{got} against {want}");
        // A flat strip on its own line: no bow, whatever kg and tg do.
        let flat = sagitta_mm(&constant(l, 50.0, 1e-3, 0.0, 1e-3), LamellaOffset::CENTRE);
        assert!(flat < 1e-9, "{flat}");
        // A lamella offset dz = 25 mm towards the centre lies on radius
        // R − 25 (stretch 1 − dz·kn): the same angle over a shorter line.
        let inner = LamellaOffset {
            number: 2,
            dy_mm: 0.0,
            dz_mm: 25.0,
        };
        let ri = r - 25.0;
        let ci = 2.0 * ri * (l / (2.0 * r)).sin();
        let want = ri - (ri * ri - ci * ci / 4.0).sqrt();
        let got = sagitta_mm(&constant(l, 50.0, 0.0, 1.0 / r, 0.0), inner);
        assert!((got - want).abs() < 0.01, "{got} against {want}");
    }

    /// A0: an arc of radius 1000 mm in z = 0 over 60°, normals pointing
    /// away from its centre (kg = tg = 0, |kn| = 1/1000: bent about its
    /// strong axis). B0: a vertical line through it at 30°, normals the
    /// same radial direction (straight, kg = kn = tg = 0).
    fn arc_standing_on_its_normal() -> Network {
        let radial = |a: f64| DVec3::new(a.cos(), a.sin(), 0.0);
        let arc: Vec<DVec3> = (0..=60)
            .map(|k| radial(f64::from(k).to_radians()) * 1000.0)
            .collect();
        let normals = (0..=60)
            .map(|k| radial(f64::from(k).to_radians()))
            .collect();
        let at = radial(30f64.to_radians());
        let line = (0..=20)
            .map(|k| at * 1000.0 + DVec3::Z * (10.0 * f64::from(k) - 100.0))
            .collect();
        let raw = RawNetwork {
            name: "arc-on-edge".into(),
            unit: Unit::Mm,
            tolerance: None,
            precision: None,
            curves: vec![
                raw("A0", Family::A, arc, normals),
                raw("B0", Family::B, line, vec![at; 21]),
            ],
        };
        Network::new(raw, Path::new("test.yaml")).expect("valid network")
    }

    #[test]
    fn an_arc_bent_about_its_strong_axis_fails_on_its_sagitta() {
        // 60° of R = 1000 mm: half chord R·sin 30° = 500 mm, sagitta
        // 1000 − √(1000² − 500²) = 133.9746 mm; no stress at all.
        let want = 1000.0 - (1000.0f64.powi(2) - 500.0f64.powi(2)).sqrt();
        let net = arc_standing_on_its_normal();
        let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
        let report = check(&an, &steel_single(), false).0;
        let a = &report.strips[0];
        assert!((a.sagitta_mm() - want).abs() < 0.01, "{}", a.sagitta_mm());
        assert!(a.worst().utilization < 1e-6, "{}", a.worst().utilization);
        assert!(report.strips[1].sagitta_mm() < 1e-6);
        assert_eq!(
            report.limit_sagitta_mm,
            crate::profile::DEFAULT_MAX_SAGITTA_MM
        );
        assert_eq!((report.overstressed(), report.bowed()), (0, 1));
        assert!(!report.passes());
        assert_eq!(report.most_bowed().map(|s| s.id.as_str()), Some("A0"));
        // Doubled: both lamellas lie 5.75 mm above and below the arc
        // (y = z × x is vertical), each on a circle of the same radius.
        let mut doubled = steel_single();
        doubled.section.per_strip = 2;
        doubled.section.gap_mm = 10.0;
        doubled.check.max_sagitta_mm = Some(150.0);
        let report = check(&an, &doubled, false).0;
        for l in &report.strips[0].lamellas {
            assert!((l.sagitta_mm - want).abs() < 0.01, "{}", l.sagitta_mm);
        }
        assert!(report.passes(), "within a 150 mm limit");
    }

    #[test]
    fn the_thickest_lamella_that_bends_round_a_metre() {
        // Bending alone (the line untwisted): σb = E·t/(2R) ≤ f_d up to
        // t = 2 × 355 × 1000 / 210 000 = 3.380952 mm; the height does not
        // matter without twist.
        let net = arc_and_twisted_line(0.0);
        let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
        let s = suggest(&an, &steel_single());
        let t = s.max_thickness_mm.expect("a thickness passes");
        assert!((t - 3.380952).abs() < 2.0 * SUGGEST_RESOLUTION_MM, "{t}");
        assert_eq!(s.max_height_mm, None);
        assert_eq!(s.height_and_thickness_mm, None);
    }
}
