//! Analytic surfaces behind one interface: point, first and second partial
//! derivatives, normal, fundamental forms, principal curvatures and
//! directions, and the asymptotic directions (II(d, d) = 0).
//!
//! Minimal: Enneper, catenoid, helicoid, Scherk's doubly periodic surface,
//! Schwarz D (from its Weierstrass data, integrated numerically). Anticlastic
//! but not minimal: the hyperbolic paraboloid. Each can be scaled and placed
//! ([`Placed`]).

pub use crate::geom::surface::{curvature_of, to_parameter, Curvature, Surface, SurfaceJet};
use glam::{DMat3, DVec2, DVec3};

/// Enneper's surface X = (u − u³/3 + uv², v − v³/3 + vu², u² − v²); regular
/// and embedded for u² + v² < 3.
#[derive(Debug, Clone, Copy)]
pub struct Enneper;

impl Surface for Enneper {
    fn eval(&self, q: DVec2) -> SurfaceJet {
        let (u, v) = (q.x, q.y);
        SurfaceJet {
            p: DVec3::new(
                u - u * u * u / 3.0 + u * v * v,
                v - v * v * v / 3.0 + v * u * u,
                u * u - v * v,
            ),
            pu: DVec3::new(1.0 - u * u + v * v, 2.0 * u * v, 2.0 * u),
            pv: DVec3::new(2.0 * u * v, 1.0 - v * v + u * u, -2.0 * v),
            puu: DVec3::new(-2.0 * u, 2.0 * v, 2.0),
            puv: DVec3::new(2.0 * v, 2.0 * u, 0.0),
            pvv: DVec3::new(2.0 * u, -2.0 * v, -2.0),
        }
    }
    fn in_domain(&self, q: DVec2) -> bool {
        q.length_squared() < 3.0
    }
}

/// Catenoid X = c(cosh v cos u, cosh v sin u, v).
#[derive(Debug, Clone, Copy)]
pub struct Catenoid {
    /// Scale of the neck: waist radius c, in surface units (non-zero).
    pub c: f64,
}

impl Surface for Catenoid {
    fn eval(&self, q: DVec2) -> SurfaceJet {
        let (u, v, c) = (q.x, q.y, self.c);
        let (ch, sh) = (v.cosh(), v.sinh());
        let (cu, su) = (u.cos(), u.sin());
        SurfaceJet {
            p: c * DVec3::new(ch * cu, ch * su, v),
            pu: c * DVec3::new(-ch * su, ch * cu, 0.0),
            pv: c * DVec3::new(sh * cu, sh * su, 1.0),
            puu: c * DVec3::new(-ch * cu, -ch * su, 0.0),
            puv: c * DVec3::new(-sh * su, sh * cu, 0.0),
            pvv: c * DVec3::new(ch * cu, ch * su, 0.0),
        }
    }
}

/// Helicoid X = (v cos u, v sin u, c·u).
#[derive(Debug, Clone, Copy)]
pub struct Helicoid {
    /// Pitch: the surface rises 2π·c per turn, in surface units (non-zero).
    pub c: f64,
}

impl Surface for Helicoid {
    fn eval(&self, q: DVec2) -> SurfaceJet {
        let (u, v) = (q.x, q.y);
        let (cu, su) = (u.cos(), u.sin());
        SurfaceJet {
            p: DVec3::new(v * cu, v * su, self.c * u),
            pu: DVec3::new(-v * su, v * cu, self.c),
            pv: DVec3::new(cu, su, 0.0),
            puu: DVec3::new(-v * cu, -v * su, 0.0),
            puv: DVec3::new(-su, cu, 0.0),
            pvv: DVec3::ZERO,
        }
    }
}

/// Hyperbolic paraboloid z = xy/c over (x, y): anticlastic, not minimal.
#[derive(Debug, Clone, Copy)]
pub struct Hypar {
    /// Curvature scale: z = xy/c, in surface units (non-zero).
    pub c: f64,
}

impl Surface for Hypar {
    fn eval(&self, q: DVec2) -> SurfaceJet {
        let c = self.c;
        SurfaceJet {
            p: DVec3::new(q.x, q.y, q.x * q.y / c),
            pu: DVec3::new(1.0, 0.0, q.y / c),
            pv: DVec3::new(0.0, 1.0, q.x / c),
            puu: DVec3::ZERO,
            puv: DVec3::new(0.0, 0.0, 1.0 / c),
            pvv: DVec3::ZERO,
        }
    }
}

/// Scherk's doubly periodic surface z = ln cos y − ln cos x over one cell
/// |x|, |y| < π/2 (the others are its translates by (π, π) and reflections).
#[derive(Debug, Clone, Copy)]
pub struct Scherk;

impl Surface for Scherk {
    fn eval(&self, q: DVec2) -> SurfaceJet {
        let (x, y) = (q.x, q.y);
        let (tx, ty) = (x.tan(), y.tan());
        SurfaceJet {
            p: DVec3::new(x, y, y.cos().ln() - x.cos().ln()),
            pu: DVec3::new(1.0, 0.0, tx),
            pv: DVec3::new(0.0, 1.0, -ty),
            puu: DVec3::new(0.0, 0.0, 1.0 + tx * tx),
            puv: DVec3::ZERO,
            pvv: DVec3::new(0.0, 0.0, -(1.0 + ty * ty)),
        }
    }
    fn in_domain(&self, q: DVec2) -> bool {
        let lim = std::f64::consts::FRAC_PI_2 - 1e-9;
        q.x.abs() < lim && q.y.abs() < lim
    }
}

/// Schwarz's D surface from its Weierstrass data f = (1 − 14z⁴ + z⁸)^(−1/2),
/// g = z over z = u + iv: X = Re ∫₀^z f·(1 − g², i(1 + g²), 2g) dζ, integrated
/// along the straight path by Gauss–Legendre (graded near the end). The domain
/// is the disc inside the branch points at |z| = (2 − √3)^½ ≈ 0.518, the flat
/// vertices of the skew quadrilateral {z: |z| < ...} whose edges are straight
/// lines through z = (√2 − 1)·e^{i(π/4 + kπ/2)}. The diagonals z = t·e^{±iπ/4}
/// are straight lines through the centre.
#[derive(Debug, Clone, Copy)]
pub struct SchwarzD;

/// Domain radius of [`SchwarzD`] in the z plane: the branch points
/// z⁴ = 7 − 4√3 (|z| = (2 − √3)^½), images of the flat vertices of its skew
/// quadrilaterals.
pub const SCHWARZ_D_RADIUS: f64 = 0.517_638_090_205_041_5;

/// |z| of the midpoints of the quadrilateral's edges on the diagonals
/// z = t·e^{±iπ/4}: √2 − 1 (where the normals at t and −t are perpendicular).
pub const SCHWARZ_D_EDGE_MIDPOINT: f64 = std::f64::consts::SQRT_2 - 1.0;

#[derive(Debug, Clone, Copy, PartialEq)]
struct C64 {
    re: f64,
    im: f64,
}

impl C64 {
    const fn new(re: f64, im: f64) -> C64 {
        C64 { re, im }
    }
    fn mul(self, o: C64) -> C64 {
        C64::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    fn add(self, o: C64) -> C64 {
        C64::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: C64) -> C64 {
        C64::new(self.re - o.re, self.im - o.im)
    }
    fn scale(self, s: f64) -> C64 {
        C64::new(self.re * s, self.im * s)
    }
    fn inv(self) -> C64 {
        let d = self.re * self.re + self.im * self.im;
        C64::new(self.re / d, -self.im / d)
    }
    /// Principal square root.
    fn sqrt(self) -> C64 {
        let r = self.re.hypot(self.im);
        let re = (0.5 * (r + self.re)).max(0.0).sqrt();
        let im = (0.5 * (r - self.re)).max(0.0).sqrt();
        C64::new(re, if self.im < 0.0 { -im } else { im })
    }
}

impl SchwarzD {
    /// φ(z) = f(1 − z², i(1 + z²), 2z) and its derivative φ'(z).
    fn phi(z: C64) -> ([C64; 3], [C64; 3]) {
        let one = C64::new(1.0, 0.0);
        let i = C64::new(0.0, 1.0);
        let z2 = z.mul(z);
        let z4 = z2.mul(z2);
        let z8 = z4.mul(z4);
        let w = one.sub(z4.scale(14.0)).add(z8);
        let f = w.sqrt().inv();
        // f' = −½ w^(−3/2) w',  w' = −56 z³ + 8 z⁷
        let z3 = z2.mul(z);
        let z7 = z4.mul(z3);
        let dw = z3.scale(-56.0).add(z7.scale(8.0));
        let df = f.mul(f).mul(f).mul(dw).scale(-0.5);
        let a = [one.sub(z2), i.mul(one.add(z2)), z.scale(2.0)];
        let da = [z.scale(-2.0), i.mul(z.scale(2.0)), C64::new(2.0, 0.0)];
        let phi = [f.mul(a[0]), f.mul(a[1]), f.mul(a[2])];
        let dphi = [
            df.mul(a[0]).add(f.mul(da[0])),
            df.mul(a[1]).add(f.mul(da[1])),
            df.mul(a[2]).add(f.mul(da[2])),
        ];
        (phi, dphi)
    }
}

/// Gauss–Legendre nodes and weights on [0, 1], computed once (Newton on the
/// Legendre polynomial's roots).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = Vec::with_capacity(n);
    let mut w = Vec::with_capacity(n);
    for i in 0..n {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x.push(0.5 * (1.0 - z));
        w.push(1.0 / ((1.0 - z * z) * dp * dp));
    }
    (x, w)
}

/// The real parts of a complex 3-vector.
fn re(c: [C64; 3]) -> DVec3 {
    DVec3::new(c[0].re, c[1].re, c[2].re)
}

/// The imaginary parts of a complex 3-vector.
fn im(c: [C64; 3]) -> DVec3 {
    DVec3::new(c[0].im, c[1].im, c[2].im)
}

/// The jet at `p` of the Weierstrass–Enneper surface with φ = `phi` and
/// φ' = `dphi` there: X_u = Re φ, X_v = −Im φ and their derivatives.
fn jet(p: DVec3, phi: [C64; 3], dphi: [C64; 3]) -> SurfaceJet {
    SurfaceJet {
        p,
        pu: re(phi),
        pv: -im(phi),
        puu: re(dphi),
        puv: -im(dphi),
        pvv: -re(dphi),
    }
}

fn gl24() -> &'static (Vec<f64>, Vec<f64>) {
    static GL: std::sync::OnceLock<(Vec<f64>, Vec<f64>)> = std::sync::OnceLock::new();
    GL.get_or_init(|| gauss_legendre(24))
}

impl Surface for SchwarzD {
    fn derivatives(&self, q: DVec2) -> SurfaceJet {
        let (phi, dphi) = SchwarzD::phi(C64::new(q.x, q.y));
        jet(DVec3::ZERO, phi, dphi)
    }
    fn eval(&self, q: DVec2) -> SurfaceJet {
        let z = C64::new(q.x, q.y);
        // ∫₀^z φ(ζ) dζ along ζ = t z, t ∈ [0, 1]: z · ∫₀¹ φ(t z) dt, on panels
        // graded towards t = 1 (the end may lie near a branch point, where φ
        // grows like (z − z₀)^(−½)).
        let mut acc = [C64::new(0.0, 0.0); 3];
        let (xs, ws) = gl24();
        let mut panel = |t0: f64, t1: f64| {
            for (x, w) in xs.iter().zip(ws) {
                let (phi, _) = SchwarzD::phi(z.scale(t0 + (t1 - t0) * x));
                for k in 0..3 {
                    acc[k] = acc[k].add(phi[k].scale(w * (t1 - t0)));
                }
            }
        };
        let panels = if q.length() > 0.4 { 10 } else { 1 };
        let mut t0 = 0.0;
        for k in 1..=panels {
            let t1 = if k == panels {
                1.0
            } else {
                1.0 - 0.5f64.powi(k)
            };
            panel(t0, t1);
            t0 = t1;
        }
        let integral = [z.mul(acc[0]), z.mul(acc[1]), z.mul(acc[2])];
        let (phi, dphi) = SchwarzD::phi(z);
        jet(re(integral), phi, dphi)
    }
    fn in_domain(&self, q: DVec2) -> bool {
        q.length() < SCHWARZ_D_RADIUS
    }
}

/// A surface scaled by `scale_mm` (mm per surface unit) and placed by a
/// rotation and a translation (mm): X' = R·(s·X) + t.
#[derive(Clone)]
pub struct Placed {
    /// The surface in its own units.
    pub surface: std::sync::Arc<dyn Surface>,
    /// Millimetres per surface unit (positive).
    pub scale_mm: f64,
    /// Rotation applied after scaling (orthonormal).
    pub rotation: DMat3,
    /// Translation applied last, world frame, mm.
    pub translation_mm: DVec3,
}

impl Surface for Placed {
    fn eval(&self, q: DVec2) -> SurfaceJet {
        let j = self.surface.eval(q);
        let r = |v: DVec3| self.rotation * (v * self.scale_mm);
        SurfaceJet {
            p: r(j.p) + self.translation_mm,
            pu: r(j.pu),
            pv: r(j.pv),
            puu: r(j.puu),
            puv: r(j.puv),
            pvv: r(j.pvv),
        }
    }
    fn derivatives(&self, q: DVec2) -> SurfaceJet {
        let j = self.surface.derivatives(q);
        let r = |v: DVec3| self.rotation * (v * self.scale_mm);
        SurfaceJet {
            p: DVec3::ZERO,
            pu: r(j.pu),
            pv: r(j.pv),
            puu: r(j.puu),
            puv: r(j.puv),
            pvv: r(j.pvv),
        }
    }
    fn in_domain(&self, q: DVec2) -> bool {
        self.surface.in_domain(q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd_check(s: &dyn Surface, q: DVec2) {
        let h = 1e-6;
        let j = s.eval(q);
        let du = (s.point(q + DVec2::X * h) - s.point(q - DVec2::X * h)) / (2.0 * h);
        let dv = (s.point(q + DVec2::Y * h) - s.point(q - DVec2::Y * h)) / (2.0 * h);
        assert!(
            du.distance(j.pu) < 1e-6 * (1.0 + j.pu.length()),
            "pu {du} vs {}",
            j.pu
        );
        assert!(
            dv.distance(j.pv) < 1e-6 * (1.0 + j.pv.length()),
            "pv {dv} vs {}",
            j.pv
        );
        let duu = (s.eval(q + DVec2::X * h).pu - s.eval(q - DVec2::X * h).pu) / (2.0 * h);
        let duv = (s.eval(q + DVec2::Y * h).pu - s.eval(q - DVec2::Y * h).pu) / (2.0 * h);
        let dvv = (s.eval(q + DVec2::Y * h).pv - s.eval(q - DVec2::Y * h).pv) / (2.0 * h);
        assert!(duu.distance(j.puu) < 1e-5 * (1.0 + j.puu.length()), "puu");
        assert!(duv.distance(j.puv) < 1e-5 * (1.0 + j.puv.length()), "puv");
        assert!(dvv.distance(j.pvv) < 1e-5 * (1.0 + j.pvv.length()), "pvv");
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let q = DVec2::new(0.23, -0.31);
        fd_check(&Enneper, q);
        fd_check(&Catenoid { c: 2.0 }, q);
        fd_check(&Helicoid { c: 0.7 }, q);
        fd_check(&Hypar { c: 1.5 }, q);
        fd_check(&Scherk, q);
        fd_check(&SchwarzD, DVec2::new(0.21, 0.13));
    }

    #[test]
    fn minimal_surfaces_have_zero_mean_curvature() {
        let q = DVec2::new(0.3, 0.2);
        for s in [
            &Enneper as &dyn Surface,
            &Catenoid { c: 2.0 },
            &Helicoid { c: 0.7 },
            &Scherk,
            &SchwarzD,
        ] {
            let c = s.curvature(q);
            assert!(
                c.mean().abs() < 1e-9 * c.k1.abs().max(1.0),
                "H = {}",
                c.mean()
            );
            let (a, b) = c.asymptotic(0.0).expect("anticlastic");
            assert!(
                a.dot(b).abs() < 1e-12,
                "asymptotic directions cross at 90° on a minimal surface"
            );
            assert!(c.normal_curvature(a).abs() < 1e-12 && c.normal_curvature(b).abs() < 1e-12);
            assert!(
                (c.geodesic_torsion(a).powi(2) + c.gaussian()).abs() < 1e-9 * c.gaussian().abs()
            );
        }
        // Enneper: k = ±2/λ².
        let lambda = 1.0 + q.length_squared();
        let c = Enneper.curvature(q);
        assert!((c.k1 - 2.0 / (lambda * lambda)).abs() < 1e-12);
        // The hypar is anticlastic but not minimal.
        let h = Hypar { c: 1.0 }.curvature(q);
        assert!(h.gaussian() < 0.0 && h.mean().abs() > 1e-3);
    }

    #[test]
    fn gauss_legendre_integrates_polynomials() {
        let (x, w) = gauss_legendre(24);
        let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(40)).sum();
        assert!((integral - 1.0 / 41.0).abs() < 1e-14);
    }

    #[test]
    fn schwarz_d_diagonal_is_a_straight_line() {
        let d = DVec2::new(1.0, 1.0).normalize();
        let p1 = SchwarzD.point(d * 0.1);
        let p2 = SchwarzD.point(d * 0.3);
        let p3 = SchwarzD.point(d * 0.45);
        assert!((p2 - p1).normalize().cross((p3 - p1).normalize()).length() < 1e-12);
    }
}
