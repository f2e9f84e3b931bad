//! The verdict on one lamella element: cross-section and member checks of
//! an upright rectangular strip under load plus its erection state.
//!
//! Section (thickness t across, height h along the surface normal):
//!
//! ```text
//! A = t·h     W_y = t·h²/6 (strong)     W_z = h·t²/6 (weak)
//! J = h·t³/3·(1 − 0.630·t/h + 0.052·(t/h)⁵)        (Roark, thin rectangle)
//! τ_max = T·t/J                                       (mid long side)
//! ```
//!
//! **Cross-section** (EN 1993-1-1 §6.2.1(5) for steel; the same elastic
//! criterion for timber with f_d = k_mod·f_k/γ_M, EN 1995-1-1 §6 — one
//! strength, the profile's bending strength, for every stress kind):
//!
//! ```text
//! σ = |N|/A + |M_y|/W_y + |M_z|/W_z + σ_w       σ_w = E·tg²·h²/12 (trapeze)
//! σ_v = √(σ² + 3·τ²) ≤ f_d
//! ```
//!
//! the fibres of largest σ and of largest τ taken at one point, as the
//! elastic check does (conservative). The erection moments E·I_z·kg and
//! torque G·J·tg give exactly that check's σb = E·|kg|·t/2 and
//! τ = G·|tg|·t.
//!
//! **Member** between restraints (the crossing nodes), buckling length L:
//!
//! * steel, EN 1993-1-1 §6.3: flexural buckling about the weak axis,
//!   N_cr = π²·E·I_z/L², curve c (α = 0.49, solid sections, Table 6.2);
//!   lateral–torsional buckling of the upright strip,
//!   M_cr = (π/L)·√(E·I_z·G·J) (C1 = 1, uniform moment, no warping: a thin
//!   rectangle's is negligible), curve d (α_LT = 0.76, Table 6.4 "other
//!   sections"), χ from §6.3.1.2 and §6.3.2.2 (general case); interaction
//!   §6.3.3 (6.61) with the k factors taken as 1:
//!   N/(χ_z·N_Rk) + M_y/(χ_LT·M_y,Rk) + M_z/M_z,Rk ≤ 1/γ_M1 (as utilisation);
//! * timber, EN 1995-1-1 §6.3.2 (columns, β_c = 0.2 solid timber) and
//!   §6.3.3 (beams, k_crit of (6.34)), with the profile's mean E and G for
//!   the 5 % values (stated: a profile gives one modulus) and f_k for
//!   f_c,0,k and f_m,k; interaction (6.35):
//!   (σ_m/(k_crit·f_m,d))² + σ_c/(k_c·f_c,0,d) ≤ 1 with the weak-axis
//!   bending added to the linear term.

use std::f64::consts::PI;

/// A rectangular strip section, upright: thickness across, height along
/// the surface normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rectangle {
    /// Thickness t, mm.
    pub thickness_mm: f64,
    /// Height h, mm.
    pub height_mm: f64,
}

impl Rectangle {
    /// A = t·h, mm².
    pub fn area_mm2(&self) -> f64 {
        self.thickness_mm * self.height_mm
    }
    /// I_y = t·h³/12 (strong axis), mm⁴.
    pub fn i_strong_mm4(&self) -> f64 {
        self.thickness_mm * self.height_mm.powi(3) / 12.0
    }
    /// I_z = h·t³/12 (weak axis), mm⁴.
    pub fn i_weak_mm4(&self) -> f64 {
        self.height_mm * self.thickness_mm.powi(3) / 12.0
    }
    /// W_y = t·h²/6, mm³.
    pub fn w_strong_mm3(&self) -> f64 {
        self.thickness_mm * self.height_mm.powi(2) / 6.0
    }
    /// W_z = h·t²/6, mm³.
    pub fn w_weak_mm3(&self) -> f64 {
        self.height_mm * self.thickness_mm.powi(2) / 6.0
    }
    /// St. Venant constant of a rectangle, J = b·c³/3·(1 − 0.630·c/b +
    /// 0.052·(c/b)⁵) with c the shorter side (Roark, Table 10.7), mm⁴.
    pub fn torsion_j_mm4(&self) -> f64 {
        let (b, c) = if self.height_mm >= self.thickness_mm {
            (self.height_mm, self.thickness_mm)
        } else {
            (self.thickness_mm, self.height_mm)
        };
        let r = c / b;
        b * c.powi(3) / 3.0 * (1.0 - 0.630 * r + 0.052 * r.powi(5))
    }
    /// The largest shear stress of a torque T: τ = T·c/J (c the shorter
    /// side), MPa per N·mm.
    pub fn torsion_shear_per_nmm(&self) -> f64 {
        self.thickness_mm.min(self.height_mm) / self.torsion_j_mm4()
    }
}

/// Section forces at one point (load plus erection), local axes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Forces {
    /// Axial force, N (tension positive).
    pub axial_n: f64,
    /// Torque, N·mm.
    pub torque_nmm: f64,
    /// Moment about the strong axis, N·mm.
    pub moment_y_nmm: f64,
    /// Moment about the weak axis, N·mm.
    pub moment_z_nmm: f64,
}

/// The stresses of [`Forces`] on a [`Rectangle`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionStress {
    /// σ = |N|/A + |M_y|/W_y + |M_z|/W_z + σ_w, MPa.
    pub normal_mpa: f64,
    /// τ = |T|·t/J, MPa.
    pub shear_mpa: f64,
    /// σ_v = √(σ² + 3τ²), MPa.
    pub von_mises_mpa: f64,
}

/// The section's stresses: `trapeze_mpa` is σ_w = E·tg²·h²/12 of the
/// erection twist (an axial stress no section force carries).
pub fn section_stress(section: &Rectangle, forces: &Forces, trapeze_mpa: f64) -> SectionStress {
    let normal_mpa = forces.axial_n.abs() / section.area_mm2()
        + forces.moment_y_nmm.abs() / section.w_strong_mm3()
        + forces.moment_z_nmm.abs() / section.w_weak_mm3()
        + trapeze_mpa.abs();
    let shear_mpa = forces.torque_nmm.abs() * section.torsion_shear_per_nmm();
    SectionStress {
        normal_mpa,
        shear_mpa,
        von_mises_mpa: (normal_mpa * normal_mpa + 3.0 * shear_mpa * shear_mpa).sqrt(),
    }
}

/// How the material is checked for member buckling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Code {
    /// EN 1993-1-1: yield strength f_y (MPa) and γ_M1.
    Steel {
        /// f_y, MPa.
        yield_mpa: f64,
        /// γ_M1.
        gamma_m1: f64,
    },
    /// EN 1995-1-1: characteristic strength f_k (MPa), k_mod and γ_M.
    Timber {
        /// f_k, MPa (used for f_m,k and f_c,0,k).
        strength_mpa: f64,
        /// k_mod.
        k_mod: f64,
        /// γ_M.
        gamma_m: f64,
    },
}

/// A member check between two restraints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MemberCheck {
    /// Reduction for flexural buckling about the weak axis (χ_z or k_c).
    pub chi_flexural: f64,
    /// Reduction for lateral–torsional buckling (χ_LT or k_crit).
    pub chi_lateral_torsional: f64,
    /// The interaction's utilisation (≤ 1 passes).
    pub utilisation: f64,
}

/// EN 1993-1-1 (6.49)/(6.56): χ = 1/(φ + √(φ² − λ̄²)) ≤ 1,
/// φ = ½·(1 + α·(λ̄ − 0.2) + λ̄²).
pub fn chi_en1993(alpha: f64, slenderness: f64) -> f64 {
    let phi = 0.5 * (1.0 + alpha * (slenderness - 0.2) + slenderness * slenderness);
    (1.0 / (phi + (phi * phi - slenderness * slenderness).max(0.0).sqrt())).min(1.0)
}

/// The member check of an upright strip between restraints `span_mm`
/// apart, with the largest |forces| along it (compression only counts
/// for flexural buckling).
pub fn member_check(
    section: &Rectangle,
    youngs_mpa: f64,
    shear_mpa: f64,
    span_mm: f64,
    forces: &Forces,
    code: Code,
) -> MemberCheck {
    let (a, iz) = (section.area_mm2(), section.i_weak_mm4());
    let (wy, wz) = (section.w_strong_mm3(), section.w_weak_mm3());
    let n_cr = PI * PI * youngs_mpa * iz / (span_mm * span_mm);
    let m_cr = PI / span_mm * (youngs_mpa * iz * shear_mpa * section.torsion_j_mm4()).sqrt();
    let compression_n = (-forces.axial_n).max(0.0);
    let (my, mz) = (forces.moment_y_nmm.abs(), forces.moment_z_nmm.abs());
    match code {
        Code::Steel {
            yield_mpa,
            gamma_m1,
        } => {
            let chi_z = chi_en1993(0.49, (a * yield_mpa / n_cr).sqrt());
            let chi_lt = chi_en1993(0.76, (wy * yield_mpa / m_cr).sqrt());
            let utilisation = gamma_m1
                * (compression_n / (chi_z * a * yield_mpa)
                    + my / (chi_lt * wy * yield_mpa)
                    + mz / (wz * yield_mpa));
            MemberCheck {
                chi_flexural: chi_z,
                chi_lateral_torsional: chi_lt,
                utilisation,
            }
        }
        Code::Timber {
            strength_mpa,
            k_mod,
            gamma_m,
        } => {
            let f_d = k_mod * strength_mpa / gamma_m;
            // EN 1995-1-1 (6.21)–(6.27): λ_rel = (λ/π)·√(f_c,0,k/E_0.05).
            let radius_mm = (iz / a).sqrt();
            let lambda_rel = span_mm / radius_mm / PI * (strength_mpa / youngs_mpa).sqrt();
            let k = 0.5 * (1.0 + 0.2 * (lambda_rel - 0.3) + lambda_rel * lambda_rel);
            let k_c = if lambda_rel <= 0.3 {
                1.0
            } else {
                (1.0 / (k + (k * k - lambda_rel * lambda_rel).max(0.0).sqrt())).min(1.0)
            };
            // (6.30)–(6.34): σ_m,crit = M_cr/W_y, k_crit.
            let lambda_m = (strength_mpa / (m_cr / wy)).sqrt();
            let k_crit = if lambda_m <= 0.75 {
                1.0
            } else if lambda_m <= 1.4 {
                1.56 - 0.75 * lambda_m
            } else {
                1.0 / (lambda_m * lambda_m)
            };
            let sigma_my = my / wy;
            let utilisation = (sigma_my / (k_crit * f_d)).powi(2)
                + compression_n / a / (k_c * f_d)
                + mz / wz / f_d;
            MemberCheck {
                chi_flexural: k_c,
                chi_lateral_torsional: k_crit,
                utilisation,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STRIP: Rectangle = Rectangle {
        thickness_mm: 1.5,
        height_mm: 88.0,
    };

    #[test]
    fn erection_moments_give_the_elastic_checks_stresses() {
        // By hand: E = 210000 MPa, kg = 1/5000 mm⁻¹: σb = E·kg·t/2 = 31.5 MPa;
        // G = 81000 MPa, tg = 1e-4 rad/mm: τ = G·tg·t = 12.15 MPa (J = h·t³/3
        // of a thin strip would give it exactly; Roark's J keeps τ = T·t/J).
        let (e, g) = (210_000.0, 81_000.0);
        let forces = Forces {
            moment_z_nmm: e * STRIP.i_weak_mm4() / 5000.0,
            torque_nmm: g * STRIP.torsion_j_mm4() * 1e-4,
            ..Forces::default()
        };
        let s = section_stress(&STRIP, &forces, 0.0);
        assert!((s.normal_mpa - 31.5).abs() < 1e-9, "{s:?}");
        assert!((s.shear_mpa - 12.15).abs() < 1e-9, "{s:?}");
        let vm = (31.5f64 * 31.5 + 3.0 * 12.15 * 12.15).sqrt();
        assert!((s.von_mises_mpa - vm).abs() < 1e-9);
    }

    #[test]
    fn torsion_constant_of_a_thin_and_a_square_section() {
        // Thin: b·c³/3·(1 − 0.63·c/b) = 88·1.5³/3·(1 − 0.01074) = 97.94.
        let j = STRIP.torsion_j_mm4();
        assert!((j - 97.9369).abs() < 1e-3, "{j}");
        // Square: the exact series gives 0.1406·a⁴; Roark's fit 0.1407·a⁴.
        let sq = Rectangle {
            thickness_mm: 10.0,
            height_mm: 10.0,
        };
        assert!((sq.torsion_j_mm4() / 1e4 - 0.1406).abs() < 2e-4);
    }

    #[test]
    fn chi_matches_en1993_table_values() {
        // The reduction factors tabulated for EN 1993-1-1 Figure 6.4 at
        // λ̄ = 1.0: curve b 0.5970, curve c 0.5399, curve d 0.4671; λ̄ ≤ 0.2: 1.
        assert!((chi_en1993(0.34, 1.0) - 0.5970).abs() < 1e-4);
        assert!((chi_en1993(0.49, 1.0) - 0.5399).abs() < 1e-4);
        assert!((chi_en1993(0.76, 1.0) - 0.4671).abs() < 1e-4);
        assert_eq!(chi_en1993(0.49, 0.1), 1.0);
    }

    #[test]
    fn a_short_stocky_member_is_its_cross_section() {
        // 50 mm of a 20 × 20 bar: λ̄ = √(A·f_y/N_cr) = √(400·355/(π²·210000·
        // 13333/2500)) = 0.113 ≤ 0.2, no buckling reduction; utilisation =
        // N/(A·f_y)·γ_M1.
        let bar = Rectangle {
            thickness_mm: 20.0,
            height_mm: 20.0,
        };
        let forces = Forces {
            axial_n: -40_000.0,
            ..Forces::default()
        };
        let m = member_check(
            &bar,
            210_000.0,
            81_000.0,
            50.0,
            &forces,
            Code::Steel {
                yield_mpa: 355.0,
                gamma_m1: 1.0,
            },
        );
        assert_eq!(m.chi_flexural, 1.0);
        assert!((m.utilisation - 40_000.0 / (400.0 * 355.0)).abs() < 1e-12);
    }

    #[test]
    fn a_slender_strip_buckles_sideways_at_euler_and_lateral_torsional_loads() {
        // 1.5 × 88 strip, 300 mm: N_cr = π²·E·I_z/L² = π²·210000·24.75/90000
        // = 569.9 N; λ̄ = √(A·f_y/N_cr) = √(132·355/569.9) = 9.07, so
        // χ ≈ 1/λ̄² roughly: the utilisation of 100 N is about 100/(χ·A·f_y).
        let forces = Forces {
            axial_n: -100.0,
            ..Forces::default()
        };
        let m = member_check(
            &STRIP,
            210_000.0,
            81_000.0,
            300.0,
            &forces,
            Code::Steel {
                yield_mpa: 355.0,
                gamma_m1: 1.0,
            },
        );
        let n_cr = PI * PI * 210_000.0 * (88.0 * 1.5f64.powi(3) / 12.0) / 90_000.0;
        assert!((n_cr - 569.9).abs() < 0.1);
        // Curve c at λ̄ = 9.067 (by hand: φ = 0.5·(1 + 0.49·8.867 + 82.21)
        // = 43.78; χ = 1/(43.78 + √(43.78² − 82.21)) = 0.011546).
        assert!((m.chi_flexural - 0.011546).abs() < 2e-6, "{m:?}");
        assert!(m.utilisation > 100.0 / n_cr, "never above the Euler load");
    }
}
