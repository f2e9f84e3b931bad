//! The surface interface every stage shares: a parametric surface X(u, v)
//! with its jet (point and partial derivatives), its curvature (fundamental
//! forms, principal curvatures and directions) and asymptotic directions
//! (II(d, d) = 0). The analytic surfaces are in `design::surface`, the
//! mesh surface in `design::mesh::surface`.

use glam::{DMat3, DVec2, DVec3};

/// A point of a surface with its partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceJet {
    /// The point X(u, v), in the surface's frame and units (mm and world for `design::surface::Placed`).
    pub p: DVec3,
    /// ∂X/∂u, same units per unit of u.
    pub pu: DVec3,
    /// ∂X/∂v.
    pub pv: DVec3,
    /// ∂²X/∂u².
    pub puu: DVec3,
    /// ∂²X/∂u∂v.
    pub puv: DVec3,
    /// ∂²X/∂v².
    pub pvv: DVec3,
}

/// Curvature of a surface at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    /// Unit normal pu × pv / |pu × pv|.
    pub normal: DVec3,
    /// First fundamental form E, F, G.
    pub first: [f64; 3],
    /// Second fundamental form L, M, N.
    pub second: [f64; 3],
    /// The larger principal curvature (k1 ≥ k2), 1 per surface unit (1/mm
    /// for `design::surface::Placed`); the normal curvature along d1.
    pub k1: f64,
    /// The smaller principal curvature, 1 per surface unit (1/mm for `design::surface::Placed`).
    pub k2: f64,
    /// Unit principal direction (3D) of k1, tangent to the surface.
    pub d1: DVec3,
    /// Unit principal direction of k2, normal × d1.
    pub d2: DVec3,
}

impl Curvature {
    /// Gaussian curvature K = k1·k2 (negative on an anticlastic surface).
    pub fn gaussian(&self) -> f64 {
        self.k1 * self.k2
    }
    /// The shape operator as a 3D tensor on the tangent plane,
    /// k1·d1d1ᵀ + k2·d2d2ᵀ (as [`shape_tensor_of`] makes it from a jet).
    pub fn shape_tensor(&self) -> DMat3 {
        outer(self.d1, self.d1) * self.k1 + outer(self.d2, self.d2) * self.k2
    }
    /// Mean curvature H = (k1 + k2)/2 (zero on a minimal surface).
    pub fn mean(&self) -> f64 {
        0.5 * (self.k1 + self.k2)
    }
    /// The two asymptotic directions (3D, unit), family A turned from d1
    /// towards d2, family B away; None where the surface is not anticlastic
    /// (K ≥ −`min_neg_k`).
    pub fn asymptotic(&self, min_neg_k: f64) -> Option<(DVec3, DVec3)> {
        if self.gaussian() >= -min_neg_k {
            return None;
        }
        // II(d) = k1 cos²θ + k2 sin²θ = 0.
        let theta = (-self.k1 / self.k2).sqrt().atan();
        let (s, c) = theta.sin_cos();
        Some((self.d1 * c + self.d2 * s, self.d1 * c - self.d2 * s))
    }
    /// Geodesic torsion of the surface along a unit tangent direction d:
    /// tg = (k2 − k1)·sin θ·cos θ with θ the angle from d1.
    pub fn geodesic_torsion(&self, d: DVec3) -> f64 {
        let (c, s) = (d.dot(self.d1), d.dot(self.d2));
        (self.k2 - self.k1) * s * c
    }
    /// Normal curvature along a unit tangent direction.
    pub fn normal_curvature(&self, d: DVec3) -> f64 {
        let (c, s) = (d.dot(self.d1), d.dot(self.d2));
        self.k1 * c * c + self.k2 * s * s
    }
}

/// A parametric surface X(u, v).
pub trait Surface: Sync + Send {
    /// Point and partial derivatives.
    fn eval(&self, uv: DVec2) -> SurfaceJet;
    /// Whether (u, v) lies in the domain where the surface is regular.
    fn in_domain(&self, _uv: DVec2) -> bool {
        true
    }
    /// The partial derivatives only (`p` may be left zero): cheaper where the
    /// point itself is costly (Schwarz D integrates it).
    fn derivatives(&self, uv: DVec2) -> SurfaceJet {
        self.eval(uv)
    }
    /// The point X(u, v) (mm, world frame for `design::surface::Placed`).
    fn point(&self, uv: DVec2) -> DVec3 {
        self.eval(uv).p
    }
    /// (X_u, X_v).
    fn partials(&self, uv: DVec2) -> (DVec3, DVec3) {
        let j = self.derivatives(uv);
        (j.pu, j.pv)
    }
    /// Unit normal X_u × X_v / |X_u × X_v|.
    fn normal(&self, uv: DVec2) -> DVec3 {
        let (pu, pv) = self.partials(uv);
        pu.cross(pv).normalize()
    }
    /// Fundamental forms, principal curvatures and directions.
    fn curvature(&self, uv: DVec2) -> Curvature {
        curvature_of(&self.derivatives(uv))
    }
}

/// Curvature from a jet (shape operator in an orthonormal tangent basis).
pub fn curvature_of(j: &SurfaceJet) -> Curvature {
    let n = j.pu.cross(j.pv).normalize();
    let (e, f, g) = (j.pu.dot(j.pu), j.pu.dot(j.pv), j.pv.dot(j.pv));
    let (l, m, nn) = (j.puu.dot(n), j.puv.dot(n), j.pvv.dot(n));
    let e1 = j.pu / e.sqrt();
    let e2 = n.cross(e1);
    // Parameter coordinates of e1, e2: solve [pu pv](a, b) = d.
    let det = e * g - f * f;
    let coords = |d: DVec3| {
        let (r1, r2) = (j.pu.dot(d), j.pv.dot(d));
        DVec2::new((g * r1 - f * r2) / det, (e * r2 - f * r1) / det)
    };
    let ii = |a: DVec2, b: DVec2| l * a.x * b.x + m * (a.x * b.y + a.y * b.x) + nn * a.y * b.y;
    let (c1, c2) = (coords(e1), coords(e2));
    let (s11, s12, s22) = (ii(c1, c1), ii(c1, c2), ii(c2, c2));
    // Eigen-decomposition of the symmetric 2×2 shape operator.
    let mean = 0.5 * (s11 + s22);
    let rad = (0.25 * (s11 - s22).powi(2) + s12 * s12).sqrt();
    let (k1, k2) = (mean + rad, mean - rad);
    let phi = 0.5 * (2.0 * s12).atan2(s11 - s22);
    let d1 = e1 * phi.cos() + e2 * phi.sin();
    let d2 = n.cross(d1);
    Curvature {
        normal: n,
        first: [e, f, g],
        second: [l, m, nn],
        k1,
        k2,
        d1,
        d2,
    }
}

/// The unit normal and the shape operator of a jet as a symmetric 3D
/// tensor on its tangent plane: S = J·I⁻¹·II·I⁻¹·Jᵀ with J = [pu pv], so
/// that tᵀ·S·t is the second fundamental form of a tangent vector t (and
/// S·n = 0). Its eigenpairs in the tangent plane are [`curvature_of`]'s
/// principal curvatures and directions; as a tensor it can be averaged.
pub fn shape_tensor_of(j: &SurfaceJet) -> (DVec3, DMat3) {
    let n = j.pu.cross(j.pv).normalize();
    let (e, f, g) = (j.pu.dot(j.pu), j.pu.dot(j.pv), j.pv.dot(j.pv));
    let (l, m, nn) = (j.puu.dot(n), j.puv.dot(n), j.pvv.dot(n));
    let det = e * g - f * f;
    // A = I⁻¹ = [g, −f; −f, e]/det; M = A·II·A.
    let (a11, a12, a22) = (g / det, -f / det, e / det);
    let (b11, b12, b21, b22) = (
        a11 * l + a12 * m,
        a11 * m + a12 * nn,
        a12 * l + a22 * m,
        a12 * m + a22 * nn,
    );
    let (m11, m12, m22) = (
        b11 * a11 + b12 * a12,
        b11 * a12 + b12 * a22,
        b21 * a12 + b22 * a22,
    );
    let cross = outer(j.pu, j.pv);
    (
        n,
        outer(j.pu, j.pu) * m11 + (cross + cross.transpose()) * m12 + outer(j.pv, j.pv) * m22,
    )
}

/// The outer product a·bᵀ.
pub fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// Parameter-space vector (du, dv) of a 3D tangent vector at a jet.
pub fn to_parameter(j: &SurfaceJet, d: DVec3) -> DVec2 {
    let (e, f, g) = (j.pu.dot(j.pu), j.pu.dot(j.pv), j.pv.dot(j.pv));
    let det = e * g - f * f;
    let (r1, r2) = (j.pu.dot(d), j.pv.dot(d));
    DVec2::new((g * r1 - f * r2) / det, (e * r2 - f * r1) / det)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a jet with a skew, non-unit parametrisation the tensor is
    /// symmetric, annihilates the normal and has `curvature_of`'s
    /// principal curvatures along its principal directions.
    #[test]
    fn the_shape_tensor_has_the_principal_curvatures() {
        let j = SurfaceJet {
            p: DVec3::ZERO,
            pu: DVec3::new(1.0, 0.2, 0.3),
            pv: DVec3::new(0.1, 1.4, -0.2),
            puu: DVec3::new(0.05, 0.1, 0.7),
            puv: DVec3::new(0.2, -0.1, 0.3),
            pvv: DVec3::new(0.0, 0.3, -0.9),
        };
        let c = curvature_of(&j);
        let (n, s) = shape_tensor_of(&j);
        assert!((n - c.normal).length() < 1e-15);
        assert!((s - s.transpose())
            .to_cols_array()
            .iter()
            .all(|x| x.abs() < 1e-14));
        assert!((s * n).length() < 1e-14);
        assert!(
            (s * c.d1 - c.d1 * c.k1).length() < 1e-14,
            "{} {}",
            s * c.d1,
            c.k1
        );
        assert!((s * c.d2 - c.d2 * c.k2).length() < 1e-14);
        assert!(c.k1 - c.k2 > 0.1);
    }
}
