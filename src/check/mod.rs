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

use crate::analysis::lines::{LamellaLine, NetworkLines, StripLines};
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
    /// One per A and B strip, in strip order (edges are never checked).
    pub strips: Vec<StripCheck>,
}

impl CheckReport {
    /// Every strip passes (utilisation ≤ 1 on every lamella).
    pub fn passes(&self) -> bool {
        self.strips.iter().all(StripCheck::passes)
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
