//! NURBS curves: rational B-splines evaluated with de Boor's algorithm in
//! homogeneous coordinates and sampled per knot span (how DXF SPLINEs are
//! read). Pure geometry: no file format, no units of its own.

use glam::DVec3;

/// A NURBS curve, evaluated with de Boor's algorithm in homogeneous coordinates.
pub struct Nurbs {
    degree: usize,
    knots: Vec<f64>,
    /// (w·P, w)
    ctrl: Vec<(DVec3, f64)>,
}

impl Nurbs {
    /// A curve of `degree` ≥ 1 with `knots` (non-decreasing, finite, exactly
    /// control points + degree + 1 of them), control points `ctrl` (finite, more
    /// than `degree`; any length unit, kept) and `weights` (one per control point,
    /// positive). Fails with a one-line reason when any of that does not hold.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        ctrl: Vec<DVec3>,
        weights: Vec<f64>,
    ) -> std::result::Result<Nurbs, String> {
        if degree == 0 {
            return Err("spline degree must be at least 1".into());
        }
        if ctrl.len() <= degree {
            return Err(format!(
                "spline of degree {degree} needs more than {degree} control points, has {}",
                ctrl.len()
            ));
        }
        if knots.len() != ctrl.len() + degree + 1 {
            return Err(format!(
                "spline has {} knots; {} control points of degree {degree} need {}",
                knots.len(),
                ctrl.len(),
                ctrl.len() + degree + 1
            ));
        }
        if knots.windows(2).any(|w| w[1] < w[0]) || knots.iter().any(|k| !k.is_finite()) {
            return Err("spline knots are not a non-decreasing sequence of numbers".into());
        }
        if weights.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
            return Err("spline weights must be positive".into());
        }
        if ctrl.iter().any(|p| !p.is_finite()) {
            return Err("spline control point has a NaN or infinite coordinate".into());
        }
        let ctrl = ctrl
            .into_iter()
            .zip(weights)
            .map(|(p, w)| (p * w, w))
            .collect();
        Ok(Nurbs {
            degree,
            knots,
            ctrl,
        })
    }

    /// Evaluate at parameter `u` in the valid domain.
    pub fn eval(&self, u: f64) -> DVec3 {
        let p = self.degree;
        let n = self.ctrl.len();
        // Span k with knots[k] <= u < knots[k+1], p <= k < n.
        let mut k = p;
        while k + 1 < n && self.knots[k + 1] <= u {
            k += 1;
        }
        let mut d: Vec<(DVec3, f64)> = (0..=p).map(|j| self.ctrl[j + k - p]).collect();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = j + k - p;
                let denom = self.knots[i + 1 + p - r] - self.knots[i];
                let alpha = if denom > 0.0 {
                    (u - self.knots[i]) / denom
                } else {
                    0.0
                };
                d[j] = (
                    d[j - 1].0 * (1.0 - alpha) + d[j].0 * alpha,
                    d[j - 1].1 * (1.0 - alpha) + d[j].1 * alpha,
                );
            }
        }
        d[p].0 / d[p].1
    }

    /// Points at `per_span` equal parameter steps in every non-empty knot span.
    pub fn sample(&self, per_span: usize) -> Vec<DVec3> {
        let p = self.degree;
        let n = self.ctrl.len();
        let mut out = Vec::new();
        for k in p..n {
            let (a, b) = (self.knots[k], self.knots[k + 1]);
            if b <= a {
                continue;
            }
            for j in 0..per_span {
                let u = a + (b - a) * j as f64 / per_span as f64;
                out.push(self.eval(u));
            }
        }
        out.push(self.eval(self.knots[n]));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nurbs_quarter_circle_is_exact() {
        // Rational quadratic quarter circle of radius 100.
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let c = Nurbs::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![
                DVec3::new(100.0, 0.0, 0.0),
                DVec3::new(100.0, 100.0, 0.0),
                DVec3::new(0.0, 100.0, 0.0),
            ],
            vec![1.0, w, 1.0],
        )
        .expect("valid");
        for p in c.sample(10) {
            assert!((p.length() - 100.0).abs() < 1e-9, "{p}");
        }
        assert!(c.eval(1.0).distance(DVec3::new(0.0, 100.0, 0.0)) < 1e-12);
    }

    #[test]
    fn nurbs_rejects_bad_knots() {
        let e = Nurbs::new(3, vec![0.0; 3], vec![DVec3::ZERO; 4], vec![1.0; 4]);
        assert!(e.is_err());
    }
}
