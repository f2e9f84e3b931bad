//! Networks made from closed forms, for lamella's integration tests and
//! benchmarks: analytic surfaces and families of parameter lines on them
//! that are known to be asymptotic (Enneper and catenoid: u ± v = const;
//! helicoid and hyperbolic paraboloid: the coordinate lines).
//!
//! A dev-dependency of lamella, built against the same lamella library as
//! the binary, so neither `cargo test` nor `cargo bench` builds lamella
//! with other features.

#![warn(missing_docs)]

use glam::DVec2;
use lamella::network::{Family, RawCurve, RawNetwork, Unit};

/// The analytic surfaces, from the library.
pub use lamella::design::surface::{Catenoid, Enneper, Helicoid, Hypar, Surface as ParamSurface};

/// A straight line in the parameter plane: uv(t) = start + dir·t, t ∈ [t0, t1].
#[derive(Debug, Clone, PartialEq)]
pub struct ParamLine {
    /// Curve id in the network.
    pub id: String,
    /// Curve family.
    pub family: Family,
    /// uv at t = 0.
    pub start: DVec2,
    /// uv per unit of t.
    pub dir: DVec2,
    /// First t.
    pub t0: f64,
    /// Last t.
    pub t1: f64,
}

impl ParamLine {
    /// The parameter point at t.
    pub fn uv(&self, t: f64) -> DVec2 {
        self.start + self.dir * t
    }
}

/// How to sample the lines.
#[derive(Debug, Clone, Copy)]
pub struct Sampling {
    /// Target spacing of samples along the curve, mm.
    pub step_mm: f64,
    /// Write surface normals with the points.
    pub normals: bool,
}

/// Sample one parameter line of a surface scaled by `scale_mm` (mm per
/// surface unit), at equal parameter steps close to `step_mm` apart.
pub fn sample_line(
    surface: &dyn ParamSurface,
    line: &ParamLine,
    scale_mm: f64,
    sampling: Sampling,
) -> RawCurve {
    // Estimate the length from a fine polygon to choose the sample count.
    let fine = 256;
    let mut len = 0.0;
    let mut prev = surface.point(line.uv(line.t0));
    for i in 1..=fine {
        let t = line.t0 + (line.t1 - line.t0) * i as f64 / fine as f64;
        let p = surface.point(line.uv(t));
        len += p.distance(prev);
        prev = p;
    }
    let n = ((len * scale_mm / sampling.step_mm).ceil() as usize).max(1) + 1;
    let ts: Vec<f64> = (0..n)
        .map(|i| line.t0 + (line.t1 - line.t0) * i as f64 / (n - 1) as f64)
        .collect();
    RawCurve {
        id: line.id.clone(),
        family: line.family,
        points: ts
            .iter()
            .map(|&t| surface.point(line.uv(t)) * scale_mm)
            .collect(),
        normals: sampling
            .normals
            .then(|| ts.iter().map(|&t| surface.normal(line.uv(t))).collect()),
    }
}

/// A network of parameter lines on a surface, in mm.
pub fn network(
    name: &str,
    surface: &dyn ParamSurface,
    lines: &[ParamLine],
    scale_mm: f64,
    sampling: Sampling,
) -> RawNetwork {
    RawNetwork {
        name: name.to_string(),
        unit: Unit::Mm,
        tolerance: None,
        precision: None,
        curves: lines
            .iter()
            .map(|l| sample_line(surface, l, scale_mm, sampling))
            .collect(),
    }
}

/// Evenly spaced values from −half to +half (n ≥ 2).
pub fn spread(half: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| -half + 2.0 * half * i as f64 / (n - 1) as f64)
        .collect()
}

/// Asymptotic lines u + v = p (family A, along q = u − v) and u − v = q
/// (family B) on Enneper or the catenoid, for p, q ∈ [−half, half]: curve A_i
/// is p = p_i with q running over [−half, half], and vice versa.
pub fn diagonal_lines(half: f64, n: usize, center: DVec2) -> Vec<ParamLine> {
    let values = spread(half, n);
    let mut lines = Vec::with_capacity(2 * n);
    for (i, &p) in values.iter().enumerate() {
        // u = (p + q)/2, v = (p − q)/2 with q = t.
        lines.push(ParamLine {
            id: format!("A{i:02}"),
            family: Family::A,
            start: center + DVec2::new(p / 2.0, p / 2.0),
            dir: DVec2::new(0.5, -0.5),
            t0: -half,
            t1: half,
        });
    }
    for (j, &q) in values.iter().enumerate() {
        lines.push(ParamLine {
            id: format!("B{j:02}"),
            family: Family::B,
            start: center + DVec2::new(q / 2.0, -q / 2.0),
            dir: DVec2::new(0.5, 0.5),
            t0: -half,
            t1: half,
        });
    }
    lines
}

/// Coordinate lines: A_i is u = u_i (running over v), B_j is v = v_j.
pub fn coordinate_lines(us: &[f64], vs: &[f64]) -> Vec<ParamLine> {
    let (v0, v1) = (vs[0], vs[vs.len() - 1]);
    let (u0, u1) = (us[0], us[us.len() - 1]);
    let mut lines = Vec::with_capacity(us.len() + vs.len());
    for (i, &u) in us.iter().enumerate() {
        lines.push(ParamLine {
            id: format!("A{i:02}"),
            family: Family::A,
            start: DVec2::new(u, 0.0),
            dir: DVec2::new(0.0, 1.0),
            t0: v0,
            t1: v1,
        });
    }
    for (j, &v) in vs.iter().enumerate() {
        lines.push(ParamLine {
            id: format!("B{j:02}"),
            family: Family::B,
            start: DVec2::new(0.0, v),
            dir: DVec2::new(1.0, 0.0),
            t0: u0,
            t1: u1,
        });
    }
    lines
}

/// Arc length along the Enneper asymptotic line p = const from q0 to q1, in
/// surface units: ds = λ |dq| / √2, λ = 1 + (p² + q²)/2.
pub fn enneper_arc_length(p: f64, q0: f64, q1: f64) -> f64 {
    let f = |q: f64| (1.0 + p * p / 2.0) * q + q * q * q / 6.0;
    (f(q1) - f(q0)).abs() / std::f64::consts::SQRT_2
}

/// The 4 m steel-prototype Enneper network: 13 × 13 asymptotic lines over
/// |u ± v| ≤ 0.5, 4400 mm per unit: a 4.0 m diagonal span, 2.2 m rise,
/// cells of about 260 mm.
pub fn enneper_4m(sampling: Sampling) -> RawNetwork {
    let lines = diagonal_lines(ENNEPER_4M_HALF, 13, DVec2::ZERO);
    network(
        "enneper-4m",
        &Enneper,
        &lines,
        ENNEPER_4M_SCALE_MM,
        sampling,
    )
}

/// Parameter half-range of [`enneper_4m`].
pub const ENNEPER_4M_HALF: f64 = 0.5;
/// mm per surface unit of [`enneper_4m`].
pub const ENNEPER_4M_SCALE_MM: f64 = 4400.0;

/// The benchmarks' fabrication network: n × n Enneper curves with cells
/// like the 4 m prototype's (~260 mm between nodes, so the steel profile's
/// washers, blocks and splice plates fit), sampled every 100 mm; at
/// n = 400 a 100 m grid with curves up to ~150 m long.
pub fn enneper_prototype_grid(n: usize) -> RawNetwork {
    enneper_grid(n, ENNEPER_4M_SCALE_MM * (n - 1) as f64 / 12.0, 100.0)
}

/// A square n × n Enneper network for benchmarks, `step_mm` sampling.
pub fn enneper_grid(n: usize, scale_mm: f64, step_mm: f64) -> RawNetwork {
    let lines = diagonal_lines(0.5, n, DVec2::ZERO);
    network(
        &format!("enneper-{n}x{n}"),
        &Enneper,
        &lines,
        scale_mm,
        Sampling {
            step_mm,
            normals: false,
        },
    )
}
