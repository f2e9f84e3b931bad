//! Tracing curves on a surface: an adaptive Runge–Kutta integrator
//! (Dormand–Prince 5(4) with error control in mm) in the parameter domain,
//! along a direction field of unit 3D speed, so the integration variable is
//! arc length. Fields: the two asymptotic directions, the two principal
//! directions (the façade web), and the level sets of clip planes (edges).
//!
//! A trace keeps its direction consistent (each evaluation is turned to agree
//! with the step's start) and stops cleanly at the clip boundary and the
//! domain edge (located by bisection to `boundary_tolerance_mm`), at flat
//! points (K → 0, where the asymptotic net is singular), on closing a loop,
//! or at a length limit.

use crate::geom::surface::{curvature_of, to_parameter, Surface, SurfaceJet};
use glam::{DVec2, DVec3};

/// A direction field on the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Field {
    /// The asymptotic direction turned from the first principal direction d1 towards d2 (family A).
    AsymptoticA,
    /// The other asymptotic direction, turned from d1 away from d2 (family B).
    AsymptoticB,
    /// The principal direction of the larger curvature k1.
    PrincipalMax,
    /// The principal direction of the smaller curvature k2.
    PrincipalMin,
    /// The level set of the plane (point, unit normal): tangent n_surface × n_plane.
    Level {
        /// A point of the plane, in the surface's frame (world for [`Placed`](crate::design::surface::Placed)), mm.
        point_mm: DVec3,
        /// Unit normal of the plane, in the same frame.
        normal: DVec3,
    },
}

impl Field {
    /// The field's unit 3D direction at uv (sign not yet chosen), or the reason it has none.
    pub fn direction(
        &self,
        surface: &dyn Surface,
        uv: DVec2,
        flat_k_per_mm2: f64,
    ) -> Result<DVec3, Stop> {
        self.direction_at(&surface.derivatives(uv), flat_k_per_mm2)
    }

    /// The field's unit 3D direction at a jet (derivatives only are used).
    pub fn direction_at(&self, j: &SurfaceJet, flat_k_per_mm2: f64) -> Result<DVec3, Stop> {
        let c = curvature_of(j);
        match self {
            Field::AsymptoticA | Field::AsymptoticB => {
                let (a, b) = c.asymptotic(flat_k_per_mm2).ok_or(Stop::FlatPoint)?;
                Ok(if *self == Field::AsymptoticA { a } else { b })
            }
            Field::PrincipalMax | Field::PrincipalMin => {
                if (c.k1 - c.k2).abs() < flat_k_per_mm2.sqrt() {
                    return Err(Stop::FlatPoint);
                }
                Ok(if *self == Field::PrincipalMax {
                    c.d1
                } else {
                    c.d2
                })
            }
            Field::Level { normal, .. } => c
                .normal
                .cross(*normal)
                .try_normalize()
                .ok_or(Stop::FlatPoint),
        }
    }
}

/// Why a trace ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// Left the clip region (the end lies on its boundary).
    Clip,
    /// Reached the edge of the surface's parameter domain.
    DomainEdge,
    /// The field vanishes (K → 0 for asymptotic directions, umbilic for principal ones).
    FlatPoint,
    /// Came back to its start: the curve is a closed loop.
    ClosedLoop,
    /// Reached the length limit.
    MaxLength,
    /// The step size fell below its minimum (a singularity of the field).
    StepTooSmall,
    /// Took more steps than [`TraceOptions::max_steps`] (steps held tiny
    /// near a singularity).
    StepLimit,
}

impl Stop {
    /// A few words for messages and the design report (`clip`, `domain edge`, …).
    pub fn as_str(self) -> &'static str {
        match self {
            Stop::Clip => "clip",
            Stop::DomainEdge => "domain edge",
            Stop::FlatPoint => "flat point",
            Stop::ClosedLoop => "closed loop",
            Stop::MaxLength => "length limit",
            Stop::StepTooSmall => "step too small",
            Stop::StepLimit => "step limit",
        }
    }
}

/// Tolerances and limits of a trace.
#[derive(Debug, Clone, Copy)]
pub struct TraceOptions {
    /// Local error per step, mm.
    pub tolerance_mm: f64,
    /// Largest step (and so sample spacing), mm.
    pub max_step_mm: f64,
    /// Smallest step, mm: a step that must shrink below it ends the trace with [`Stop::StepTooSmall`].
    pub min_step_mm: f64,
    /// How precisely a boundary crossing is located, mm.
    pub boundary_tolerance_mm: f64,
    /// Length limit of one direction of a trace, mm.
    pub max_length_mm: f64,
    /// |K| below this (1/mm²) is a flat point.
    pub flat_k_per_mm2: f64,
    /// Most integrator steps (accepted and rejected) of one direction of a trace.
    pub max_steps: usize,
}

impl Default for TraceOptions {
    fn default() -> Self {
        TraceOptions {
            tolerance_mm: 1e-7,
            max_step_mm: 25.0,
            min_step_mm: 1e-6,
            boundary_tolerance_mm: 1e-7,
            max_length_mm: 200_000.0,
            flat_k_per_mm2: 1e-14,
            max_steps: 4_000_000,
        }
    }
}

/// A region of space (and of the parameter domain) that traces stay inside.
pub trait Region: Sync {
    /// Whether the surface point `p_mm` (the surface's frame, mm) at parameters
    /// `uv` is inside; a point on the boundary may count either way.
    fn contains(&self, uv: DVec2, p_mm: DVec3) -> bool;
}

/// Everything.
pub struct Everywhere;
impl Region for Everywhere {
    fn contains(&self, _uv: DVec2, _p: DVec3) -> bool {
        true
    }
}

/// A traced curve, both ways from its seed.
///
/// Guarantees (from [`trace_through`]): at least two samples, at equal arc
/// length, at most `max_step_mm` apart (⌈length/step⌉ pieces, more where the
/// curve turns more than [`MAX_SAMPLE_TURN_RAD`] between chords); each
/// within the integrator's `tolerance_mm` (local, per step) of the field's
/// integral curve; an end that stopped at the clip lies on its boundary to
/// `boundary_tolerance_mm`; points from the exact surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Traced {
    /// Parameters (u, v) of every sample.
    pub uv: Vec<DVec2>,
    /// The surface point of every sample, in the surface's frame (world for a
    /// [`Placed`](crate::design::surface::Placed) surface), mm.
    pub points_world_mm: Vec<DVec3>,
    /// Arc length from the first point, mm.
    pub stations_mm: Vec<f64>,
    /// Why the backward trace (towards the first sample) ended.
    pub stop_start: Stop,
    /// Why the forward trace (towards the last sample) ended.
    pub stop_end: Stop,
}

impl Traced {
    /// The same curve run the other way.
    pub fn reversed(mut self) -> Traced {
        let length = self.length_mm();
        self.uv.reverse();
        self.points_world_mm.reverse();
        self.stations_mm.reverse();
        for s in &mut self.stations_mm {
            *s = length - *s;
        }
        std::mem::swap(&mut self.stop_start, &mut self.stop_end);
        self
    }

    /// Arc length, mm (the last station).
    pub fn length_mm(&self) -> f64 {
        *self.stations_mm.last().unwrap_or(&0.0)
    }
    /// The parameter point at a station, interpolated linearly between the
    /// two steps around it (steps are at most `max_step_mm` apart; used to
    /// seed new curves, whose own traces are exact).
    pub fn uv_at(&self, station_mm: f64) -> DVec2 {
        let k = self
            .stations_mm
            .partition_point(|&s| s <= station_mm)
            .clamp(1, self.uv.len() - 1);
        let (s0, s1) = (self.stations_mm[k - 1], self.stations_mm[k]);
        let t = if s1 > s0 {
            ((station_mm - s0) / (s1 - s0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.uv[k - 1].lerp(self.uv[k], t)
    }
}

struct Tracer<'a> {
    surface: &'a dyn Surface,
    field: Field,
    region: &'a dyn Region,
    opts: TraceOptions,
}

// Dormand–Prince 5(4) tableau (the field is autonomous: no c column needed).
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
const B5: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
const B4: [f64; 7] = [
    5179.0 / 57600.0,
    0.0,
    7571.0 / 16695.0,
    393.0 / 640.0,
    -92097.0 / 339200.0,
    187.0 / 2100.0,
    1.0 / 40.0,
];

impl Tracer<'_> {
    /// d(uv)/ds and the 3D direction, turned to agree with `reference`.
    fn velocity(&self, uv: DVec2, reference: DVec3) -> Result<(DVec2, DVec3), Stop> {
        if !self.surface.in_domain(uv) {
            return Err(Stop::DomainEdge);
        }
        let j = self.surface.derivatives(uv);
        let d = self.field.direction_at(&j, self.opts.flat_k_per_mm2)?;
        let d = if d.dot(reference) < 0.0 { -d } else { d };
        Ok((to_parameter(&j, d), d))
    }

    /// One Dormand–Prince step of length h: (5th-order result, error in mm, end direction).
    fn step(&self, uv: DVec2, dir: DVec3, h: f64) -> Result<(DVec2, f64, DVec3), Stop> {
        let mut k = [DVec2::ZERO; 7];
        let mut reference = dir;
        for i in 0..7 {
            let mut y = uv;
            for (j, kj) in k.iter().enumerate().take(i) {
                y += *kj * (h * A[i][j]);
            }
            let (v, d) = self.velocity(y, reference)?;
            reference = d;
            k[i] = v;
        }
        let mut y5 = uv;
        let mut e = DVec2::ZERO;
        for i in 0..7 {
            y5 += k[i] * (h * B5[i]);
            e += k[i] * (h * (B5[i] - B4[i]));
        }
        if !self.surface.in_domain(y5) {
            return Err(Stop::DomainEdge);
        }
        let j = self.surface.derivatives(uv);
        let err_mm = (j.pu * e.x + j.pv * e.y).length();
        Ok((y5, err_mm, reference))
    }

    /// Trace from `uv0` in the direction closest to `dir0`.
    fn run(&self, uv0: DVec2, dir0: DVec3) -> Run {
        let (out, stations, dirs, stop) = self.run_inner(uv0, dir0);
        Run {
            uv: out,
            stations_mm: stations,
            dirs,
            stop,
        }
    }

    /// The samples, their stations, the field direction at the start of
    /// every segment (one fewer than samples) and why the trace stopped.
    fn run_inner(&self, uv0: DVec2, dir0: DVec3) -> (Vec<DVec2>, Vec<f64>, Vec<DVec3>, Stop) {
        let mut uv = uv0;
        let mut dir = dir0;
        let mut s = 0.0;
        let mut out = vec![uv0];
        let mut stations = vec![0.0];
        let mut dirs: Vec<DVec3> = Vec::new();
        let mut h = self.opts.max_step_mm.min(1.0);
        let p0 = self.surface.point(uv0);
        for _ in 0..self.opts.max_steps {
            if s >= self.opts.max_length_mm {
                return (out, stations, dirs, Stop::MaxLength);
            }
            h = h
                .min(self.opts.max_step_mm)
                .min(self.opts.max_length_mm - s);
            match self.step(uv, dir, h) {
                Ok((next, err, d_end)) => {
                    if err > self.opts.tolerance_mm && h > self.opts.min_step_mm {
                        h = (h * (0.9 * (self.opts.tolerance_mm / err).powf(0.2)).clamp(0.1, 0.9))
                            .max(self.opts.min_step_mm);
                        continue;
                    }
                    let p = self.surface.point(next);
                    if !self.region.contains(next, p) {
                        // Bisect the step length for the boundary.
                        let (b_uv, b_h) =
                            self.bisect(uv, dir, 0.0, h, |q, p| self.region.contains(q, p));
                        if b_h > 0.0 {
                            out.push(b_uv);
                            stations.push(s + b_h);
                            dirs.push(dir);
                        }
                        return (out, stations, dirs, Stop::Clip);
                    }
                    s += h;
                    // Closed loop: back near the start after going some way.
                    if s > 4.0 * self.opts.max_step_mm
                        && p.distance(p0) < 0.5 * h.min(self.opts.max_step_mm)
                    {
                        out.push(uv0);
                        stations.push(s - h + self.surface.point(uv).distance(p0));
                        dirs.push(dir);
                        return (out, stations, dirs, Stop::ClosedLoop);
                    }
                    out.push(next);
                    stations.push(s);
                    dirs.push(dir);
                    uv = next;
                    dir = d_end;
                    let grow = if err > 0.0 {
                        (0.9 * (self.opts.tolerance_mm / err).powf(0.2)).clamp(1.0, 5.0)
                    } else {
                        5.0
                    };
                    h *= grow;
                }
                Err(stop @ (Stop::DomainEdge | Stop::FlatPoint)) => {
                    if h > self.opts.boundary_tolerance_mm {
                        // Approach the edge / flat point by bisection.
                        let (b_uv, b_h) = self.bisect(uv, dir, 0.0, h, |q, _| {
                            self.surface.in_domain(q)
                                && self
                                    .field
                                    .direction(self.surface, q, self.opts.flat_k_per_mm2)
                                    .is_ok()
                        });
                        if b_h > self.opts.boundary_tolerance_mm {
                            out.push(b_uv);
                            stations.push(s + b_h);
                            dirs.push(dir);
                        }
                    }
                    return (out, stations, dirs, stop);
                }
                Err(other) => return (out, stations, dirs, other),
            }
            if h < self.opts.min_step_mm {
                return (out, stations, dirs, Stop::StepTooSmall);
            }
        }
        (out, stations, dirs, Stop::StepLimit)
    }

    /// Largest step length in [lo, hi] whose end satisfies `ok`, by bisection;
    /// returns that end and the length.
    fn bisect(
        &self,
        uv: DVec2,
        dir: DVec3,
        mut lo: f64,
        mut hi: f64,
        ok: impl Fn(DVec2, DVec3) -> bool,
    ) -> (DVec2, f64) {
        let mut best = (uv, 0.0);
        // Halving from at most max_step_mm to the tolerance takes < 64 rounds.
        for _ in 0..64 {
            if hi - lo <= self.opts.boundary_tolerance_mm {
                break;
            }
            let mid = 0.5 * (lo + hi);
            match self.step(uv, dir, mid) {
                Ok((q, _, _)) if ok(q, self.surface.point(q)) => {
                    best = (q, mid);
                    lo = mid;
                }
                _ => hi = mid,
            }
        }
        best
    }
}

/// One direction of a trace: every accepted step, with the field direction
/// at the start of each segment, so any station in between can be
/// integrated to (dense output by a fresh step from the segment's start).
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// Parameters (u, v) at the start and after every accepted step.
    pub uv: Vec<DVec2>,
    /// Arc length of every step from the start, mm (ascending, 0 first).
    pub stations_mm: Vec<f64>,
    /// Direction (3D, unit) at the start of segment k (`uv[k]` → `uv[k + 1]`).
    pub dirs: Vec<DVec3>,
    /// Why this direction ended.
    pub stop: Stop,
}

impl Run {
    /// Arc length of this direction, mm (the last station).
    pub fn length_mm(&self) -> f64 {
        *self.stations_mm.last().unwrap_or(&0.0)
    }

    /// The parameters at a station: one Dormand–Prince step from the start
    /// of the segment holding it (no longer than the step the trace
    /// accepted there, so within its tolerance). The ends are exact.
    pub fn uv_at(&self, surface: &dyn Surface, field: Field, opts: TraceOptions, s: f64) -> DVec2 {
        let n = self.uv.len();
        if n < 2 || s <= 0.0 {
            return self.uv[0];
        }
        if s >= self.length_mm() {
            return self.uv[n - 1];
        }
        let k = (self.stations_mm.partition_point(|&x| x <= s) - 1).min(n - 2);
        let delta = s - self.stations_mm[k];
        if delta <= 0.0 {
            return self.uv[k];
        }
        let tracer = Tracer {
            surface,
            field,
            region: &Everywhere,
            opts,
        };
        match tracer.step(self.uv[k], self.dirs[k], delta) {
            Ok((q, _, _)) => q,
            Err(_) => {
                let (s0, s1) = (self.stations_mm[k], self.stations_mm[k + 1]);
                self.uv[k].lerp(self.uv[k + 1], (delta / (s1 - s0)).clamp(0.0, 1.0))
            }
        }
    }
}

/// Largest turn between consecutive chords of a resampled curve, rad: a
/// quintic through samples this close keeps its tangents to ~0.001°, so
/// crossings near tight bends (flat vertices of Schwarz D) hold 90° ± 0.01°.
pub const MAX_SAMPLE_TURN_RAD: f64 = 0.05;
/// Finest spacing the refinement goes to, mm.
const MIN_SAMPLE_STEP_MM: f64 = 0.05;

/// If the curve sampled in `n` equal pieces of `length_mm` turns more than
/// [`MAX_SAMPLE_TURN_RAD`] between consecutive chords somewhere (a tight
/// bend), the number of equal pieces that would not; None if it does not.
pub fn finer_pieces(points_mm: &[DVec3], n: usize, length_mm: f64) -> Option<usize> {
    let turn = points_mm
        .windows(3)
        .map(|w| (w[1] - w[0]).angle_between(w[2] - w[1]))
        .filter(|a| a.is_finite())
        .fold(0.0, f64::max);
    if turn <= MAX_SAMPLE_TURN_RAD {
        return None;
    }
    let cap = pieces(length_mm, MIN_SAMPLE_STEP_MM);
    let finer = ((n as f64 * turn / MAX_SAMPLE_TURN_RAD * 1.1).ceil() as usize).min(cap);
    (finer > n).then_some(finer)
}

/// How many equal pieces of at most `step_mm` make up `length_mm` (≥ 1).
pub fn pieces(length_mm: f64, step_mm: f64) -> usize {
    let n = (length_mm / step_mm * (1.0 - 1e-12)).ceil();
    if n.is_finite() && n >= 1.0 {
        n as usize
    } else {
        1
    }
}

/// Trace one way from `uv0`, in the direction of `field` closest to `dir0`:
/// the parameters and stations of every accepted step, and why it stopped.
pub fn trace_from(
    surface: &dyn Surface,
    field: Field,
    uv0: DVec2,
    dir0: DVec3,
    region: &dyn Region,
    opts: TraceOptions,
) -> Run {
    Tracer {
        surface,
        field,
        region,
        opts,
    }
    .run(uv0, dir0)
}

/// Trace the curve of `field` through `seed` in both directions, and sample
/// it uniformly: n = ⌈length / max_step_mm⌉ equal pieces of arc length (more
/// where the curve turns more than [`MAX_SAMPLE_TURN_RAD`] between samples), each
/// point integrated to from the trace's own steps (so within its
/// tolerance), the two ends exactly where the trace stopped.
pub fn trace_through(
    surface: &dyn Surface,
    field: Field,
    seed: DVec2,
    region: &dyn Region,
    opts: TraceOptions,
) -> Result<Traced, Stop> {
    let tracer = Tracer {
        surface,
        field,
        region,
        opts,
    };
    if !surface.in_domain(seed) {
        return Err(Stop::DomainEdge);
    }
    let d0 = field.direction(surface, seed, opts.flat_k_per_mm2)?;
    let fwd = tracer.run(seed, d0);
    let bwd = if fwd.stop == Stop::ClosedLoop {
        Run {
            uv: vec![seed],
            stations_mm: vec![0.0],
            dirs: Vec::new(),
            stop: Stop::ClosedLoop,
        }
    } else {
        tracer.run(seed, -d0)
    };
    let back = bwd.length_mm();
    let total = back + fwd.length_mm();
    let sample = |n: usize| {
        let mut uv = Vec::with_capacity(n + 1);
        let mut stations_mm = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let s = total * i as f64 / n as f64;
            let q = if i == 0 {
                *bwd.uv.last().unwrap_or(&seed)
            } else if i == n {
                *fwd.uv.last().unwrap_or(&seed)
            } else if s < back {
                bwd.uv_at(surface, field, opts, back - s)
            } else {
                fwd.uv_at(surface, field, opts, s - back)
            };
            uv.push(q);
            stations_mm.push(s);
        }
        let points_mm: Vec<DVec3> = uv.iter().map(|&q| surface.point(q)).collect();
        (uv, stations_mm, points_mm)
    };
    let mut n = pieces(total, opts.max_step_mm);
    let (mut uv, mut stations_mm, mut points_mm) = sample(n);
    while let Some(finer) = finer_pieces(&points_mm, n, total) {
        n = finer;
        (uv, stations_mm, points_mm) = sample(n);
    }
    Ok(Traced {
        uv,
        points_world_mm: points_mm,
        stations_mm,
        stop_start: bwd.stop,
        stop_end: fwd.stop,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::surface::{Enneper, Placed};
    use glam::DMat3;
    use std::sync::Arc;

    fn enneper_mm(scale: f64) -> Placed {
        Placed {
            surface: Arc::new(Enneper),
            scale_mm: scale,
            rotation: DMat3::IDENTITY,
            translation_mm: DVec3::ZERO,
        }
    }

    /// A region in the parameter plane: |u ± v| ≤ half.
    struct Diamond(f64);
    impl Region for Diamond {
        fn contains(&self, q: DVec2, _p: DVec3) -> bool {
            (q.x + q.y).abs() <= self.0 && (q.x - q.y).abs() <= self.0
        }
    }

    #[test]
    fn enneper_asymptotic_line_follows_the_closed_form() {
        let s = enneper_mm(4400.0);
        let seed = DVec2::new(0.12, 0.05);
        for field in [Field::AsymptoticA, Field::AsymptoticB] {
            let t = trace_through(&s, field, seed, &Diamond(0.6), TraceOptions::default())
                .expect("traced");
            // One of u + v, u − v stays constant along an asymptotic line.
            let (p0, q0) = (seed.x + seed.y, seed.x - seed.y);
            let along_p = t.uv.iter().all(|q| ((q.x + q.y) - p0).abs() < 1e-3);
            let mut worst: f64 = 0.0;
            for q in &t.uv {
                let exact = if along_p {
                    let qq = q.x - q.y;
                    DVec2::new((p0 + qq) / 2.0, (p0 - qq) / 2.0)
                } else {
                    let pp = q.x + q.y;
                    DVec2::new((pp + q0) / 2.0, (pp - q0) / 2.0)
                };
                worst = worst.max(s.point(*q).distance(s.point(exact)));
            }
            eprintln!(
                "{field:?}: {worst:e} mm over {} mm, {} steps",
                t.length_mm(),
                t.uv.len()
            );
            assert!(
                worst < 0.01,
                "{field:?}: {worst} mm from the closed form over {} mm",
                t.length_mm()
            );
            assert!(t.length_mm() > 3000.0);
            assert_eq!((t.stop_start, t.stop_end), (Stop::Clip, Stop::Clip));
        }
    }

    #[test]
    fn a_reversed_trace_runs_back_over_the_same_points() {
        let t = Traced {
            uv: vec![
                DVec2::new(0.0, 0.0),
                DVec2::new(1.0, 0.0),
                DVec2::new(1.0, 2.0),
            ],
            points_world_mm: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 2.0, 0.0)],
            stations_mm: vec![0.0, 1.0, 3.0],
            stop_start: Stop::Clip,
            stop_end: Stop::DomainEdge,
        };
        let r = t.clone().reversed();
        assert_eq!(r.stations_mm, vec![0.0, 2.0, 3.0]);
        assert_eq!(r.points_world_mm[0], DVec3::new(1.0, 2.0, 0.0));
        assert_eq!(r.uv[2], DVec2::ZERO);
        assert_eq!((r.stop_start, r.stop_end), (Stop::DomainEdge, Stop::Clip));
        assert_eq!(r.uv_at(0.5), DVec2::new(1.0, 1.5));
        assert_eq!(r.reversed(), t);
    }
}
