//! The surface normal along a curve that has no file normals, as an angle
//! field in a rotation-minimising frame.
//!
//! A curve's tangent x is known to first order from its samples; the surface
//! normal z ⟂ x is then one angle θ(s) about x. Measured in a
//! rotation-minimising frame (u₁, u₂ = x × u₁, x), whose u's do not turn
//! about x, the geodesic torsion is exactly θ′(s) (docs/geometry.md: with
//! y = z × x, z′·y = −θ′), and kn, kg follow from the curvature vector. So
//! the twist needs θ to first order only, and θ is observed:
//!
//! * at every node, from the two crossing tangents (z = tₐ × t_b): first
//!   derivatives only, the most reliable observation there is;
//! * along an asymptotic curve (A, B), from its binormal, whose direction is
//!   the surface normal; its uncertainty is the curvature's error over the
//!   curvature itself (σθ = σκ/κ), so it weighs nothing near inflections and
//!   on straight stretches. σκ is the rounding noise and the interpolant's
//!   own error between samples (about h·|Δd³| over a segment h long): on a
//!   grid's polylines, sampled at their nodes only, the binormal between
//!   nodes a cell apart is an interpolant's guess and the nodes govern,
//!   ends and short boundary strips included.
//!
//! θ(s) is the weighted least-squares cubic B-spline (uniform knots) through
//! these observations with a small third-difference penalty (P-spline) that
//! bridges gaps without bending quadratic trends: between nodes on a straight
//! ruling it is a smooth interpolant of the node angles. Edge curves are not
//! asymptotic: their normal comes from their nodes only.

use crate::geom::curve::{Piece, SmoothCurve};
use glam::DVec3;

/// One observation of the normal's angle.
#[derive(Debug, Clone, Copy)]
struct Observation {
    station_mm: f64,
    theta: f64,
    weight: f64,
}

/// A uniform cubic B-spline θ(s) over [0, length], fitted by penalised
/// least squares.
#[derive(Debug, Clone)]
pub struct AngleSpline {
    step_mm: f64,
    intervals: usize,
    coef: Vec<f64>,
}

/// Uniform cubic B-spline basis values and u-derivatives at local u.
fn basis(u: f64) -> ([f64; 4], [f64; 4]) {
    let v = 1.0 - u;
    (
        [
            v * v * v / 6.0,
            (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0,
            (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0,
            u * u * u / 6.0,
        ],
        [
            -v * v / 2.0,
            (3.0 * u * u - 4.0 * u) / 2.0,
            (-3.0 * u * u + 2.0 * u + 1.0) / 2.0,
            u * u / 2.0,
        ],
    )
}

/// Half-bandwidth of the normal equations (cubic basis, third differences).
const BAND: usize = 3;

impl AngleSpline {
    /// Fit θ(s) on [0, length_mm] with knots about `knot_step_mm` apart to
    /// weighted observations; `smoothing` scales the third-difference penalty
    /// relative to the mean observation weight per interval.
    fn fit(length_mm: f64, knot_step_mm: f64, obs: &[Observation], smoothing: f64) -> AngleSpline {
        let intervals = ((length_mm / knot_step_mm).ceil() as usize).max(1);
        let step_mm = length_mm.max(1e-9) / intervals as f64;
        let n = intervals + 3;
        if obs.is_empty() {
            return AngleSpline {
                step_mm,
                intervals,
                coef: vec![0.0; n],
            };
        }
        // Banded normal matrix: a[i][d] = A(i, i + d).
        let mut a = vec![[0.0f64; BAND + 1]; n];
        let mut rhs = vec![0.0f64; n];
        let mut total_weight = 0.0;
        let locate = |s: f64| {
            let x = (s / step_mm).clamp(0.0, intervals as f64);
            let k = (x.floor() as usize).min(intervals - 1);
            (k, x - k as f64)
        };
        for o in obs {
            let (k, u) = locate(o.station_mm);
            let (b, _) = basis(u);
            for m in 0..4 {
                rhs[k + m] += o.weight * b[m] * o.theta;
                for l in m..4 {
                    a[k + m][l - m] += o.weight * b[m] * b[l];
                }
            }
            total_weight += o.weight;
        }
        let lambda = smoothing * total_weight / intervals as f64;
        // Third differences; with fewer than three distinct stations (whose
        // quadratic would be free) also vanishing second and first ones.
        let mut stations: Vec<f64> = obs.iter().map(|o| o.station_mm).collect();
        stations.sort_by(f64::total_cmp);
        let mut distinct = 0;
        let mut last = f64::NEG_INFINITY;
        for s in stations {
            if (s - last).abs() > 1e-6 {
                distinct += 1;
                last = s;
            }
        }
        let low = if distinct < 3 { lambda * 1e-6 } else { 0.0 };
        let diffs: [(&[f64], f64); 3] = [
            (&[-1.0, 3.0, -3.0, 1.0], lambda),
            (&[1.0, -2.0, 1.0], low),
            (&[-1.0, 1.0], low),
        ];
        for (d, weight) in diffs {
            for j in 0..=n - d.len() {
                for m in 0..d.len() {
                    for l in m..d.len() {
                        a[j + m][l - m] += weight * d[m] * d[l];
                    }
                }
            }
        }
        let coef = solve_banded(a, rhs);
        AngleSpline {
            step_mm,
            intervals,
            coef,
        }
    }

    /// θ and dθ/ds (rad/mm) at a station (clamped to the curve).
    pub fn eval(&self, station_mm: f64) -> (f64, f64) {
        let x = (station_mm / self.step_mm).clamp(0.0, self.intervals as f64);
        let k = (x.floor() as usize).min(self.intervals - 1);
        let (b, db) = basis(x - k as f64);
        let c = &self.coef[k..k + 4];
        let theta = (0..4).map(|m| c[m] * b[m]).sum();
        let dtheta = (0..4).map(|m| c[m] * db[m]).sum::<f64>() / self.step_mm;
        (theta, dtheta)
    }
}

/// Solve the symmetric positive definite banded system (upper band rows
/// a[i][d] = A(i, i + d)) by Cholesky factorisation.
fn solve_banded(mut a: Vec<[f64; BAND + 1]>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    // In place: a becomes the upper factor R with A = RᵀR.
    for i in 0..n {
        for k in i.saturating_sub(BAND)..i {
            let r_ki = a[k][i - k];
            for j in i..(k + BAND + 1).min(n) {
                let r_kj = a[k][j - k];
                a[i][j - i] -= r_ki * r_kj;
            }
        }
        let d = a[i][0].max(1e-300).sqrt();
        for j in i..(i + BAND + 1).min(n) {
            a[i][j - i] /= d;
        }
    }
    // Rᵀ y = b, then R x = y.
    for i in 0..n {
        for k in i.saturating_sub(BAND)..i {
            b[i] -= a[k][i - k] * b[k];
        }
        b[i] /= a[i][0];
    }
    for i in (0..n).rev() {
        for j in i + 1..(i + BAND + 1).min(n) {
            b[i] -= a[i][j - i] * b[j];
        }
        b[i] /= a[i][0];
    }
    b
}

/// Options of the normal field.
#[derive(Debug, Clone, Copy)]
pub struct NormalFieldOptions {
    /// Standard deviation of a node normal's angle, rad.
    pub node_sigma_rad: f64,
    /// Curvature error (1/mm) of an exact interpolant, added to the rounding
    /// noise when weighing binormals.
    pub curvature_floor_per_mm: f64,
    /// Binormals less certain than this (rad) are not used.
    pub max_binormal_sigma_rad: f64,
    /// Largest spacing of the rotation-minimising frame's stations, mm.
    pub max_frame_step_mm: f64,
    /// Penalty weight of the angle spline (relative).
    pub smoothing: f64,
}

impl Default for NormalFieldOptions {
    fn default() -> Self {
        NormalFieldOptions {
            node_sigma_rad: 1e-4,
            curvature_floor_per_mm: 1e-7,
            max_binormal_sigma_rad: 0.3,
            max_frame_step_mm: 50.0,
            smoothing: 1e-4,
        }
    }
}

/// What the angle field was fitted to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FieldSources {
    /// The field was fitted to node normals (the curve has at least one node).
    pub nodes: bool,
    /// The field was fitted to the curve's binormal where its curvature is known.
    pub binormals: bool,
}

/// The normal along a curve: a rotation-minimising frame at stations and
/// the fitted angle θ(s) of the normal in it.
#[derive(Debug, Clone)]
pub struct NormalField {
    stations_mm: Vec<f64>,
    points_mm: Vec<DVec3>,
    tangents: Vec<DVec3>,
    /// u₁ of the rotation-minimising frame at each station.
    refs: Vec<DVec3>,
    /// Index of the first station in each segment of the curve (the
    /// sample's own), and last the final station's: segment k's stations
    /// are `segment_first[k]..segment_first[k + 1]`.
    segment_first: Vec<usize>,
    angle: AngleSpline,
    /// What the angle θ(s) was fitted to.
    pub sources: FieldSources,
}

/// One double reflection (Wang, Jüttler, Zheng & Liu 2008): carry the frame
/// vector `r` at (p0, t0) to (p1, t1) without rotation about the tangent.
fn double_reflection(p0: DVec3, t0: DVec3, r: DVec3, p1: DVec3, t1: DVec3) -> DVec3 {
    let v1 = p1 - p0;
    let c1 = v1.length_squared();
    let r1 = if c1 < MIN_REFLECTION_STEP_MM * MIN_REFLECTION_STEP_MM {
        // So close that v1's direction is rounding noise (reflecting in it
        // would turn r about the tangent at random): the frame barely moves,
        // projection is exact to O(|v1|²).
        r
    } else {
        let r_l = r - v1 * (2.0 / c1 * v1.dot(r));
        let t_l = t0 - v1 * (2.0 / c1 * v1.dot(t0));
        let v2 = t1 - t_l;
        let c2 = v2.length_squared();
        if c2 > 1e-300 {
            r_l - v2 * (2.0 / c2 * v2.dot(r_l))
        } else {
            r_l
        }
    };
    (r1 - t1 * r1.dot(t1))
        .try_normalize()
        .unwrap_or_else(|| t1.any_orthonormal_vector())
}

/// Below this distance (mm) a frame is carried by projection, not reflection.
const MIN_REFLECTION_STEP_MM: f64 = 1e-4;

/// A node's normal as the field takes it: its station on the curve, where
/// that lies (segment and local u, as `SmoothCurve::locate_station` gives
/// them), and the unit normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeNormal {
    /// Station on the curve, mm.
    pub station_mm: f64,
    /// Segment of the curve the station lies in.
    pub segment: usize,
    /// Local coordinate of the station in its segment.
    pub u: f64,
    /// Unit normal, world frame.
    pub normal_world: DVec3,
}

/// Position, unit tangent and curvature vector (1/mm) of a piece at local u.
fn point_tangent_curvature(piece: &Piece, u: f64) -> (DVec3, DVec3, DVec3) {
    let j = piece.jet(u);
    let v2 = j.d1.length_squared();
    let x = j.d1 / v2.sqrt();
    (j.value, x, (j.d2 - x * j.d2.dot(x)) / v2)
}

impl NormalField {
    /// Fit the normal field of a curve to its node normals (`nodes`: unit
    /// normals oriented consistently, sorted by station) and, when
    /// `use_binormal`, to its binormals.
    pub fn new(
        smooth: &SmoothCurve,
        nodes: &[NodeNormal],
        use_binormal: bool,
        opts: NormalFieldOptions,
    ) -> NormalField {
        let length = smooth.length_mm();
        // Frame stations: every sample, each segment subdivided evenly in
        // its parameter to the largest step.
        let samples = smooth.sample_stations_mm();
        let n = samples.len();
        let parts_of = |k: usize| {
            ((samples[k + 1] - samples[k]) / opts.max_frame_step_mm)
                .ceil()
                .max(1.0) as usize
        };
        let mut segment_first = Vec::with_capacity(n);
        let mut total = 0;
        for k in 0..n - 1 {
            segment_first.push(total);
            total += parts_of(k);
        }
        segment_first.push(total);
        let count = total + 1;
        let mut stations_mm: Vec<f64> = Vec::with_capacity(count);
        let mut points_mm: Vec<DVec3> = Vec::with_capacity(count);
        let mut tangents: Vec<DVec3> = Vec::with_capacity(count);
        let mut refs: Vec<DVec3> = Vec::with_capacity(count);
        // The binormal observations, their angle raw (the branch is chosen
        // once the node field is known), in station order; and whether the
        // first one's binormal points down.
        let mut binormals: Vec<Observation> =
            Vec::with_capacity(if use_binormal { count } else { 0 });
        let mut first_points_down: Option<bool> = None;
        let mut push = |piece: &Piece, u: f64, station: f64, near: usize, interp: f64| {
            let (p, x, kvec) = point_tangent_curvature(piece, u);
            // The rotation-minimising frame, carried from the last station.
            let r = match (points_mm.last(), tangents.last(), refs.last()) {
                (Some(&p0), Some(&t0), Some(&r0)) => double_reflection(p0, t0, r0, p, x),
                _ => x.any_orthonormal_vector(),
            };
            stations_mm.push(station);
            points_mm.push(p);
            tangents.push(x);
            refs.push(r);
            if !use_binormal {
                return;
            }
            let kappa = kvec.length();
            let sigma_kappa = smooth
                .curvature_noise_per_mm(near)
                .hypot(opts.curvature_floor_per_mm)
                .hypot(interp);
            let sigma = sigma_kappa / kappa.max(1e-300);
            if sigma > opts.max_binormal_sigma_rad {
                return;
            }
            let b = x.cross(kvec / kappa);
            first_points_down.get_or_insert(b.z < 0.0);
            binormals.push(Observation {
                station_mm: station,
                theta: b.dot(x.cross(r)).atan2(b.dot(r)),
                weight: 1.0 / (sigma * sigma),
            });
        };
        for (k, &sample_mm) in samples[..n - 1].iter().enumerate() {
            let piece = smooth.piece(k);
            let interp = interpolation_error_per_mm(&piece, samples[k + 1] - sample_mm);
            let parts = parts_of(k);
            for p in 0..parts {
                let u = p as f64 / parts as f64;
                let station = if p == 0 {
                    sample_mm
                } else {
                    smooth.station_in(&piece, k, u)
                };
                push(
                    &piece,
                    u,
                    station,
                    if 2 * p < parts { k } else { k + 1 },
                    interp,
                );
            }
        }
        let last = smooth.piece(n - 2);
        let interp = interpolation_error_per_mm(&last, length - samples[n - 2]);
        push(&last, 1.0, length, n - 1, interp);
        let mut field = NormalField {
            stations_mm,
            points_mm,
            tangents,
            refs,
            segment_first,
            angle: AngleSpline {
                step_mm: length.max(1e-9),
                intervals: 1,
                coef: vec![0.0; 4],
            },
            sources: FieldSources {
                nodes: !nodes.is_empty(),
                binormals: false,
            },
        };
        let knot_step = knot_step_mm(smooth);

        // Node angles, unwrapped along the curve (normals oriented alike).
        let node_weight = 1.0 / (opts.node_sigma_rad * opts.node_sigma_rad);
        let mut obs: Vec<Observation> = Vec::with_capacity(nodes.len() + binormals.len());
        for nn in nodes {
            let (s, z) = (nn.station_mm, nn.normal_world);
            debug_assert_eq!(smooth.locate_station(s), (nn.segment, nn.u));
            let (p, x, _) = point_tangent_curvature(&smooth.piece(nn.segment), nn.u);
            let mut theta = field.angle_of(nn.segment, s, p, x, z);
            if let Some(prev) = obs.last() {
                theta = unwrap_near(theta, prev.theta, std::f64::consts::TAU);
            }
            obs.push(Observation {
                station_mm: s,
                theta,
                weight: node_weight,
            });
        }
        let from_nodes = AngleSpline::fit(length, knot_step, &obs, opts.smoothing);

        // The binormal is the normal up to sign: take the branch nearest the
        // node field, else the previous binormal, else the one whose normal
        // points up.
        let mut previous: Option<f64> = None;
        for o in &mut binormals {
            let raw = o.theta;
            o.theta = if !nodes.is_empty() {
                unwrap_near(raw, from_nodes.eval(o.station_mm).0, std::f64::consts::PI)
            } else if let Some(prev) = previous {
                unwrap_near(raw, prev, std::f64::consts::PI)
            } else if first_points_down == Some(true) {
                raw + std::f64::consts::PI
            } else {
                raw
            };
            previous = Some(o.theta);
        }
        if !binormals.is_empty() {
            field.sources.binormals = true;
            obs.extend(binormals);
        }
        field.angle = if field.sources.binormals {
            AngleSpline::fit(length, knot_step, &obs, opts.smoothing)
        } else {
            from_nodes
        };
        field
    }

    /// Index of the last frame station at or before `station_mm` (the
    /// first if none), found among segment k's stations when the station
    /// lies there, else by a search of them all: the same index either way.
    fn station_index(&self, k: usize, station_mm: f64) -> usize {
        let st = &self.stations_mm;
        if k < self.segment_first.len().saturating_sub(1) {
            let (lo, hi) = (self.segment_first[k], self.segment_first[k + 1]);
            if st[lo] <= station_mm && station_mm < st[hi] {
                return lo + st[lo..hi].partition_point(|&t| t <= station_mm) - 1;
            }
        }
        st.partition_point(|&t| t <= station_mm)
            .saturating_sub(1)
            .min(st.len() - 1)
    }

    /// The rotation-minimising u₁ at station s (in segment k), point p,
    /// unit tangent x.
    fn reference(&self, k: usize, station_mm: f64, p: DVec3, x: DVec3) -> DVec3 {
        let i = self.station_index(k, station_mm);
        double_reflection(self.points_mm[i], self.tangents[i], self.refs[i], p, x)
    }

    /// Angle of the vector z (any, not necessarily ⟂ x) about x in the frame.
    fn angle_of(&self, k: usize, station_mm: f64, p: DVec3, x: DVec3, z: DVec3) -> f64 {
        let u1 = self.reference(k, station_mm, p, x);
        let u2 = x.cross(u1);
        z.dot(u2).atan2(z.dot(u1))
    }

    /// Unit normal and geodesic torsion (rad/mm) at a station with point p
    /// and unit tangent x.
    pub fn at(&self, station_mm: f64, p: DVec3, x: DVec3) -> (DVec3, f64) {
        self.at_in(usize::MAX, station_mm, p, x)
    }

    /// [`NormalField::at`] for a station in segment k of the curve (any k
    /// gives the same result; the right one spares a search).
    pub fn at_in(&self, k: usize, station_mm: f64, p: DVec3, x: DVec3) -> (DVec3, f64) {
        let u1 = self.reference(k, station_mm, p, x);
        let u2 = x.cross(u1);
        let (theta, dtheta) = self.angle.eval(station_mm);
        (u1 * theta.cos() + u2 * theta.sin(), dtheta)
    }
}

/// The interpolant's own curvature error over a segment `h_mm` long, 1/mm:
/// the second derivative of an interpolant is off by about h² times the
/// curve's fourth, which the change of its third over the segment measures
/// (h·|Δd³|). Negligible between dense samples; between samples a cell
/// apart (a grid's polylines) it is what the binormal is worth.
fn interpolation_error_per_mm(piece: &Piece, h_mm: f64) -> f64 {
    h_mm * (piece.jet(1.0).d3 - piece.jet(0.0).d3).length()
}

/// `theta` moved by a multiple of `period` to lie nearest `target`.
fn unwrap_near(theta: f64, target: f64, period: f64) -> f64 {
    theta + ((target - theta) / period).round() * period
}

/// Knot spacing of the angle spline: about twice the smoothing window (the
/// binormals' noise is correlated over it), within 10…400 mm.
fn knot_step_mm(smooth: &SmoothCurve) -> f64 {
    let n = smooth.sample_stations_mm().len();
    let h = smooth.length_mm() / (n - 1).max(1) as f64;
    (2.5 * smooth.smoothing_mm())
        .max(3.0 * h)
        .clamp(10.0, 400.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fit_samples(f: impl Fn(f64) -> f64) -> AngleSpline {
        let obs: Vec<Observation> = (0..=100)
            .map(|i| {
                let s = 10.0 * i as f64;
                Observation {
                    station_mm: s,
                    theta: f(s),
                    weight: 1.0,
                }
            })
            .collect();
        AngleSpline::fit(1000.0, 50.0, &obs, 1e-4)
    }

    #[test]
    fn spline_reproduces_a_quadratic_exactly() {
        // Quadratics are the null space of the third-difference penalty.
        let sp = fit_samples(|s| 0.3 + 1e-3 * s - 2e-6 * s * s);
        for i in 0..=40 {
            let s = 25.0 * i as f64;
            let (t, dt) = sp.eval(s);
            assert!(
                (t - (0.3 + 1e-3 * s - 2e-6 * s * s)).abs() < 1e-10,
                "θ at {s}"
            );
            assert!((dt - (1e-3 - 4e-6 * s)).abs() < 1e-12, "θ' at {s}");
        }
    }

    #[test]
    fn spline_follows_a_cubic_slope_closely() {
        // The penalty leans on the cubic term, lightly: θ' within 0.1 % of
        // its range, ends included.
        let sp = fit_samples(|s| 0.3 + 1e-3 * s - 2e-6 * s * s + 1e-9 * s * s * s);
        for i in 0..=40 {
            let s = 25.0 * i as f64;
            let want = 1e-3 - 4e-6 * s + 3e-9 * s * s;
            let (_, dt) = sp.eval(s);
            assert!((dt - want).abs() < 1e-3 * 1e-3, "θ' at {s}: {dt} vs {want}");
        }
    }

    #[test]
    fn sparse_nodes_are_interpolated_smoothly() {
        // Angles at five points only (a straight ruling's nodes): the fit
        // passes through them and its slope follows a smooth trend.
        let f = |s: f64| (s / 1000.0).atan();
        let obs: Vec<Observation> = (0..5)
            .map(|i| {
                let s = 300.0 * i as f64;
                Observation {
                    station_mm: s,
                    theta: f(s),
                    weight: 1e8,
                }
            })
            .collect();
        let sp = AngleSpline::fit(1200.0, 20.0, &obs, 1e-4);
        for o in &obs {
            assert!((sp.eval(o.station_mm).0 - o.theta).abs() < 1e-6);
        }
        let (_, slope) = sp.eval(600.0);
        let want = 1000.0 / (600.0f64.powi(2) + 1e6);
        assert!((slope - want).abs() < 0.02 * want, "{slope} vs {want}");
    }

    #[test]
    fn frame_is_continuous_at_its_own_stations() {
        // A helix; the field's stations are its samples. Evaluating exactly
        // at a station (where the carried point coincides with the stored
        // one to rounding) must agree with evaluating next to it.
        let pts: Vec<DVec3> = (0..60)
            .map(|i| {
                let a = i as f64 * 0.02;
                DVec3::new(900.0 * a.cos(), 900.0 * a.sin(), 300.0 * a)
            })
            .collect();
        let smooth = SmoothCurve::new(&pts);
        let field = NormalField::new(&smooth, &[], true, NormalFieldOptions::default());
        for &s in &smooth.sample_stations_mm()[1..58] {
            for ds in [0.0, 1e-7, -1e-7] {
                let (k, u) = smooth.locate_station(s + ds);
                let j = smooth.jet_at(k, u);
                let (z, tg) = field.at(s + ds, j.value, j.d1.normalize());
                let (k0, u0) = smooth.locate_station(s + 1e-3);
                let j0 = smooth.jet_at(k0, u0);
                let (z0, tg0) = field.at(s + 1e-3, j0.value, j0.d1.normalize());
                assert!(z.distance(z0) < 1e-5, "normal jumps at {s}{ds:+}");
                assert!((tg - tg0).abs() < 1e-8, "twist jumps at {s}");
            }
        }
    }
}
