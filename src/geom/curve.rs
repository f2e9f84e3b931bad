//! Curves as smooth interpolants of their samples.
//!
//! A [`Hermite5`] passes a C² piecewise quintic through values at strictly
//! increasing parameters, with the first and second derivatives at each
//! sample from a local least-squares polynomial fit. A [`SmoothCurve`] is
//! such an interpolant over the cumulative chord length, with its arc length
//! tabulated by Gauss–Legendre quadrature, so that stations (arc length from
//! the first point) map to points and tangents to far better than the chord
//! polygon.
//!
//! **Precision.** Exported coordinates are rounded (Rhino: 0.001 mm). A
//! curvature from second differences of rounded samples carries an error of
//! order ε/h², its derivative ε/h³: the denser the sampling, the worse. So a
//! curve is smoothed to the precision of its coordinates: each sample's value
//! and derivatives come from a degree-4 least-squares fit over the samples
//! within a half-width W of it (at least 7), with W chosen so that the
//! rounding noise in the curvature stays below
//! [`CURVATURE_NOISE_TARGET_PER_MM`] (W ∝ (ε²·h)^(1/5)), and no wider than a
//! fifth of the smallest bending radius so the fit's own bias stays below
//! ~1e-4 relative. That bound counts bending only: a curve that twists
//! faster than it bends (a catenoid's asymptotic lines, torsion three to
//! five times the curvature) changes its curvature vector on the scale of
//! the twist, and a fit evaluated at the edge of its window (a curve's
//! first and last samples) is a power less exact than a centred one, so a
//! precision declared far above a curve's real noise reads its ends too
//! curved (7 % on a 100 mm mesh of the catenoid, with windows of ±800 mm):
//! a precision says what the coordinates' noise is, not a bound on their
//! error. Exact coordinates (precision below [`EXACT_PRECISION_MM`])
//! keep the 7-sample fit and the interpolant passes through every sample;
//! smoothed ones lie within the rounding of them.

use glam::DVec3;

/// Samples in each local fit window (the least).
const FIT_WINDOW: usize = 7;
/// Coordinates rounded more finely than this (mm) count as exact: no
/// smoothing beyond the 7-sample fit.
pub const EXACT_PRECISION_MM: f64 = 1e-6;
/// The rounding noise the smoothing window allows in the curvature, 1/mm
/// (a bending radius of 10 km).
pub const CURVATURE_NOISE_TARGET_PER_MM: f64 = 1e-7;
/// The smoothing half-width stays below this fraction of the smallest
/// bending radius (the degree-4 fit's bias in the curvature is then of
/// order (W/R)⁴ ≈ 1e-3 relative at most).
const WINDOW_PER_RADIUS: f64 = 0.2;
/// Variance factor of the second derivative from a centred degree-4
/// biweight-kernel least-squares fit of N evenly spaced samples over
/// [−W, W]: var(f'') ≈ C·ε²/(N·W⁴), C ≈ 1180 (from the design's hat matrix).
const D2_VARIANCE_FACTOR: f64 = 1180.0;
/// Degree of the local least-squares fit for sampled curves (smooths rounding).
pub const FIT_DEGREE_SAMPLES: usize = 4;
/// Largest fit degree: with 7 samples, interpolation (for exact data such as
/// node normals, few and far apart).
pub const FIT_DEGREE_EXACT: usize = 6;
const MAX_DEGREE: usize = FIT_DEGREE_EXACT;

/// 8-point Gauss–Legendre nodes and weights on [0, 1].
const GL_NODES: [f64; 8] = [
    0.019855071751231856,
    0.10166676129318664,
    0.2372337950418355,
    0.4082826787521751,
    0.591_717_321_247_825,
    0.7627662049581645,
    0.8983332387068134,
    0.9801449282487681,
];
const GL_WEIGHTS: [f64; 8] = [
    0.05061426814518813,
    0.11119051722668724,
    0.15685332293894363,
    0.181_341_891_689_181,
    0.181_341_891_689_181,
    0.15685332293894363,
    0.11119051722668724,
    0.05061426814518813,
];

/// Value and derivatives (with respect to the parameter) at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet {
    /// The value at the point (same units as the samples).
    pub value: DVec3,
    /// First derivative with respect to the parameter.
    pub d1: DVec3,
    /// Second derivative with respect to the parameter.
    pub d2: DVec3,
    /// Third derivative with respect to the parameter.
    pub d3: DVec3,
}

/// A C² piecewise-quintic Hermite interpolant of vector samples over a
/// strictly increasing parameter.
#[derive(Debug, Clone)]
pub struct Hermite5 {
    t: Vec<f64>,
    p: Vec<DVec3>,
    d1: Vec<DVec3>,
    d2: Vec<DVec3>,
}

impl Hermite5 {
    /// Interpolate `values` at parameters `t` (strictly increasing, at least 2).
    pub fn new(t: Vec<f64>, values: Vec<DVec3>) -> Hermite5 {
        Hermite5::with_fit_degree(t, values, FIT_DEGREE_SAMPLES)
    }

    /// As [`Hermite5::new`], with the degree of the local derivative fit
    /// (4: least squares over 7 samples; 6: interpolation of 7 samples).
    pub fn with_fit_degree(t: Vec<f64>, values: Vec<DVec3>, degree: usize) -> Hermite5 {
        debug_assert!(t.len() >= 2 && t.len() == values.len());
        debug_assert!(
            t.windows(2).all(|w| w[1] > w[0]),
            "parameters must increase"
        );
        let (d1, d2) = fit_derivatives(&t, &values, degree.min(MAX_DEGREE));
        Hermite5 {
            t,
            p: values,
            d1,
            d2,
        }
    }

    /// Values smoothed by local degree-4 fits over ±`half_width_mm` of the
    /// parameter (at least 9 samples each, as curves are smoothed to their
    /// precision), then interpolated with the fitted derivatives.
    pub fn smoothed(t: Vec<f64>, values: &[DVec3], half_width_mm: f64) -> Hermite5 {
        let fit = fit_window(&t, values, half_width_mm, 0.0);
        Hermite5::from_parts(t, fit.values, fit.d1, fit.d2)
    }

    /// A Hermite interpolant with given values and derivatives at `t`.
    pub fn from_parts(t: Vec<f64>, p: Vec<DVec3>, d1: Vec<DVec3>, d2: Vec<DVec3>) -> Hermite5 {
        debug_assert!(t.len() >= 2 && t.len() == p.len() && p.len() == d1.len());
        debug_assert!(d1.len() == d2.len());
        Hermite5 { t, p, d1, d2 }
    }

    /// The parameters of the samples (strictly increasing).
    pub fn knots(&self) -> &[f64] {
        &self.t
    }
    /// The values at the knots.
    pub fn values(&self) -> &[DVec3] {
        &self.p
    }
    /// Number of polynomial pieces (knots − 1, at least 1).
    pub fn segments(&self) -> usize {
        self.t.len() - 1
    }

    /// Segment and local coordinate u ∈ [0, 1] of parameter `t` (clamped).
    pub fn locate(&self, t: f64) -> (usize, f64) {
        let n = self.t.len();
        if t <= self.t[0] {
            return (0, 0.0);
        }
        if t >= self.t[n - 1] {
            return (n - 2, 1.0);
        }
        let k = segment_of(&self.t, t);
        let h = self.t[k + 1] - self.t[k];
        (k, ((t - self.t[k]) / h).clamp(0.0, 1.0))
    }

    /// Power-basis coefficients of segment `k` in u (c(u) = Σ a_j u^j).
    fn coefficients(&self, k: usize) -> [DVec3; 6] {
        let h = self.t[k + 1] - self.t[k];
        let a0 = self.p[k];
        let a1 = self.d1[k] * h;
        let a2 = self.d2[k] * (h * h * 0.5);
        let pp = self.p[k + 1] - a0 - a1 - a2;
        let vv = self.d1[k + 1] * h - a1 - 2.0 * a2;
        let aa = self.d2[k + 1] * (h * h) - 2.0 * a2;
        let a3 = pp * 10.0 - vv * 4.0 + aa * 0.5;
        let a4 = pp * -15.0 + vv * 7.0 - aa;
        let a5 = pp * 6.0 - vv * 3.0 + aa * 0.5;
        [a0, a1, a2, a3, a4, a5]
    }

    /// Segment `k` as one polynomial piece (its coefficients computed once,
    /// for evaluating several points of it).
    pub fn piece(&self, k: usize) -> Piece {
        Piece {
            a: self.coefficients(k),
            h: self.t[k + 1] - self.t[k],
        }
    }

    /// Value and derivatives with respect to `t` in segment `k` at local u.
    pub fn jet_at(&self, k: usize, u: f64) -> Jet {
        self.piece(k).jet(u)
    }

    /// Value and derivatives with respect to `t` at parameter `t` (clamped).
    pub fn jet(&self, t: f64) -> Jet {
        let (k, u) = self.locate(t);
        self.jet_at(k, u)
    }
}

/// One segment of a [`Hermite5`] in power basis over its local u ∈ [0, 1],
/// with its parameter length. Guarantees: every evaluation gives exactly
/// (bit for bit) what the interpolant's per-segment methods give
/// ([`Hermite5::jet_at`], [`SmoothCurve::station_at`]); it only saves
/// recomputing the coefficients when one segment is evaluated many times.
#[derive(Debug, Clone, Copy)]
pub struct Piece {
    a: [DVec3; 6],
    h: f64,
}

impl Piece {
    /// Value and derivatives with respect to the interpolant's parameter at local u.
    #[inline]
    pub fn jet(&self, u: f64) -> Jet {
        let a = &self.a;
        let h = self.h;
        let value = a[0] + u * (a[1] + u * (a[2] + u * (a[3] + u * (a[4] + u * a[5]))));
        let du = a[1] + u * (2.0 * a[2] + u * (3.0 * a[3] + u * (4.0 * a[4] + u * 5.0 * a[5])));
        let ddu = 2.0 * a[2] + u * (6.0 * a[3] + u * (12.0 * a[4] + u * 20.0 * a[5]));
        let dddu = 6.0 * a[3] + u * (24.0 * a[4] + u * 60.0 * a[5]);
        Jet {
            value,
            d1: du / h,
            d2: ddu / (h * h),
            d3: dddu / (h * h * h),
        }
    }

    /// The value at local u.
    #[inline]
    pub fn value(&self, u: f64) -> DVec3 {
        let a = &self.a;
        a[0] + u * (a[1] + u * (a[2] + u * (a[3] + u * (a[4] + u * a[5]))))
    }

    /// |d value / du| (the speed in the local coordinate).
    #[inline]
    fn speed_u(&self, u: f64) -> f64 {
        let a = &self.a;
        (a[1] + u * (2.0 * a[2] + u * (3.0 * a[3] + u * (4.0 * a[4] + u * 5.0 * a[5])))).length()
    }

    /// ∫₀ᵘ |c′(w)| dw by 8-point Gauss–Legendre (the arc length from the
    /// segment's start to local u, for a curve over its chord parameter).
    #[inline]
    fn arc_length_to(&self, u: f64) -> f64 {
        if u <= 0.0 {
            return 0.0;
        }
        let mut sum = 0.0;
        for (x, w) in GL_NODES.iter().zip(GL_WEIGHTS.iter()) {
            sum += w * self.speed_u(x * u);
        }
        sum * u
    }
}

/// Local least-squares estimates of the first and second derivatives at each sample.
pub fn fit_derivatives(t: &[f64], v: &[DVec3], degree: usize) -> (Vec<DVec3>, Vec<DVec3>) {
    let n = t.len();
    let mut d1 = Vec::with_capacity(n);
    let mut d2 = Vec::with_capacity(n);
    if n == 2 {
        let slope = (v[1] - v[0]) / (t[1] - t[0]);
        return (vec![slope; 2], vec![DVec3::ZERO; 2]);
    }
    let m = FIT_WINDOW.min(n);
    let deg = degree.min(m - 1);
    for i in 0..n {
        let lo = i.saturating_sub(m / 2).min(n - m);
        let window = lo..lo + m;
        let half = 0.5 * (t[lo + m - 1] - t[lo]);
        let coef = poly_fit(&t[window.clone()], &v[window], t[i], half, deg);
        d1.push(coef[1] / half);
        d2.push(coef[2] * (2.0 / (half * half)));
    }
    (d1, d2)
}

/// A curve's samples smoothed to the precision of its coordinates: fitted
/// values, first and second derivatives over `t`, and the standard deviation
/// of the rounding noise left in each second derivative (1/mm for a chord
/// parameter).
#[derive(Debug, Clone)]
pub struct SmoothedSamples {
    /// Fitted value at each sample (the sample itself for exact coordinates), mm.
    pub values: Vec<DVec3>,
    /// First derivative over `t` at each sample.
    pub d1: Vec<DVec3>,
    /// Second derivative over `t` at each sample.
    pub d2: Vec<DVec3>,
    /// Standard deviation of the rounding noise in each second derivative (1/mm
    /// for a chord parameter; 0 for exact coordinates).
    pub d2_noise: Vec<f64>,
    /// Half-width of the fit window used, mm (0: the 7-sample fit).
    pub half_width_mm: f64,
}

/// Smooth samples `v` at chord parameters `t` whose coordinates are rounded
/// to `precision_mm` (module docs): degree-4 least-squares fits over the
/// samples within the chosen half-width of each sample.
pub fn smooth_samples(t: &[f64], v: &[DVec3], precision_mm: f64) -> SmoothedSamples {
    let n = t.len();
    if precision_mm < EXACT_PRECISION_MM || n < FIT_WINDOW {
        let (d1, d2) = fit_derivatives(t, v, FIT_DEGREE_SAMPLES);
        return SmoothedSamples {
            values: v.to_vec(),
            d1,
            d2,
            d2_noise: vec![0.0; n],
            half_width_mm: 0.0,
        };
    }
    // Rounding to a grid of `precision` is uniform noise of this deviation.
    let eps = precision_mm / 12f64.sqrt();
    let h = (t[n - 1] - t[0]) / (n - 1) as f64;
    let target = CURVATURE_NOISE_TARGET_PER_MM;
    let w_noise = (0.5 * D2_VARIANCE_FACTOR * eps * eps * h / (target * target)).powf(0.2);
    let first = fit_window(t, v, w_noise, eps);
    // Bias cap: no wider than a fraction of the smallest bending radius
    // (from a robust high percentile of the smoothed curvature).
    let mut kappa: Vec<f64> = (0..n)
        .map(|i| {
            let d1 = first.d1[i];
            d1.cross(first.d2[i]).length() / d1.length().powi(3).max(1e-300)
        })
        .collect();
    // The 95th percentile: the element a full sort would put there.
    let i95 = (n * 95 / 100).min(n - 1);
    let k95 = *kappa.select_nth_unstable_by(i95, f64::total_cmp).1;
    let w_bias = WINDOW_PER_RADIUS / k95.max(1e-12);
    if w_bias < w_noise {
        fit_window(t, v, w_bias, eps)
    } else {
        first
    }
}

/// Root-mean-square distance of samples from their local degree-4 fits
/// over ±`half_window_mm` of chord length (at least 9 samples each), mm:
/// the roughness a curve carries at scales below the window (0 for fewer
/// than 9 samples). A smooth curve whose bending radius is well above the
/// window has none to speak of; a curve traced through a field that kinks
/// from triangle to triangle shows its wiggles here.
pub fn roughness_mm(points_mm: &[DVec3], half_window_mm: f64) -> f64 {
    let n = points_mm.len();
    if n < FIT_WINDOW + 2 {
        return 0.0;
    }
    let mut t = Vec::with_capacity(n);
    let mut acc = 0.0;
    t.push(0.0);
    for w in points_mm.windows(2) {
        acc += w[1].distance(w[0]).max(1e-9);
        t.push(acc);
    }
    let fit = fit_window(&t, points_mm, half_window_mm, 0.0);
    let sum: f64 = fit
        .values
        .iter()
        .zip(points_mm)
        .map(|(a, b)| a.distance_squared(*b))
        .sum();
    (sum / n as f64).sqrt()
}

/// Degree-4 fits over [t_i − w, t_i + w] (shifted inside the curve at its
/// ends, at least 7 samples).
fn fit_window(t: &[f64], v: &[DVec3], w: f64, eps: f64) -> SmoothedSamples {
    let n = t.len();
    let mut out = SmoothedSamples {
        values: Vec::with_capacity(n),
        d1: Vec::with_capacity(n),
        d2: Vec::with_capacity(n),
        d2_noise: Vec::with_capacity(n),
        half_width_mm: w,
    };
    let (t_first, t_last) = (t[0], t[n - 1]);
    for i in 0..n {
        // The window [a, b] of width 2w, moved inside [t_first, t_last].
        let (mut a, mut b) = (t[i] - w, t[i] + w);
        if a < t_first {
            b = (b + (t_first - a)).min(t_last);
            a = t_first;
        }
        if b > t_last {
            a = (a - (b - t_last)).max(t_first);
            b = t_last;
        }
        let mut lo = t.partition_point(|&x| x < a);
        let mut hi = t.partition_point(|&x| x <= b);
        // At least FIT_WINDOW + 2 samples (the outermost weigh almost
        // nothing), taken nearest first.
        while hi - lo < FIT_WINDOW + 2 {
            let left = lo > 0;
            let right = hi < n;
            match (left, right) {
                (true, true) => {
                    if t[i] - t[lo - 1] <= t[hi] - t[i] {
                        lo -= 1
                    } else {
                        hi += 1
                    }
                }
                (true, false) => lo -= 1,
                (false, true) => hi += 1,
                (false, false) => break,
            }
        }
        let half = 0.5 * (t[hi - 1] - t[lo]);
        // The kernel reaches just past the farthest sample of the window, so
        // samples enter and leave a moving window with vanishing weight and
        // neighbouring fits agree (no wiggles between samples).
        let radius = (t[i] - t[lo]).max(t[hi - 1] - t[i]) * (1.0 + 1e-9) + 1e-12;
        let deg = FIT_DEGREE_SAMPLES.min(hi - lo - 3);
        let (coef, var2) = kernel_fit(&t[lo..hi], &v[lo..hi], t[i], half, radius, deg);
        out.values.push(coef[0]);
        out.d1.push(coef[1] / half);
        out.d2.push(coef[2] * (2.0 / (half * half)));
        out.d2_noise
            .push(2.0 * eps * var2.max(0.0).sqrt() / (half * half));
    }
    out
}

/// Weighted least-squares polynomial of degree `deg` through (t, v) in
/// τ = (t − t0)/scale, with biweight kernel weights (1 − (|t − t0|/radius)²)²;
/// returns the coefficients and Σ aⱼ², where c₂ = Σ aⱼ vⱼ (the variance of the
/// τ² coefficient per unit variance of the data).
fn kernel_fit(
    t: &[f64],
    v: &[DVec3],
    t0: f64,
    scale: f64,
    radius: f64,
    deg: usize,
) -> ([DVec3; MAX_DEGREE + 1], f64) {
    let k = deg + 1;
    let weight = |tj: f64| {
        let r = ((tj - t0) / radius).abs().min(1.0);
        let q = 1.0 - r * r;
        q * q
    };
    let (m, rhs) = normal_equations(t, v, t0, scale, deg, weight);
    // M is symmetric positive definite: factor once (Cholesky, M = LLᵀ),
    // solve for the three coordinates and for row 2 of M⁻¹.
    let Some(l) = cholesky(&m, k) else {
        // Degenerate window (coincident parameters): fall back to pivoting.
        let coef = poly_fit(t, v, t0, scale, deg);
        return (coef, 0.0);
    };
    let coef = cholesky_solve3(&l, &rhs, k);
    if deg < 2 {
        return (coef, 0.0);
    }
    // Row 2 of M⁻¹, then aⱼ = wⱼ Σ_q z_q τⱼ^q.
    let mut e2 = [0.0f64; MAX_DEGREE + 1];
    e2[2] = 1.0;
    let z = cholesky_solve(&l, &e2, k);
    let mut sum_a2 = 0.0;
    for &tj in t {
        let tau = (tj - t0) / scale;
        let mut pw = 1.0;
        let mut a = 0.0;
        for zq in z.iter().take(k) {
            a += zq * pw;
            pw *= tau;
        }
        let a = a * weight(tj);
        sum_a2 += a * a;
    }
    (coef, sum_a2)
}

/// The piece of the ascending `knots` (at least two) that holds `x`: the
/// last k with knots[k] ≤ x, at most the last piece.
fn segment_of(knots: &[f64], x: f64) -> usize {
    knots
        .partition_point(|&k| k <= x)
        .saturating_sub(1)
        .min(knots.len() - 2)
}

type Small = [[f64; MAX_DEGREE + 1]; MAX_DEGREE + 1];

/// The normal equations of the least-squares polynomial of degree `deg`
/// through (t, v) in τ = (t − t0)/scale, each point weighted by
/// `weight(t)`: the (Hankel) matrix of weighted power sums and the
/// right-hand sides.
fn normal_equations(
    t: &[f64],
    v: &[DVec3],
    t0: f64,
    scale: f64,
    deg: usize,
    weight: impl Fn(f64) -> f64,
) -> (Small, [DVec3; MAX_DEGREE + 1]) {
    let k = deg + 1;
    let mut sums = [0.0f64; 2 * MAX_DEGREE + 1];
    let mut rhs = [DVec3::ZERO; MAX_DEGREE + 1];
    for (tj, vj) in t.iter().zip(v) {
        let (tau, w) = ((tj - t0) / scale, weight(*tj));
        let mut pw = w;
        for (q, s) in sums.iter_mut().enumerate().take(2 * deg + 1) {
            if q <= deg {
                rhs[q] += *vj * pw;
            }
            *s += pw;
            pw *= tau;
        }
    }
    let mut m = [[0.0f64; MAX_DEGREE + 1]; MAX_DEGREE + 1];
    for (r, row) in m.iter_mut().enumerate().take(k) {
        for (c, cell) in row.iter_mut().enumerate().take(k) {
            *cell = sums[r + c];
        }
    }
    (m, rhs)
}

/// Cholesky factor L (lower) of the leading k×k block of a symmetric
/// positive definite matrix; None if it is not (numerically) definite.
fn cholesky(m: &Small, k: usize) -> Option<Small> {
    let mut l = [[0.0f64; MAX_DEGREE + 1]; MAX_DEGREE + 1];
    for i in 0..k {
        for j in 0..=i {
            let (row_i, row_j) = (l[i], l[j]);
            let sum = m[i][j]
                - row_i[..j]
                    .iter()
                    .zip(&row_j[..j])
                    .map(|(a, b)| a * b)
                    .sum::<f64>();
            if i == j {
                if sum <= m[i][i] * 1e-13 {
                    return None;
                }
                l[i][i] = sum.sqrt();
            } else {
                l[i][j] = sum / l[j][j];
            }
        }
    }
    Some(l)
}

/// Solve L Lᵀ x = b on the leading k×k block.
fn cholesky_solve(l: &Small, b: &[f64; MAX_DEGREE + 1], k: usize) -> [f64; MAX_DEGREE + 1] {
    let mut y = [0.0f64; MAX_DEGREE + 1];
    for i in 0..k {
        let mut sum = b[i];
        for p in 0..i {
            sum -= l[i][p] * y[p];
        }
        y[i] = sum / l[i][i];
    }
    let mut x = [0.0f64; MAX_DEGREE + 1];
    for i in (0..k).rev() {
        let mut sum = y[i];
        for p in i + 1..k {
            sum -= l[p][i] * x[p];
        }
        x[i] = sum / l[i][i];
    }
    x
}

/// [`cholesky_solve`] for the three coordinates at once: each coordinate
/// goes through exactly the operations the scalar solve does (the same
/// result bit for bit, one pass instead of three).
fn cholesky_solve3(l: &Small, b: &[DVec3; MAX_DEGREE + 1], k: usize) -> [DVec3; MAX_DEGREE + 1] {
    let mut y = [DVec3::ZERO; MAX_DEGREE + 1];
    for i in 0..k {
        let mut sum = b[i];
        for p in 0..i {
            sum -= y[p] * l[i][p];
        }
        y[i] = sum / l[i][i];
    }
    let mut x = [DVec3::ZERO; MAX_DEGREE + 1];
    for i in (0..k).rev() {
        let mut sum = y[i];
        for p in i + 1..k {
            sum -= x[p] * l[p][i];
        }
        x[i] = sum / l[i][i];
    }
    x
}

/// Least-squares polynomial of degree `deg` through (t, v) in τ = (t − t0)/scale;
/// returns the coefficients of τ^0..τ^deg (unused ones zero).
fn poly_fit(t: &[f64], v: &[DVec3], t0: f64, scale: f64, deg: usize) -> [DVec3; MAX_DEGREE + 1] {
    let k = deg + 1;
    let (mut m, mut rhs) = normal_equations(t, v, t0, scale, deg, |_| 1.0);
    // Gaussian elimination with partial pivoting.
    for col in 0..k {
        let piv = (col..k)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .unwrap_or(col);
        m.swap(col, piv);
        rhs.swap(col, piv);
        let d = m[col][col];
        if d.abs() < 1e-300 {
            continue;
        }
        for r in col + 1..k {
            let f = m[r][col] / d;
            if f != 0.0 {
                let pivot_row = m[col];
                for (cell, p) in m[r][col..k].iter_mut().zip(&pivot_row[col..k]) {
                    *cell -= f * p;
                }
                let sub = rhs[col] * f;
                rhs[r] -= sub;
            }
        }
    }
    let mut x = [DVec3::ZERO; MAX_DEGREE + 1];
    for r in (0..k).rev() {
        let mut acc = rhs[r];
        for c in r + 1..k {
            acc -= x[c] * m[r][c];
        }
        x[r] = if m[r][r].abs() < 1e-300 {
            DVec3::ZERO
        } else {
            acc / m[r][r]
        };
    }
    x
}

/// A space curve through its samples, parameterised by arc length.
///
/// Guarantees: passes through every sample (exact coordinates) or within the
/// rounding of its coordinates (rounded ones, smoothed to `precision_mm`);
/// C² (quintic Hermite over the chord-length parameter, derivatives from
/// local degree-4 least-squares fits over at least 7 samples); stations are
/// arc length from the first point, by 8-point Gauss–Legendre per segment,
/// ascending. Points keep the frame and units of the samples (mm; the world
/// frame for network curves).
#[derive(Debug, Clone)]
pub struct SmoothCurve {
    h: Hermite5,
    /// Arc length (mm) at each sample.
    s: Vec<f64>,
    /// Rounding noise left in the second derivative at each sample, 1/mm.
    d2_noise: Vec<f64>,
    /// Precision of the coordinates the curve was made from, mm.
    precision_mm: f64,
    /// Half-width of the smoothing window, mm (0: 7-sample fits).
    smoothing_mm: f64,
}

/// Position and unit tangent at a station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    /// Arc length from the first sample, mm, clamped to [0, length].
    pub station_mm: f64,
    /// The point, in the frame of the curve's samples (world for network curves), mm.
    pub point_mm: DVec3,
    /// Unit tangent along increasing station (zero only on a degenerate curve).
    pub tangent: DVec3,
}

impl SmoothCurve {
    /// Interpolate exact points (mm; at least 2, consecutive points distinct).
    pub fn new(points_mm: &[DVec3]) -> SmoothCurve {
        SmoothCurve::with_precision(points_mm, 0.0)
    }

    /// A smooth curve through points whose coordinates are rounded to
    /// `precision_mm` (0 for exact), smoothed to that precision (module docs).
    pub fn with_precision(points_mm: &[DVec3], precision_mm: f64) -> SmoothCurve {
        let mut t = Vec::with_capacity(points_mm.len());
        let mut acc = 0.0;
        t.push(0.0);
        for w in points_mm.windows(2) {
            acc += w[1].distance(w[0]);
            t.push(acc);
        }
        let smoothed = smooth_samples(&t, points_mm, precision_mm);
        let smoothing_mm = smoothed.half_width_mm;
        let d2_noise = smoothed.d2_noise;
        let h = if smoothing_mm > 0.0 {
            // The chord parameter of rounded samples is itself noisy: take
            // the chord of the smoothed positions as the parameter (≈ arc
            // length) and carry the fitted derivatives over to it: unit
            // tangent, curvature vector as second derivative.
            let values = smoothed.values;
            let mut t = Vec::with_capacity(values.len());
            let mut acc = 0.0;
            t.push(0.0);
            for w in values.windows(2) {
                acc += w[1].distance(w[0]).max(1e-9);
                t.push(acc);
            }
            let (mut d1, mut d2) = (smoothed.d1, smoothed.d2);
            for (a, b) in d1.iter_mut().zip(d2.iter_mut()) {
                let v2 = a.length_squared().max(1e-300);
                let x = *a / v2.sqrt();
                *b = (*b - x * b.dot(x)) / v2;
                *a = x;
            }
            Hermite5::from_parts(t, values, d1, d2)
        } else {
            Hermite5::from_parts(t, smoothed.values, smoothed.d1, smoothed.d2)
        };
        let mut s = Vec::with_capacity(points_mm.len());
        s.push(0.0);
        let mut total = 0.0;
        for k in 0..h.segments() {
            total += h.piece(k).arc_length_to(1.0);
            s.push(total);
        }
        SmoothCurve {
            h,
            s,
            d2_noise,
            precision_mm,
            smoothing_mm,
        }
    }

    /// Precision of the coordinates, mm (0: exact).
    pub fn precision_mm(&self) -> f64 {
        self.precision_mm
    }
    /// Half-width of the smoothing window, mm (0: 7-sample fits).
    pub fn smoothing_mm(&self) -> f64 {
        self.smoothing_mm
    }
    /// Standard deviation of the rounding noise in the curvature at sample
    /// `i`, 1/mm (0 for exact coordinates).
    pub fn curvature_noise_per_mm(&self, i: usize) -> f64 {
        self.d2_noise[i]
    }

    /// Total arc length, mm.
    pub fn length_mm(&self) -> f64 {
        *self.s.last().unwrap_or(&0.0)
    }
    /// Stations of the samples, mm.
    pub fn sample_stations_mm(&self) -> &[f64] {
        &self.s
    }
    /// The (smoothed) samples the curve passes through, mm, one per station.
    pub fn samples(&self) -> &[DVec3] {
        self.h.values()
    }
    /// The interpolant over the chord parameter.
    pub fn hermite(&self) -> &Hermite5 {
        &self.h
    }

    /// Chord parameter of the i-th sample.
    pub fn sample_param(&self, i: usize) -> f64 {
        self.h.t[i]
    }

    /// Segment and local coordinate of a station (clamped to the curve).
    pub fn locate_station(&self, station_mm: f64) -> (usize, f64) {
        let n = self.s.len();
        if station_mm <= 0.0 {
            return (0, 0.0);
        }
        if station_mm >= self.s[n - 1] {
            return (n - 2, 1.0);
        }
        let k = segment_of(&self.s, station_mm);
        self.solve_in_segment(k, station_mm)
    }

    /// [`SmoothCurve::locate_station`] for a station expected in segment
    /// `hint` (or, failing that, the next one): exactly the same result, the
    /// search for the segment skipped when the guess is right (stations
    /// visited in order).
    pub fn locate_station_near(&self, station_mm: f64, hint: usize) -> (usize, f64) {
        let s = &self.s;
        for k in [hint, hint + 1] {
            // The segment the search would find: the last k with s[k] ≤ station.
            if k + 1 < s.len() && 0.0 < station_mm && s[k] <= station_mm && station_mm < s[k + 1] {
                return self.solve_in_segment(k, station_mm);
            }
        }
        self.locate_station(station_mm)
    }

    /// Local u of a station known to lie in segment k (Newton on the arc
    /// length from the linear guess, to |Δu| < 1e-14).
    fn solve_in_segment(&self, k: usize, station_mm: f64) -> (usize, f64) {
        let target = station_mm - self.s[k];
        let seg_len = self.s[k + 1] - self.s[k];
        let piece = self.h.piece(k);
        let mut u = (target / seg_len).clamp(0.0, 1.0);
        for _ in 0..12 {
            let f = piece.arc_length_to(u) - target;
            let speed = piece.speed_u(u);
            if speed <= 0.0 {
                break;
            }
            let step = f / speed;
            u = (u - step).clamp(0.0, 1.0);
            if step.abs() < 1e-14 {
                break;
            }
        }
        (k, u)
    }

    /// Segment k as one polynomial piece, for evaluating several points of
    /// it ([`SmoothCurve::gauss_nodes4_in`], [`SmoothCurve::station_in`],
    /// [`Piece::jet`]): exactly what the per-segment methods give.
    pub fn piece(&self, k: usize) -> Piece {
        self.h.piece(k)
    }

    /// 4-point Gauss–Legendre quadrature (exact for degree 7) over segment
    /// k from local u0 to u1 in arc length: for each node its local u, its
    /// station (mm) and its weight (mm), so Σ w·f(u) ≈ ∫ f ds over that
    /// piece of the curve. The nodes' stations are interpolated linearly in
    /// u between the piece's exact end stations: the parameter is the chord
    /// length, so |c′| is nearly constant and the error is below
    /// (Δs)²·max|d|c′|/du|/8, far under 1e-6 mm on sampled curves.
    pub fn gauss_nodes4(&self, k: usize, u0: f64, u1: f64) -> [(f64, f64, f64); 4] {
        self.gauss_nodes4_in(&self.h.piece(k), k, u0, u1)
    }

    /// [`SmoothCurve::gauss_nodes4`] with segment k given as its piece
    /// (`self.piece(k)`).
    pub fn gauss_nodes4_in(
        &self,
        piece: &Piece,
        k: usize,
        u0: f64,
        u1: f64,
    ) -> [(f64, f64, f64); 4] {
        const X: [f64; 4] = [
            0.069_431_844_202_973_71,
            0.330_009_478_207_571_87,
            0.669_990_521_792_428_1,
            0.930_568_155_797_026_3,
        ];
        const W: [f64; 4] = [
            0.173_927_422_568_726_93,
            0.326_072_577_431_273_07,
            0.326_072_577_431_273_07,
            0.173_927_422_568_726_93,
        ];
        let du = u1 - u0;
        let s0 = self.s[k] + piece.arc_length_to(u0);
        let mut speeds = [0.0; 4];
        let mut total = 0.0;
        for i in 0..4 {
            speeds[i] = piece.speed_u(u0 + X[i] * du);
            total += W[i] * speeds[i] * du;
        }
        let mut out = [(0.0, 0.0, 0.0); 4];
        for i in 0..4 {
            out[i] = (u0 + X[i] * du, s0 + X[i] * total, W[i] * speeds[i] * du);
        }
        out
    }

    /// Station of segment k at local u.
    pub fn station_at(&self, k: usize, u: f64) -> f64 {
        self.station_in(&self.h.piece(k), k, u)
    }

    /// [`SmoothCurve::station_at`] with segment k given as its piece.
    pub fn station_in(&self, piece: &Piece, k: usize, u: f64) -> f64 {
        self.s[k] + piece.arc_length_to(u)
    }

    /// Derivatives with respect to the chord parameter at segment k, local u.
    pub fn jet_at(&self, k: usize, u: f64) -> Jet {
        self.h.jet_at(k, u)
    }

    /// Point and unit tangent at a station (clamped to [0, length]).
    pub fn at(&self, station_mm: f64) -> CurvePoint {
        self.at_located(station_mm, self.locate_station(station_mm))
    }

    /// [`SmoothCurve::at`] for a station already located:
    /// `located = self.locate_station(station_mm)`.
    pub fn at_located(&self, station_mm: f64, located: (usize, f64)) -> CurvePoint {
        let (k, u) = located;
        let j = self.h.jet_at(k, u);
        CurvePoint {
            station_mm: station_mm.clamp(0.0, self.length_mm()),
            point_mm: j.value,
            tangent: j.d1.normalize_or_zero(),
        }
    }

    /// Point at a station.
    pub fn point(&self, station_mm: f64) -> DVec3 {
        self.at(station_mm).point_mm
    }
    /// Unit tangent at a station.
    pub fn tangent(&self, station_mm: f64) -> DVec3 {
        self.at(station_mm).tangent
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn helix(r: f64, c: f64, n: usize, turns: f64) -> (Vec<DVec3>, f64) {
        let pts = (0..n)
            .map(|i| {
                let a = turns * 2.0 * PI * i as f64 / (n - 1) as f64;
                DVec3::new(r * a.cos(), r * a.sin(), c * a)
            })
            .collect();
        let len = (r * r + c * c).sqrt() * turns * 2.0 * PI;
        (pts, len)
    }

    #[test]
    fn straight_line_is_exact() {
        let pts = vec![DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0)];
        let c = SmoothCurve::new(&pts);
        assert!((c.length_mm() - 5.0).abs() < 1e-12);
        assert!(c.point(2.5).distance(DVec3::new(1.5, 2.0, 0.0)) < 1e-12);
    }

    #[test]
    fn helix_length_and_stations_sparse_sampling() {
        // Radius 1 m helix sampled every ~50 mm: length good to 0.01 mm.
        let (pts, len) = helix(1000.0, 100.0, 127, 1.0);
        let c = SmoothCurve::new(&pts);
        assert!(
            (c.length_mm() - len).abs() < 0.01,
            "{} vs {len}",
            c.length_mm()
        );
        // A station in the middle of a segment maps to the exact point.
        let s = 1234.5;
        let a = s / (1000.0f64.powi(2) + 100.0f64.powi(2)).sqrt();
        let exact = DVec3::new(1000.0 * a.cos(), 1000.0 * a.sin(), 100.0 * a);
        assert!(
            c.point(s).distance(exact) < 0.01,
            "{}",
            c.point(s).distance(exact)
        );
    }

    #[test]
    fn station_round_trip() {
        let (pts, _) = helix(500.0, 50.0, 40, 0.8);
        let c = SmoothCurve::new(&pts);
        for &s in &[0.0, 1.0, 100.0, 777.7, c.length_mm() - 0.5] {
            let (k, u) = c.locate_station(s);
            assert!((c.station_at(k, u) - s).abs() < 1e-9);
        }
    }

    #[test]
    fn roughness_sees_wiggles_below_the_window_and_not_a_smooth_arc() {
        // An arc of radius 5 m sampled every 25 mm: a degree-4 fit over
        // ±200 mm follows it to far below a micrometre.
        let arc: Vec<DVec3> = (0..200)
            .map(|i| {
                let a = i as f64 * 25.0 / 5000.0;
                DVec3::new(5000.0 * a.sin(), 5000.0 * (1.0 - a.cos()), 0.0)
            })
            .collect();
        assert!(
            roughness_mm(&arc, 200.0) < 1e-4,
            "{}",
            roughness_mm(&arc, 200.0)
        );
        // The same arc with a lateral wiggle of 0.05 mm and a 75 mm
        // wavelength: the fit cannot follow it, so the roughness is its
        // RMS, 0.05/√2 = 0.035 mm (less the few percent the fit absorbs).
        let wiggly: Vec<DVec3> = arc
            .iter()
            .enumerate()
            .map(|(i, p)| *p + DVec3::Z * 0.05 * (2.0 * PI * i as f64 * 25.0 / 75.0).sin())
            .collect();
        let r = roughness_mm(&wiggly, 200.0);
        assert!((r - 0.05 / 2f64.sqrt()).abs() < 0.004, "{r}");
        assert_eq!(roughness_mm(&arc[..5], 200.0), 0.0);
    }
}
